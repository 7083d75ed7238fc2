#pragma once
// Listener interface. Events are delivered after World::step returns its physics work, on the
// caller's thread; a listener may create and destroy bodies (and joints) from inside a callback.
// Per step: the contact and trigger events first, then the joints that broke.
#include "anyphys/listeners/events.hpp"

namespace anyphys {

class ContactListener {
public:
    virtual ~ContactListener() = default;
    virtual void onCollisionEnter(const ContactEvent&) {}
    virtual void onCollisionStay(const ContactEvent&) {}
    virtual void onCollisionExit(const ContactEvent&) {}
    virtual void onTriggerEnter(const ContactEvent&) {}
    virtual void onTriggerExit(const ContactEvent&) {}
    /// A joint broke in the last step (JointDef::breakForce / breakTorque exceeded).
    virtual void onJointBreak(const JointEvent&) {}
};

/// A listener that takes every contact and trigger event in one function, for code that treats
/// them alike (recorders, counters, checks): the event's `phase` and `trigger` say which it is.
/// Joint breaks still arrive in onJointBreak.
class ContactEventListener : public ContactListener {
public:
    virtual void onContactEvent(const ContactEvent& event) = 0;

    void onCollisionEnter(const ContactEvent& e) final { onContactEvent(e); }
    void onCollisionStay(const ContactEvent& e) final { onContactEvent(e); }
    void onCollisionExit(const ContactEvent& e) final { onContactEvent(e); }
    void onTriggerEnter(const ContactEvent& e) final { onContactEvent(e); }
    void onTriggerExit(const ContactEvent& e) final { onContactEvent(e); }
};

}  // namespace anyphys

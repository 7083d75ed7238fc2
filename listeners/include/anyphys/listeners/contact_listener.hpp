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

}  // namespace anyphys

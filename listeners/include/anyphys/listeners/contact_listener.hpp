#pragma once
// Listener interface. Events are delivered after World::step returns its physics work, on the
// caller's thread; a listener may create and destroy bodies from inside a callback.
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
};

}  // namespace anyphys

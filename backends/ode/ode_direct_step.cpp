#include "ode_direct_step.hpp"

#include <algorithm>

#include "ode_body.hpp"
#include "ode_init.hpp"

namespace anyphys::ode {
namespace {

void copy3(const dReal* from, dReal* to) { std::copy(from, from + 3, to); }

}  // namespace

bool DirectStepper::step(dWorldID world, const std::vector<OdeBody*>& bodies, dReal h) {
    // dWorldStep consumes the force accumulators and may disable bodies (auto-disable): both are
    // kept with the pose and velocities.
    saved_.clear();
    for (const OdeBody* b : bodies) {
        const dBodyID id = b->id();
        if (!id) continue;
        Saved& s = saved_.emplace_back();
        s.id = id;
        copy3(dBodyGetPosition(id), s.position);
        std::copy(dBodyGetQuaternion(id), dBodyGetQuaternion(id) + 4, s.quaternion);
        copy3(dBodyGetLinearVel(id), s.linear);
        copy3(dBodyGetAngularVel(id), s.angular);
        copy3(dBodyGetForce(id), s.force);
        copy3(dBodyGetTorque(id), s.torque);
        s.enabled = dBodyIsEnabled(id) != 0;
    }
    const long failuresBefore = odeLcpFailuresOnThisThread();
    dWorldStep(world, h);
    if (odeLcpFailuresOnThisThread() == failuresBefore) return false;
    for (const Saved& s : saved_) {
        dBodySetPosition(s.id, s.position[0], s.position[1], s.position[2]);
        dBodySetQuaternion(s.id, s.quaternion);
        dBodySetLinearVel(s.id, s.linear[0], s.linear[1], s.linear[2]);
        dBodySetAngularVel(s.id, s.angular[0], s.angular[1], s.angular[2]);
        dBodySetForce(s.id, s.force[0], s.force[1], s.force[2]);
        dBodySetTorque(s.id, s.torque[0], s.torque[1], s.torque[2]);
        s.enabled ? dBodyEnable(s.id) : dBodyDisable(s.id);
    }
    dWorldQuickStep(world, h);
    return true;
}

}  // namespace anyphys::ode

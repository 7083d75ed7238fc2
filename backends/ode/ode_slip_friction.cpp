#include "ode_slip_friction.hpp"

#include "ode_tuning.hpp"

namespace anyphys::ode {

void alignFrictionWithSlip(dContact& contact, const Vec3& relativeVelocity) {
    const Vec3 normal(contact.geom.normal[0], contact.geom.normal[1], contact.geom.normal[2]);
    const Vec3 slip = relativeVelocity - normal.dot(relativeVelocity) * normal;
    const double speed = slip.norm();
    if (!(speed > kSlipDirectionSpeed)) return;  // no slip to align with: ODE's directions serve
    const Vec3 direction = slip / speed;
    contact.fdir1[0] = direction.x();
    contact.fdir1[1] = direction.y();
    contact.fdir1[2] = direction.z();
    contact.surface.mode |= dContactFDir1;
}

}  // namespace anyphys::ode

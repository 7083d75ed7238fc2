#include "anyphys/fields/field_forces.hpp"

namespace anyphys {

FieldForce buoyancyForce(const FieldDef& field, const FieldBody& body, const FieldState& state, const Vec3& gravity) {
    const FluidPlane fluid{field.surfaceNormal, field.surfaceOffset};
    const SubmergedVolume wet = submergedShapes(body.shapes, state.pose, fluid);
    if (wet.volume <= 0.0) return {};
    FieldForce out;
    // Archimedes: the weight of the displaced fluid, upwards, at the centre of buoyancy.
    out.force = -field.fluidDensity * wet.volume * gravity;
    out.torque = (wet.centroid - state.pose.position).cross(out.force);
    // The fluid's drag, as rates scaled by the wet fraction: dv/dt = -c f v, dw/dt = -c f w.
    const double f = body.volume > 0.0 ? std::min(1.0, wet.volume / body.volume) : 0.0;
    if (field.linearDrag > 0.0) out.force -= body.mass * field.linearDrag * f * state.linearVelocity;
    if (field.angularDrag > 0.0) {
        const Quat& q = state.pose.orientation;  // principal axes: I_world w = R I R^T w
        const Vec3 local = q.conjugate() * state.angularVelocity;
        out.torque -= field.angularDrag * f * (q * body.inertia.cwiseProduct(local));
    }
    return out;
}

}  // namespace anyphys

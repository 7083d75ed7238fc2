#include "anyphys/fields/field_forces.hpp"

namespace anyphys {

// Wind is drag in air that moves: the force depends on the velocity relative to the air, so a
// free body is pushed up to the wind's speed and no further.
FieldForce windForce(const FieldDef& field, const FieldBody& body, const FieldState& state) {
    return quadraticDrag(body, state.pose.orientation, state.linearVelocity - field.velocity, field.airDensity);
}

}  // namespace anyphys

#pragma once
// The rows of JointDef and of its limits, motor and spring objects, in the order scene files write
// them (see schema.hpp), defined in api/src/schema/joint_fields.cpp. A JointDef row's `types` are
// the joint types that use it (bit(JointType)); its capability path "joint.*.limits" stands for
// one parameter per such type ("joint.hinge.limits", ...), as backends declare them.
#include <cstdint>
#include <vector>

#include "anyphys/joint_def.hpp"
#include "anyphys/schema.hpp"

namespace anyphys::schema {

const std::vector<Field<JointDef>>& jointDefFields();
const std::vector<Field<JointLimits>>& jointLimitsFields();
const std::vector<Field<JointMotor>>& jointMotorFields();
const std::vector<Field<JointSpring>>& jointSpringFields();

/// Bit of a joint type in Field::types of a JointDef row.
constexpr std::uint32_t bit(JointType t) { return 1u << static_cast<unsigned>(t); }

}  // namespace anyphys::schema

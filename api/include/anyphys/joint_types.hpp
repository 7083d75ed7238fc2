#pragma once
// Joint value types shared by the layer and the backends: limits, motors and springs (the joint
// kinds, JointType, are in enums.hpp; JointDef, with its body handles, in joint_def.hpp).
#include "anyphys/enums.hpp"

namespace anyphys {

/// A range of motion: rad for angular joints, m for linear ones; lower <= upper, 0 in range.
struct JointLimits {
    double lower = 0.0;
    double upper = 0.0;
};

/// Drives the joint toward a relative speed with bounded effort.
struct JointMotor {
    double speed = 0.0;     ///< rad/s (hinge, wheel spin) or m/s (slider), target relative speed of B
    double maxForce = 0.0;  ///< N m (angular) or N (linear), >= 0: the most the motor may apply
};

/// A spring toward the joint's rest position (0 for hinge, slider and wheel; the rest length for
/// distance). Give either stiffness and damping, or hertz and dampingRatio (the layer turns those
/// into stiffness and damping with the joint's effective mass or inertia about its axis).
struct JointSpring {
    double stiffness = 0.0;     ///< N/m or N m/rad, >= 0
    double damping = 0.0;       ///< N s/m or N m s/rad, >= 0
    double hertz = 0.0;         ///< Hz, >= 0; used when > 0 (then stiffness and damping must be 0)
    double dampingRatio = 0.0;  ///< >= 0, with hertz
};

/// A spring as a backend receives it: stiffness and damping in SI units, hertz already resolved.
struct JointSpringSI {
    double stiffness = 0.0;  ///< N/m or N m/rad
    double damping = 0.0;    ///< N s/m or N m s/rad
};

}  // namespace anyphys

#pragma once
// Math value types used across every layer: SI units, right-handed, Y up, double precision.
#include <Eigen/Geometry>

namespace anyphys {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Mat3 = Eigen::Matrix3d;

/// A rigid placement: position (m) and unit orientation.
struct Transform {
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
};

}  // namespace anyphys

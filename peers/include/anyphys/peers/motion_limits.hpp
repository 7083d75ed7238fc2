#pragma once
// The ceilings a body's state must stay under after every step (WorldSettings::maxSpeed,
// maxAngularSpeed, anyphys::kMaxCoordinate). The layer and every backend test states with this one
// function, so a backend's own scan of its bodies (WorldPeer::findUnsound) and the layer's check
// of a single body always agree.
#include <cmath>

#include "anyphys/defs.hpp"

namespace anyphys {

struct MotionLimits {
    double maxSpeed2 = 0.0;         ///< m^2/s^2, WorldSettings::maxSpeed squared
    double maxAngularSpeed2 = 0.0;  ///< rad^2/s^2, WorldSettings::maxAngularSpeed squared
    double maxCoordinate = 0.0;     ///< m, on each coordinate of the position

    /// Whether a state is finite and under every ceiling. `orientationSum` is the sum of the
    /// orientation's coefficients (a quaternion's, a rotation matrix's or an angle): finite exactly
    /// when they all are. Every comparison is written so that a NaN fails it.
    bool admit(const Vec3& position, double orientationSum, const Vec3& linearVelocity, const Vec3& angularVelocity) const {
        return linearVelocity.squaredNorm() <= maxSpeed2 && angularVelocity.squaredNorm() <= maxAngularSpeed2 &&
               std::abs(position.x()) <= maxCoordinate && std::abs(position.y()) <= maxCoordinate &&
               std::abs(position.z()) <= maxCoordinate && std::isfinite(orientationSum);
    }

    bool admit(const BodyState& s) const {
        const Quat& q = s.orientation;
        return admit(s.position, q.w() + q.x() + q.y() + q.z(), s.linearVelocity, s.angularVelocity);
    }
};

}  // namespace anyphys

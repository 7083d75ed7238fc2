#pragma once
// Time integrators for rigid-body states. Each integrator advances positions, orientations and
// velocities of all moving bodies together, so a force that couples bodies (a user spring between
// two of them) sees consistent intermediate states.
#include <span>
#include <vector>

#include "anyphys/defs.hpp"
#include "function_ref.hpp"

namespace anyphys::native {

struct Acceleration {
    Vec3 linear = Vec3::Zero();   // m/s^2, world frame
    Vec3 angular = Vec3::Zero();  // rad/s^2, world frame
};

/// Fills `out[i]` with the accelerations of body i in `states` at time t.
using AccelerationFn = FunctionRef<void(double t, std::span<const BodyState> states, std::span<Acceleration> out)>;

/// Reusable buffers, so a step allocates nothing once sizes are stable.
struct IntegratorScratch {
    std::vector<BodyState> stage;
    std::vector<Acceleration> k1, k2, k3, k4;
    std::vector<BodyState> d1, d2, d3, d4;  // state derivatives for Runge-Kutta
};

/// Advances `states` from t to t + h with the given method.
void integrate(Integrator method, double t, double h, std::span<BodyState> states, AccelerationFn accelerations,
               IntegratorScratch& scratch);

/// dq/dt = 1/2 (0, w) q for a world-frame angular velocity, as quaternion coefficients.
Quat orientationRate(const Vec3& w, const Quat& q);
/// Exact rotation by a constant world angular velocity w over h: exp(h w / 2) q.
Quat rotateBy(const Quat& q, const Vec3& w, double h);

}  // namespace anyphys::native

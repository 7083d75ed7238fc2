#pragma once
// The restitution target of a contact point, shared by the 3D and the planar contact paths.
#include <algorithm>
#include <cmath>

namespace anyphys::native {

/// The normal velocity after a bounce of restitution e, from the stored approach velocity `vn`.
/// Restitution acts at the instant of impact, `impact` seconds into the step: under a constant
/// relative acceleration `an` along the normal the true velocity then is vn - an * offset +
/// an * impact; it reverses to -e times that, and is stored back with the integrator's offset.
/// Semi-implicit Euler's velocity lags its position by half a step (offset -h/2), explicit
/// Euler's leads (+h/2); exact flights have offset 0.
inline double bounceVelocity(double e, double vn, double an, double offset, double impact) {
    return -e * (vn - an * offset + an * impact) + an * offset;
}

/// Seconds into the step at which a point `separation` apart meets, closing at `closing` (> 0)
/// and accelerating together at `accel`: the root of s = c t + a t^2 / 2, in the form that
/// stays accurate as a goes to 0; within [0, h]. Overlapping points meet at once.
inline double timeToImpact(double separation, double closing, double accel, double h) {
    if (separation <= 0.0) return 0.0;
    const double root = std::sqrt(std::max(closing * closing + 2.0 * accel * separation, 0.0));
    const double denominator = closing + root;
    return denominator > 0.0 ? std::min(2.0 * separation / denominator, h) : h;
}

}  // namespace anyphys::native

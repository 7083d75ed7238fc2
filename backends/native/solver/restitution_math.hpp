#pragma once
// The restitution target of a contact point, shared by the 3D and the planar contact paths.
#include <algorithm>
#include <cmath>

namespace anyphys::native {

/// The normal velocity after a bounce of restitution e, from the stored approach velocity `vn`.
/// Restitution acts at the instant of impact, `impact` seconds into the step: under a constant
/// relative acceleration `an` along the normal the true velocity then is vn - an * offset +
/// an * impact; it reverses to -e times that. It is stored back with the offset of whatever moves
/// the body next. The integrator's (`offset`) for a bounce that flies free: semi-implicit Euler's
/// velocity lags its position by half a step (offset -h/2), explicit Euler's leads (+h/2); exact
/// flights have offset 0. A bounce whose rise under `an` stays within the narrow phase's margin
/// (`margin`, the speculative distance, plus a step `h` at the rebound speed) keeps its contact,
/// and the solver's substeps carry its whole flight (`solverOffset`, half a substep): stored with
/// the integrator's half step, a ball landing at 3.1 m/s with e = 0.2 rose 2.47 cm, not 2.0, at
/// 60 Hz. A higher bounce leaves the contact on the way up and flies free.
inline double bounceVelocity(double e, double vn, double an, double offset, double impact, double solverOffset,
                             double margin, double h) {
    const double rebound = -e * (vn - an * offset + an * impact);
    const bool staysInContact = an < 0.0 && rebound * rebound < -2.0 * an * (margin + rebound * h);
    return rebound + an * (staysInContact ? solverOffset : offset);
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

#pragma once
// The restitution target of a contact point, shared by the 3D and the planar contact paths.
#include <algorithm>
#include <cmath>

namespace anyphys::native {

/// The normal velocity after a bounce of restitution e, from the stored approach velocity `vn`.
/// Restitution acts at the instant of impact, `impact` seconds into the step: under a constant
/// relative acceleration `an` along the normal the true velocity then is vn - an * offset +
/// an * impact; it reverses to -e times that. It is stored back with the lag of whatever moves
/// the body: first the solver's substeps (the contact holds it within the narrow phase's reach,
/// `margin` plus a step `h` at its speed: `solverOffset`, half a substep, semi-implicit), then,
/// once it rises out of reach, the integrator (`offset`: semi-implicit Euler's velocity lags its
/// position by half a step, -h/2, explicit Euler's leads, +h/2, exact flights have 0). Passing from
/// one to the other turns a velocity's lag into the other's, which shifts the flight's height by
/// the speed at the hand-over times the difference of the lags; stored with the integrator's lag in
/// the share of the rebound speed left at the hand-over, the two shifts cancel. With the
/// integrator's lag alone a ball landing at 3.1 m/s with e = 0.2, which never leaves reach, rose
/// 2.47 cm, not 2.0, at 60 Hz; one leaving near its apex rose 20 % high.
inline double bounceVelocity(double e, double vn, double an, double offset, double impact, double solverOffset,
                             double margin, double h) {
    const double rebound = -e * (vn - an * offset + an * impact);
    double leftAtHandOver = 1.0;  // nothing pulls it back: it flies free at once
    if (an < 0.0 && rebound > 0.0) {
        // Rising at u, it is out of reach at height (rebound^2 - u^2) / 2g = margin + u h.
        const double g = -an;
        const double u = -g * h + std::sqrt(std::max(g * g * h * h + rebound * rebound - 2.0 * g * margin, 0.0));
        leftAtHandOver = std::clamp(u / rebound, 0.0, 1.0);
    }
    return rebound + an * (solverOffset + leftAtHandOver * (offset - solverOffset));
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

#pragma once
// Random test inputs drawn in a fixed order. The arguments of one call are evaluated in an order
// the compiler picks (GCC right to left, clang left to right), so `Vec3(u(rng), u(rng), u(rng))`
// is one vector under GCC and another under clang, and a seeded test would check different cases
// with each compiler. These draw one number per statement.
#include "anyphys/math.hpp"

namespace anyphys::test {

/// x, y, z in that order, each from `dist`.
template <class Dist, class Rng>
Vec3 drawVec3(Dist& dist, Rng& rng) {
    const double x = dist(rng);
    const double y = dist(rng);
    const double z = dist(rng);
    return {x, y, z};
}

/// w, x, y, z in that order, each from `dist`, normalised: with a normal distribution, a rotation
/// drawn uniformly.
template <class Dist, class Rng>
Quat drawUnitQuat(Dist& dist, Rng& rng) {
    const double w = dist(rng);
    const double x = dist(rng);
    const double y = dist(rng);
    const double z = dist(rng);
    return Quat(w, x, y, z).normalized();
}

/// A turn of `angleScale * dist(rng)` about an axis drawn after it with drawVec3.
template <class Dist, class Rng>
Quat drawTurn(Dist& dist, Rng& rng, double angleScale) {
    const double angle = angleScale * dist(rng);
    const Vec3 axis = drawVec3(dist, rng).normalized();
    return Quat(Eigen::AngleAxisd(angle, axis));
}

}  // namespace anyphys::test

#pragma once
// How a pass sweeps a manifold again, shared by the 3D and planar solve kernels.
//
// A pass solves a manifold's normal rows point by point and its friction once, at the manifold's
// centre. Where the pass moves the impulses by much (an impact: a face landing flat, a paddle
// meeting a box), one sweep is far from the answer:
//  - the points solved first take more than their share, the pair turns, and the points solved
//    last push against the turn: a box pushed by a kinematic paddle at 1 m/s left at 1.046 m/s
//    spinning at 0.18 rad/s, and a box landing flat spun at 0.1 rad/s;
//  - friction, solved before the normal rows turned the body back, stops only the slip at the
//    contact and leaves the body's own: a 10 cm box landing flat at 60 m/s down and 18 across
//    with mu 0.5 slid on 11 m, where a landing that stops its slip ends 1.6 m from the start.
// So a lane whose first sweep moved some point's velocity by more than kSweepAgainSpeed is swept
// again, on the two bodies the pass already holds: its normal rows (with more than one point)
// kMaxNormalSweeps times in all, then friction, against the normal impulses as they stand, and the
// normal rows in turn, kMaxFrictionSweeps - 1 times. The paddle's box leaves at 1.000 m/s without
// spin, the fast box ends 1.57 m out, as on ODE, Bullet and Box2D. Lanes that moved less, a
// resting pile's, pay for the test only. Four normal sweeps: two left a planar landing spinning at
// 0.011 rad/s, three the paddle's box at 1.0015 m/s. Friction after the normal rows have evened
// out: alternating from the first sweep, it met the slip of a flat landing's passing tilt and a
// box dropped flat ended 3.5 mm aside (now 3 um). Seven alternations: three left the fast box
// landing at 40 m/s 12 % long.
//
// Where a joint holds either body the extra sweeps stay out in part, as they let the contacts
// outrun the joints: friction is never swept again (it opened the soak run's pinched ragdoll pile
// to a median gap of 62 mm, 37 before), and in planar worlds neither are the normal rows (they
// opened the planar ragdoll pile's joints: the largest gap, median of 30 nudged starts, 0.031 to
// 0.062 m). The 3D pile's did not open with the normal sweeps (0.034 to 0.037 m).
#include "solver/rigid_bias.hpp"
#include "solver/wide.hpp"

namespace anyphys::native::wide {

inline constexpr int kMaxNormalSweeps = 4;
inline constexpr int kMaxFrictionSweeps = 8;
/// m/s: the normal velocity one sweep's impulse gives a point, beyond which its manifold's lane is
/// swept again. Gravity brings a resting contact 0.02 m/s a substep at 8 substeps of 1/60 s, and
/// the warm start applies most of it before the pass.
inline constexpr double kSweepAgainSpeed = 0.05;

/// What a pass's normal rows are made of beside the manifold, so a later sweep can find each
/// point's row again (positions do not move within a pass): the pass's constants and, where the
/// rows are rigid and friction predicted their load, each point's bias as friction found it.
struct PassRows {
    RigidBias rigid;
    FloatW invH, maxPush, biasRate, massScale, impulseScale;
    bool predictLoad, soft;  // soft: the solve pass's soft rows
    const FloatW* rowBias;
};

/// Whether a point's impulse change `applied` moved its velocity by more than kSweepAgainSpeed
/// (applied / normalMass, compared without dividing).
[[gnu::always_inline]] inline MaskW movedMuch(FloatW applied, FloatW normalMass) {
    return max(applied, -applied) > splat(kSweepAgainSpeed) * normalMass;
}

/// The lanes whose flag is set.
[[gnu::always_inline]] inline MaskW laneMask(const bool (&flags)[kLanes]) {
    MaskW m;
    for (int k = 0; k < kLanes; ++k) m[k] = flags[k] ? -1 : 0;
    return m;
}

}  // namespace anyphys::native::wide

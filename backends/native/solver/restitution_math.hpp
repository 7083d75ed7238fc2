#pragma once
// The restitution target of a contact point, shared by the 3D and the planar contact paths.
#include <algorithm>
#include <cmath>

namespace anyphys::native {

/// Gauss-Seidel passes over a manifold's points and its friction in the restitution stage. One
/// pass bounces the first point of a flat face fully and the others less, as the first's impulse
/// already lifts them: a 0.6 m box landing flat at 2.5 to 4 m/s with e = 0.5 rose 50 to 78 % of
/// e^2 h in a plane (2 points), 91 to 105 % in 3D (4). Repeated, the points even out (100 to
/// 101 %), and friction in each pass stops the slide the impact's uneven solve left at the face:
/// with friction once at the end that slide came back as spin (0.49 rad/s); 8 passes leave
/// 0.017 rad/s, 16 leave 0.0003. Only manifolds with a bouncing point run them.
inline constexpr int kRestitutionPasses = 16;

/// Rounds of the restitution stage over all colours. A bounce that drives a body into its own
/// resting contacts (a ball on a box on the ground) is held there by those contacts' rows, which
/// may come in a colour after the bounce's; the next round bounces again off the held body, and
/// each round closes m_box / (m_ball + m_box) of the ball's shortfall left. A 1 kg ball bouncing
/// on a 10 kg box (e = 0.5, impacts 2.5 to 4 m/s) rose 59 to 83 % of e^2 h with one round, 100 to
/// 100.7 % with 4; a 10 kg ball on it 71 to 90 % with 4, 98 to 101 % with 8, 100 to 101.6 % with
/// 16; a 30 kg ball 4 to 67 % with 4, 54 to 92 % with 8, 95 to 102 % with 16. Heavier still
/// (65 kg: 51 to 94 %; 96 to 102 % with 64 rounds) is the mass-ratio weakness of every
/// Gauss-Seidel stage, met by shock propagation (restitution_rows.hpp): 65 kg then rises 96 to
/// 102 % in 16 rounds, and a 100 kg ball on a 1 kg box 76 to 100 % (13 to 27 % before).
/// Rounds after the first run only when the first found a bounce (StepSolver::skipRestitutionRound).
inline constexpr int kRestitutionRounds = 16;

/// The share of a rebound's speed `rebound`, pulled back at g, left when the pair rises out of the
/// narrow phase's reach: `margin` plus a step h at the pair's speed, its rise u and its `slide`
/// along the surface (ContactManager keeps points within margin + |relative velocity| h). Out of
/// reach at height (rebound^2 - u^2) / 2g = margin + h sqrt(u^2 + slide^2): without a slide in
/// closed form, with one by Newton's method from that root (the left side is concave and falling,
/// so the steps approach the root from above). 0 when it never leaves reach. Counting only the
/// rise, a ball sliding at 6 m/s as it bounced stayed in reach all through its flight and rose up
/// to 10 % high (e = 0.5).
inline double shareLeftOutOfReach(double rebound, double g, double margin, double h, double slide) {
    const double reachAtRest = (rebound * rebound) / (2.0 * g) - margin - h * slide;
    if (reachAtRest <= 0.0) return 0.0;
    double u = -g * h + std::sqrt(std::max(g * g * h * h + rebound * rebound - 2.0 * g * margin, 0.0));
    if (slide > 0.0)
        for (int i = 0; i < 6; ++i) {
            const double speed = std::sqrt(u * u + slide * slide);
            const double f = (rebound * rebound - u * u) / (2.0 * g) - margin - h * speed;
            const double slope = -u / g - h * u / speed;
            if (!(slope < 0.0)) break;
            u -= f / slope;
        }
    return std::clamp(u / rebound, 0.0, 1.0);
}

/// What a bounce's rebound speed depends on besides the restitution: the approach, where the
/// velocities sit in time, and how the step leaves the pair (bounceVelocity).
struct BounceApproach {
    double vn = 0.0;            // m/s: the stored normal velocity at the step's start (< 0: approaching)
    double an = 0.0;            // m/s^2: the pair's relative normal acceleration
    double impact = 0.0;        // s: when in the step the surfaces meet (timeToImpact)
    double offset = 0.0;        // s: the integrator's velocity lag (semi-implicit Euler -h/2, explicit +h/2)
    double solverOffset = 0.0;  // s: the substeps' velocity lag (half a substep, semi-implicit)
    double margin = 0.0;        // m: the narrow phase's reach beyond a step at the pair's speed
    double h = 0.0;             // s: the step
    double gap = 0.0;           // m: the gap the substeps leave at the step's end (substepGapAtStepEnd)
    double lateGap = 0.0;       // m: the same in continuous time (gapAtStepEnd)
    double slide = 0.0;         // m/s: the pair's speed along the surface
};

/// The normal velocity after a bounce of restitution e, from the stored approach velocity `vn`.
/// Restitution acts at the instant of impact, `impact` seconds into the step: under a constant
/// relative acceleration `an` along the normal the true velocity then is vn - an * offset +
/// an * impact; it reverses to -e times that. It is stored back with the lag of whatever moves
/// the body: first the solver's substeps (the contact holds it within the narrow phase's reach,
/// `margin` plus a step `h` at its speed: `solverOffset`, half a substep, semi-implicit), then,
/// once it rises out of reach (shareLeftOutOfReach), the integrator (`offset`: semi-implicit Euler's velocity lags its
/// position by half a step, -h/2, explicit Euler's leads, +h/2, exact flights have 0). Passing from
/// one to the other turns a velocity's lag into the other's, which shifts the flight's height by
/// the speed at the hand-over times the difference of the lags; stored with the integrator's lag in
/// the share of the rebound speed left at the hand-over, the two shifts cancel. With the
/// integrator's lag alone a ball landing at 3.1 m/s with e = 0.2, which never leaves reach, rose
/// 2.47 cm, not 2.0, at 60 Hz; one leaving near its apex rose 20 % high.
/// A pair that the solver's substeps leave `gap` apart at the step's end meets only in the next
/// step, yet the last substep's relax pass sees the meeting coming and stops the approach, so the
/// bounce comes now, from the gap. It is given the speed that reaches the apex of a bounce from
/// contact: the pair, still `lateGap` apart at the step's end in continuous time (gapAtStepEnd),
/// would have met faster, by 2 |an| lateGap in the square, and rebounded e times that. Bounced from
/// the gap at the full speed, a ball with e = 0.1 landing at 3.2 m/s rose twice its share (5.4 mm
/// up at the step's end, for a 5.2 mm rise).
inline double bounceVelocity(double e, const BounceApproach& in) {
    const double an = in.an;
    double rebound = -e * (in.vn - an * in.offset + an * in.impact);
    if ((in.gap > 0.0 || in.lateGap > 0.0) && an < 0.0 && rebound > 0.0)
        rebound = std::sqrt(std::max(rebound * rebound + 2.0 * an * (in.gap - e * e * in.lateGap), 0.0));
    double leftAtHandOver = 1.0;  // nothing pulls it back: it flies free at once
    if (an < 0.0 && rebound > 0.0) leftAtHandOver = shareLeftOutOfReach(rebound, -an, in.margin, in.h, in.slide);
    return rebound + an * (in.solverOffset + leftAtHandOver * (in.offset - in.solverOffset));
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

/// The separation a pair `separation` apart, closing at `closing` and accelerating together at
/// `accel`, has left at the end of a step h in which it does not meet, in continuous time; 0 when
/// it meets.
inline double gapAtStepEnd(double separation, double closing, double accel, double h) {
    return std::max(separation - closing * h - 0.5 * accel * h * h, 0.0);
}

/// The same as the solver's substeps of `substep` move the pair (semi-implicit Euler: velocity
/// first), from its step-start normal velocity vn and normal acceleration an.
inline double substepGapAtStepEnd(double separation, double vn, double an, double h, double substep) {
    return std::max(separation + vn * h + 0.5 * an * h * (h + substep), 0.0);
}

}  // namespace anyphys::native

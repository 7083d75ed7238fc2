#pragma once
// Which rows the restitution stage runs in a wide manifold: shared by the 3D and the planar
// kernels (contact_solve.cpp, planar_solve.cpp), which differ only in how they move the bodies.
#include "solver/state_runs.hpp"
#include "solver/wide.hpp"

namespace anyphys::native::wide {

/// Per point, the lanes whose row bounces and the lanes whose row holds.
struct RestitutionRows {
    MaskW bounces[4] = {}, held[4] = {};
    MaskW bounced{}, anyHeld{};  // over the points
    bool none() const { return noLane(bounced) && noLane(anyHeld); }
};

/// Bouncing rows: where the approach was fast and the contact pushed (not speculative points that
/// never closed). Holding rows: the other pushing points of a body that takes part in a bounce
/// (the box a ball bounces on, on its ground, and the bodies under it: heldRowsThatPushed), held
/// rigidly and pushing only: no stage after the relax passes would stop the bounce driving the box
/// into its support (a 1 kg ball bouncing on a 10 kg box rose 59 to 83 % of its share).
/// `threshold` is minus the restitution threshold.
template <class Contact, class Cold>
[[gnu::always_inline]] inline RestitutionRows restitutionRows(const Contact& c, const Cold& cold, const SolverState* states,
                                                              FloatW threshold) {
    RestitutionRows rows;
    if (!allZero(cold.restitution))
        for (int j = 0; j < c.pointCount; ++j) {
            rows.bounces[j] = (cold.relativeVelocity[j] < threshold) & (c.points[j].maxImpulse > zero()) & (cold.restitution > zero());
            rows.bounced |= rows.bounces[j];
        }
    const MaskW holding = inBounce(states, c.bodyA, c.bodyB) & ~rows.bounced;
    for (int j = 0; j < c.pointCount; ++j) {
        rows.held[j] = holding & (c.points[j].maxImpulse > zero());
        rows.anyHeld |= rows.held[j];
    }
    return rows;
}

/// Lanes whose holding rows pushed: the bodies there take part in the bounce too, so their own
/// resting contacts hold in later colours and rounds, down the pile. Marking only the bounced pair,
/// a 1 kg ball bouncing on three stacked 10 kg boxes drove the top two into the third at 0.28 m/s
/// and rose 74 % of e^2 h (e = 0.5, 4 m/s).
template <class Cold>
[[gnu::always_inline]] inline MaskW heldRowsThatPushed(const RestitutionRows& rows, const Cold& cold, int pointCount) {
    MaskW lanes{};
    for (int j = 0; j < pointCount; ++j) lanes |= rows.held[j] & (cold.restitutionImpulse[j] > zero());
    return lanes;
}

/// Point j's restitution row at normal velocity vn: a bouncing row aims at its target, a holding row
/// pushes until the point stops closing; neither pulls. Adds the change to the point's impulses and
/// to what the stage has added (`cold.restitutionImpulse`), and returns it. A holding row may take
/// back what it added in an earlier pass, down to what the substeps left: where the corners of a
/// face could each push only further, the box a 65 kg ball bounced on rose off its ground at
/// 0.13 m/s after the first round (1 mm/s after 32), each round's bounce starting from there.
template <class Point, class Cold>
[[gnu::always_inline]] inline FloatW restitutionRowImpulse(const RestitutionRows& rows, int j, Point& cp, Cold& cold, FloatW vn) {
    FloatW& added = cold.restitutionImpulse[j];
    const FloatW bounced = max(cp.normalImpulse - cp.normalMass * (vn - cold.restitutionTarget[j]), zero());
    const FloatW held = cp.normalImpulse + max(added - cp.normalMass * vn, zero()) - added;
    const FloatW total = select(rows.bounces[j], bounced, select(rows.held[j], held, cp.normalImpulse));
    const FloatW applied = total - cp.normalImpulse;
    cp.normalImpulse = total;
    cp.stepImpulse += applied;
    added += applied;
    cold.impactRow[j] |= rows.bounces[j] | rows.held[j];
    return applied;
}

}  // namespace anyphys::native::wide

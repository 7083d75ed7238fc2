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
/// (the box a ball bounces on, on its ground), held rigidly and pushing only: no stage after the
/// relax passes would stop the bounce driving the box into its support (a 1 kg ball bouncing on
/// a 10 kg box rose 59 to 83 % of its share). `threshold` is minus the restitution threshold.
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

}  // namespace anyphys::native::wide

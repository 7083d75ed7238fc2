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
/// into its support (a 1 kg ball bouncing on a 10 kg box rose 59 to 83 % of its share). Touching
/// points hold too, pushed or not: a row of balls without load, struck exactly at a step's end
/// (so the substeps pushed nothing), let the first ball leave alone at the striker's speed, and
/// a later, slower impact lost 12.5 % of the energy with e = 1 (NativeRestitutionStage).
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
        rows.held[j] = holding & ((c.points[j].maxImpulse > zero()) | cold.touching[j]);
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

/// Shock propagation: a body that a holding row pressed against something immovable (a static
/// or kinematic body, or a body so pressed itself, down a pile) keeps the direction its support
/// pushes it, per solver body (`supports`, zero while nothing holds it; StepSolver resets them each
/// step). A bouncing or holding row that drives such a body into its support then meets it as
/// immovable: the support takes the blow. Without it each round of the stage closed only
/// m_box / (m_ball + m_box) of the heavy body's shortfall: a 100 kg ball bouncing on a 1 kg box
/// resting on the ground rose 13 to 27 % of e^2 h (e = 0.5), and a 65 kg ball on three stacked
/// 10 kg boxes did not rise at all. The holding rows pin too, so that a box stops on the box under
/// it, which its ground has stopped, within the round; pinning only where the ball bounced, the
/// rounds stopped each box only after the one above it and the 65 kg ball still did not rise.
/// A push more than about 45 degrees off the support's line (kSupportCos) is not held by it: a
/// ball striking a resting box from the side moves the box. Nor is a body its supports have not
/// stopped (kStoppedShare: at the row's points, along the normal, at most that share of the
/// approach speed, or at a holding point of the speed the other body closes at): a box on the end
/// of a plank balanced on a pivot is pressed against the plank, the plank against the pivot, yet
/// the plank turns, and taken as a wall it sent a 10 kg ball up 0.43 m/s faster than the rounds
/// without it. A twentieth was too strict: a planar box's two ground points, one pass a round,
/// left it moving faster, and a 100 kg ball on it rose 4 to 38 %.
inline constexpr double kSupportCos = 0.7;
inline constexpr double kStoppedShare = 0.25;

/// Per lane, the body that its support holds against the row's push.
struct PinnedLanes {
    MaskW a{}, b{};
    bool none() const { return noLane(a | b); }
};

/// Per lane, whether body A (B) is all but still along the normal at the row's points:
/// `speedA[j]`, `speedB[j]` are each body's normal velocity at point j. At a bouncing point its
/// speed is at most kStoppedShare of the approach speed; at a holding point, of the speed at which
/// the other body closes on or leaves it.
struct StoppedLanes {
    MaskW a{}, b{};
};

// Everything the kernels call with a wide value is inlined (no lambdas): an out-of-line call
// passes a 32-byte vector one way from the AVX2 kernels and another from the baseline ones, and
// at the sanitizer build's -O1 such calls were left out of line and read garbage.
[[gnu::always_inline]] inline MaskW withinSpeed(FloatW speed, FloatW limit) {
    return (speed <= limit) & (zero() - speed <= limit);
}

template <class Cold>
[[gnu::always_inline]] inline StoppedLanes stoppedLanes(const RestitutionRows& rows, const Cold& cold, int pointCount,
                                                        const FloatW* speedA, const FloatW* speedB) {
    StoppedLanes stopped{rows.bounced | rows.anyHeld, rows.bounced | rows.anyHeld};
    const FloatW share = splat(kStoppedShare);
    for (int j = 0; j < pointCount; ++j) {
        const MaskW active = rows.bounces[j] | rows.held[j];
        if (noLane(active)) continue;
        const FloatW relative = speedB[j] - speedA[j];
        const FloatW limit = share * select(rows.bounces[j], zero() - cold.relativeVelocity[j], max(relative, zero() - relative));
        stopped.a &= ~active | withinSpeed(speedA[j], limit);
        stopped.b &= ~active | withinSpeed(speedB[j], limit);
    }
    return stopped;
}

/// Over the lanes of `rows` (those that bounce or hold), the bodies whose support holds them against
/// the row's push: `normalOf(lane)` is the lane's normal (from A to B) as a Vec3, and body B is
/// pushed along it, A against it. A static or kinematic partner is a wall already.
template <class Contact, class NormalOf>
[[gnu::always_inline]] inline PinnedLanes supportedLanes(const Contact& c, const Vec3* supports, MaskW rows,
                                                         NormalOf normalOf) {
    PinnedLanes held;
    for (int k = 0; k < kLanes; ++k) {
        if (!rows[k] || !c.writeA[k] || !c.writeB[k]) continue;
        const Vec3 n = normalOf(k);
        held.a[k] = n.dot(supports[c.bodyA[k]]) > kSupportCos ? -1 : 0;
        held.b[k] = n.dot(supports[c.bodyB[k]]) < -kSupportCos ? -1 : 0;
    }
    return held;
}

/// The supported bodies (supportedLanes) that are also stopped (stoppedLanes). A lane whose bodies
/// both qualify pins neither: each would be the other's wall.
[[gnu::always_inline]] inline PinnedLanes pinnedLanes(const PinnedLanes& supported, const StoppedLanes& stopped) {
    const MaskW a = supported.a & stopped.a, b = supported.b & stopped.b;
    return {a & ~b, b & ~a};
}

/// A record's masses while its pinned lanes' bodies count as immovable: what pinBodies replaced, for
/// unpinBodies to put back (a WideContact's inverse inertia is a SymMat3W, a PlanarContact's one
/// FloatW about Z).
template <class Contact>
struct SavedMasses {
    FloatW invMassA, invMassB;
    decltype(Contact::invIA) invIA, invIB;
    FloatW normalMass[4];
};

/// The pinned body of each lane takes no impulse, and its points' normal mass is the other body's
/// alone (which moves: only a body between two moving ones is pinned). `shareA[j]`, `shareB[j]`:
/// each body's part of point j's inverse effective mass (inverse mass plus the turning term).
template <class Contact>
[[gnu::always_inline]] inline SavedMasses<Contact> pinBodies(Contact& c, const PinnedLanes& pinned, const FloatW* shareA,
                                                             const FloatW* shareB) {
    SavedMasses<Contact> saved{c.invMassA, c.invMassB, c.invIA, c.invIB, {}};
    c.invMassA = cleared(c.invMassA, pinned.a);
    c.invMassB = cleared(c.invMassB, pinned.b);
    c.invIA = cleared(c.invIA, pinned.a);
    c.invIB = cleared(c.invIB, pinned.b);
    const MaskW any = pinned.a | pinned.b;
    for (int j = 0; j < c.pointCount; ++j) {
        auto& cp = c.points[j];
        saved.normalMass[j] = cp.normalMass;
        const FloatW k = select(pinned.a, shareB[j], shareA[j]);  // pinned in B's lanes: A's share
        cp.normalMass = select(any, splat(1.0) / select(any, k, splat(1.0)), cp.normalMass);
    }
    return saved;
}

template <class Contact, class Saved>
[[gnu::always_inline]] inline void unpinBodies(Contact& c, const Saved& saved) {
    c.invMassA = saved.invMassA;
    c.invMassB = saved.invMassB;
    c.invIA = saved.invIA;
    c.invIB = saved.invIB;
    for (int j = 0; j < c.pointCount; ++j) c.points[j].normalMass = saved.normalMass[j];
}

/// `rows` in `lanes` only: the restitution passes after the first, which only lanes that bounced
/// take, so that what a lane gets does not hang on the other lanes of its record.
[[gnu::always_inline]] inline RestitutionRows rowsOfLanes(const RestitutionRows& rows, MaskW lanes) {
    RestitutionRows out = rows;
    for (int j = 0; j < 4; ++j) {
        out.bounces[j] = rows.bounces[j] & lanes;
        out.held[j] = rows.held[j] & lanes;
    }
    out.bounced = rows.bounced & lanes;
    out.anyHeld = rows.anyHeld & lanes;
    return out;
}

/// After a record's passes: across each lane of `pushed` (holding rows that pushed), a body pressed
/// against a partner that cannot give way (static, kinematic or held itself along the push) is
/// held from then on, along the normal pushing it. The first support found stays for the step.
template <class Contact, class NormalOf>
[[gnu::always_inline]] inline void propagateSupport(const Contact& c, Vec3* supports, MaskW pushed, NormalOf normalOf) {
    for (int k = 0; k < kLanes; ++k) {
        if (!pushed[k]) continue;
        const Vec3 n = normalOf(k);
        const bool aHolds = !c.writeA[k] || n.dot(supports[c.bodyA[k]]) > kSupportCos;
        const bool bHolds = !c.writeB[k] || n.dot(supports[c.bodyB[k]]) < -kSupportCos;
        if (c.writeB[k] && aHolds && supports[c.bodyB[k]].isZero()) supports[c.bodyB[k]] = n;
        if (c.writeA[k] && bHolds && supports[c.bodyA[k]].isZero()) supports[c.bodyA[k]] = -n;
    }
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

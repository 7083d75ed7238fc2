// The contact kernels that run every pass: warm start, solve (and relax), restitution. Each is
// built twice, for the x86-64 baseline (SSE2) and for AVX2, from one always-inlined body, and the
// CPU picks at run time; both do the same lane-by-lane arithmetic without fused multiply-add, so
// they give the same bits (tested), and a binary built on one machine runs on any x86-64.
#include <cmath>
#include <cstddef>

#include "solver/contact_constraint.hpp"
#include "solver/manifold_sweeps.hpp"
#include "solver/restitution_math.hpp"
#include "solver/restitution_rows.hpp"
#include "solver/rigid_bias.hpp"
#include "solver/isa_kernels.hpp"
#include "solver/prefetch.hpp"
#include "solver/state_runs.hpp"



namespace anyphys::native {

using namespace wide;

namespace {

// ---- gathering the lanes' bodies ---------------------------------------------------------------

struct BodyW {
    Vec3W v, w, dp;
    QuatW dq;
};

// What the passes read of a body: runs of SolverState (state_runs.hpp).
constexpr std::size_t kAngularRun = offsetof(SolverState, w);       // w[0..2], v[0]
constexpr std::size_t kLinearRun = offsetof(SolverState, v) + kDouble;  // v[1..2], turn
constexpr std::size_t kMotionRun = offsetof(SolverState, dp);       // dp[0..2], dq[0]
constexpr std::size_t kTurnRun = offsetof(SolverState, dq) + kDouble;   // dq[1..3], inBounce
static_assert(offsetof(SolverState, v) == kAngularRun + 3 * kDouble && offsetof(SolverState, dq) == kMotionRun + 3 * kDouble &&
                  kTurnRun + 4 * kDouble == sizeof(SolverState),
              "SolverState's runs moved");

ANYPHYS_KERNEL BodyW gatherVelocities(const SolverState* states, const std::int32_t* index) {
    BodyW b{};
    FloatW unused0, unused1;
    gatherRuns(states, index, kAngularRun, b.w.x, b.w.y, b.w.z, b.v.x);
    gatherRuns(states, index, kLinearRun, b.v.y, b.v.z, unused0, unused1);
    return b;
}

ANYPHYS_KERNEL BodyW gatherMotion(const SolverState* states, const std::int32_t* index) {
    BodyW b = gatherVelocities(states, index);
    FloatW unused;
    gatherRuns(states, index, kMotionRun, b.dp.x, b.dp.y, b.dp.z, b.dq.w);
    gatherRuns(states, index, kTurnRun, b.dq.x, b.dq.y, b.dq.z, unused);
    return b;
}

ANYPHYS_KERNEL void scatterVelocities(SolverState* states, const std::int32_t* index, const bool* write, const BodyW& b) {
    scatterRuns(states, index, write, kAngularRun, 4 * kDouble, b.w.x, b.w.y, b.w.z, b.v.x);
    scatterRuns(states, index, write, kLinearRun, 2 * kDouble, b.v.y, b.v.z, zero(), zero());  // not turn
}

// Applies impulse P at anchors rA (on A, negated) and rB.
ANYPHYS_KERNEL void applyImpulse(BodyW& a, BodyW& b, const WideContact& c, const Vec3W& rA, const Vec3W& rB, const Vec3W& P) {
    a.v = a.v - c.invMassA * P;
    a.w = a.w - c.invIA * cross(rA, P);
    b.v = b.v + c.invMassB * P;
    b.w = b.w + c.invIB * cross(rB, P);
}

ANYPHYS_KERNEL Vec3W relativeVelocity(const BodyW& a, const BodyW& b, const Vec3W& rA, const Vec3W& rB) {
    return (b.v + cross(b.w, rB)) - (a.v + cross(a.w, rA));
}

// The friction centre's arm in the lanes `turn` marks, turned as the body has since the step began.
ANYPHYS_KERNEL Vec3W turnedArm(const bool (&turn)[kLanes], const QuatW& dq, const Vec3W& arm) {
    const MaskW lanes = laneMask(turn);
    const Vec3W turned = rotate(dq, arm);
    return {select(lanes, turned.x, arm.x), select(lanes, turned.y, arm.y), select(lanes, turned.z, arm.z)};
}

// Central friction (two tangents in a circle of mu * sum of the points' loads) and twist friction
// (in mu * sum of lever arm x load). `load` is each point's normal impulse as the pass sees it;
// lanes outside `lanes` keep their impulses.
ANYPHYS_KERNEL void solveFriction(WideContact& c, BodyW& a, BodyW& b, const FloatW* load, MaskW lanes) {
    FloatW totalNormal = zero(), twistLimit = zero();
    for (int j = 0; j < c.pointCount; ++j) {
        totalNormal += load[j];
        twistLimit += c.points[j].leverArm * load[j];
    }
    {
        const FloatW twistSpeed = dot(c.normal, b.w - a.w);
        const FloatW maxTwist = c.friction * twistLimit;
        const FloatW old = c.twistImpulse;
        c.twistImpulse = select(lanes, clamp(old - c.twistMass * twistSpeed, -maxTwist, maxTwist), old);
        const Vec3W L = (c.twistImpulse - old) * c.normal;
        a.w = a.w - c.invIA * L;
        b.w = b.w + c.invIB * L;
    }
    const Vec3W tangent2 = secondTangent(c);
    const Vec3W vr = relativeVelocity(a, b, c.centerA, c.centerB);
    const FloatW vt1 = dot(vr, c.tangent1), vt2 = dot(vr, tangent2);
    FloatW f1 = c.frictionImpulse1 - (c.tangentMass.xx * vt1 + c.tangentMass.xy * vt2);
    FloatW f2 = c.frictionImpulse2 - (c.tangentMass.xy * vt1 + c.tangentMass.yy * vt2);
    const FloatW maxImpulse = c.friction * totalNormal;
    const FloatW lengthSquared = f1 * f1 + f2 * f2;
    const MaskW outside = lengthSquared > maxImpulse * maxImpulse;
    // Outside the circle lengthSquared > 0, so the division is safe where it is used.
    const FloatW factor = select(outside, maxImpulse / sqrt(select(outside, lengthSquared, splat(1.0))), splat(1.0));
    f1 = select(lanes, f1 * factor, c.frictionImpulse1);
    f2 = select(lanes, f2 * factor, c.frictionImpulse2);
    const Vec3W P = (f1 - c.frictionImpulse1) * c.tangent1 + (f2 - c.frictionImpulse2) * tangent2;
    c.frictionImpulse1 = f1;
    c.frictionImpulse2 = f2;
    applyImpulse(a, b, c, c.centerA, c.centerB, P);
}


// The record's accumulated impulses summed into one linear and one angular impulse per body, as
// velocity changes: the inverse inertia is multiplied twice per manifold instead of twice per
// point and row, and the next warm start applies them without reading the record.
ANYPHYS_KERNEL void summarize(const WideContact& c, WideWarmStart& out) {
    const Vec3W friction = c.frictionImpulse1 * c.tangent1 + c.frictionImpulse2 * secondTangent(c);
    FloatW normalTotal = zero();
    Vec3W angularA = cross(c.centerA, friction), angularB = cross(c.centerB, friction);
    for (int j = 0; j < c.pointCount; ++j) {
        const WideContactPoint& cp = c.points[j];
        const Vec3W P = cp.normalImpulse * c.normal;
        normalTotal += cp.normalImpulse;
        angularA = angularA + cross(cp.anchorA, P);
        angularB = angularB + cross(cp.anchorB, P);
    }
    const Vec3W twist = c.twistImpulse * c.normal;
    angularA = angularA + twist;
    angularB = angularB + twist;
    const Vec3W linear = friction + normalTotal * c.normal;
    copyLaneBodies(c, out);
    out.linearA = c.invMassA * linear;
    out.angularA = c.invIA * angularA;
    out.linearB = c.invMassB * linear;
    out.angularB = c.invIB * angularB;
}

ANYPHYS_KERNEL void summarizeImpl(const WideContact* contacts, WideWarmStart* warm, int count) {
    for (int i = 0; i < count; ++i) summarize(contacts[i], warm[i]);
}

ANYPHYS_KERNEL void warmStartImpl(const WideWarmStart* warm, int count, SolverState* states) {
    for (int i = 0; i < count; ++i) {
        if (i + kRecordsAhead < count) prefetchStates(states, warm[i + kRecordsAhead].bodyA, warm[i + kRecordsAhead].bodyB, kCacheLine);
        const WideWarmStart& c = warm[i];
        BodyW a = gatherVelocities(states, c.bodyA), b = gatherVelocities(states, c.bodyB);
        a.v = a.v - c.linearA;
        a.w = a.w - c.angularA;
        b.v = b.v + c.linearB;
        b.w = b.w + c.angularB;
        scatterVelocities(states, c.bodyA, c.writeA, a);
        scatterVelocities(states, c.bodyB, c.writeB, b);
    }
}

// Takes back friction beyond the bounds of the normal impulses the pass left: the friction row
// came first against a predicted load, and a pass over several points can leave less than each
// point predicted alone (a box landing on its face took 8 to 14 % more than mu N).
ANYPHYS_KERNEL void clampFrictionToLoad(WideContact& c, BodyW& a, BodyW& b) {
    FloatW totalNormal = zero(), twistLimit = zero();
    for (int j = 0; j < c.pointCount; ++j) {
        totalNormal += c.points[j].normalImpulse;
        twistLimit += c.points[j].leverArm * c.points[j].normalImpulse;
    }
    const FloatW maxTwist = c.friction * twistLimit;
    const FloatW oldTwist = c.twistImpulse;
    c.twistImpulse = clamp(oldTwist, -maxTwist, maxTwist);
    const Vec3W L = (c.twistImpulse - oldTwist) * c.normal;
    a.w = a.w - c.invIA * L;
    b.w = b.w + c.invIB * L;
    const FloatW maxImpulse = c.friction * totalNormal;
    const FloatW f1 = c.frictionImpulse1, f2 = c.frictionImpulse2;
    const FloatW lengthSquared = f1 * f1 + f2 * f2;
    const MaskW outside = lengthSquared > maxImpulse * maxImpulse;
    const FloatW factor = select(outside, maxImpulse / sqrt(select(outside, lengthSquared, splat(1.0))), splat(1.0));
    c.frictionImpulse1 = f1 * factor;
    c.frictionImpulse2 = f2 * factor;
    const Vec3W P = (c.frictionImpulse1 - f1) * c.tangent1 + (c.frictionImpulse2 - f2) * secondTangent(c);
    applyImpulse(a, b, c, c.centerA, c.centerB, P);
}

// Current separation of a point from the bodies' motion since the step began (no new collision
// pass inside the step).
ANYPHYS_KERNEL FloatW separation(const WideContact& c, const WideContactPoint& cp, const BodyW& a, const BodyW& b,
                                 const Vec3W& dp) {
    const Vec3W moved = dp + rotate(b.dq, cp.anchorB) - rotate(a.dq, cp.anchorA);
    return dot(c.normal, moved) + cp.baseSeparation;
}

// ---- a manifold's rows, swept again after an impact (manifold_sweeps.hpp) ----------------------

/// Point k's row in this pass: its velocity bias, and its softness (mass scale and impulse scale;
/// 1 and 0 for a rigid row). The same every sweep of the pass: positions do not move within it.
ANYPHYS_KERNEL void rowOf(const PassRows& p, const WideContact& c, int k, const BodyW& a, const BodyW& b, const Vec3W& dp,
                          FloatW& bias, FloatW& massScale, FloatW& impulseScale) {
    massScale = splat(1.0);
    impulseScale = zero();
    if (p.predictLoad) {
        bias = p.rowBias[k];
    } else if (p.soft) {
        const FloatW s = separation(c, c.points[k], a, b, dp);
        // A speculative point allows the approach to close exactly the gap this substep.
        const MaskW speculative = s > zero();
        bias = select(speculative, s * p.invH, max(p.biasRate * s, p.maxPush));
        massScale = select(speculative, splat(1.0), p.massScale);
        impulseScale = select(speculative, zero(), p.impulseScale);
    } else {  // a rigid row: the relax pass; PGS (Baumgarte)
        bias = rigidBias(p.rigid, separation(c, c.points[k], a, b, dp));
    }
}

// One sweep of a manifold's normal rows; after the first, only in `lanes` (the others keep their
// impulses). Returns the lanes where the first sweep moved a point by much.
template <bool kFirst>
ANYPHYS_KERNEL MaskW sweepNormalRows(WideContact& c, BodyW& a, BodyW& b, const Vec3W& dp, const PassRows& rows, bool reverse,
                                     MaskW lanes, bool endOfSubstep) {
    MaskW moved{};
    for (int n = 0; n < c.pointCount; ++n) {
        const int k = reverse ? c.pointCount - 1 - n : n;
        WideContactPoint& cp = c.points[k];
        FloatW bias, massScale, impulseScale;
        rowOf(rows, c, k, a, b, dp, bias, massScale, impulseScale);
        const FloatW vn = dot(relativeVelocity(a, b, cp.anchorA, cp.anchorB), c.normal);
        const FloatW impulse = -cp.normalMass * massScale * (vn + bias) - impulseScale * cp.normalImpulse;
        FloatW total = max(cp.normalImpulse + impulse, zero());
        if constexpr (!kFirst) total = select(lanes, total, cp.normalImpulse);
        const FloatW applied = total - cp.normalImpulse;
        if constexpr (kFirst) moved = moved | movedMuch(applied, cp.normalMass);
        cp.normalImpulse = total;
        cp.maxImpulse = max(cp.maxImpulse, total);
        if (endOfSubstep) cp.stepImpulse += kFirst ? total : applied;  // the substep's final impulse
        applyImpulse(a, b, c, cp.anchorA, cp.anchorB, applied * c.normal);
    }
    return moved;
}

// The later sweeps of the lanes an impact moved (manifold_sweeps.hpp): the normal rows (with more
// than one point), then friction, where no joint holds a body, and the normal rows in turn.
ANYPHYS_KERNEL void sweepAgain(WideContact& c, BodyW& a, BodyW& b, const Vec3W& dp, const PassRows& rows, bool reverse, MaskW again,
                               bool friction, bool endOfSubstep) {
    const MaskW normalAgain = again & laneMask(c.multiPoint);
    const bool anyNormalAgain = !noLane(normalAgain);
    if (anyNormalAgain)
        for (int sweep = 1; sweep < kMaxNormalSweeps; ++sweep)
            sweepNormalRows<false>(c, a, b, dp, rows, reverse, normalAgain, endOfSubstep);
    const MaskW frictionAgain = friction ? again & laneMask(c.unjointed) : MaskW{};
    if (noLane(frictionAgain)) return;
    for (int sweep = 1; sweep < kMaxFrictionSweeps; ++sweep) {
        FloatW load[4];
        for (int k = 0; k < c.pointCount; ++k) load[k] = c.points[k].normalImpulse;
        solveFriction(c, a, b, load, frictionAgain);
        if (anyNormalAgain) sweepNormalRows<false>(c, a, b, dp, rows, reverse, normalAgain, endOfSubstep);
    }
}

ANYPHYS_KERNEL void solveImpl(WideContact* contacts, WideWarmStart* warm, int count, SolverState* states,
                              const ContactSolveParams& params, bool useBias, bool endOfSubstep) {
    const FloatW invH = splat(params.invH);
    const FloatW maxPush = splat(-params.pushMaxVelocity);
    const FloatW one = splat(1.0);
    const FloatW baumgarte = splat(params.baumgarte * params.invH);
    const FloatW slop = splat(params.linearSlop);
    // Where a point's row is rigid (the relax pass; PGS), its friction is bounded by the impulse the
    // row will leave (below); the solve pass's soft rows keep the last impulses.
    const bool predictLoad = params.friction && (!useBias || !params.soft);
    const RigidBias rigid{invH, maxPush, baumgarte, slop, useBias};
    for (int i = 0; i < count; ++i) {
        if (i + kRecordsAhead < count) {
            prefetchStates(states, contacts[i + kRecordsAhead].bodyA, contacts[i + kRecordsAhead].bodyB, sizeof(SolverState));
            if (params.prefetchRecords) prefetchBytes<true>(&contacts[i + kRecordsAhead], sizeof(WideContact));
        }
        WideContact& c = contacts[i];
        BodyW a = gatherMotion(states, c.bodyA), b = gatherMotion(states, c.bodyB);
        const Vec3W dp = b.dp - a.dp;
        // A body's friction arm turns with it within the step where the pair is flat and the body
        // kinematic, or dynamic and turning more than kLeastArmTurn a step (WideContact::turnArmA,
        // turnArmB), so that a body riding it is held to the support's velocity where the two
        // touch now. Held at the step's first arm, a box riding a turntable (2 rad/s, 1 m out,
        // mu 0.5) was held to the table's velocity where the box had been and slid outward 18 cm
        // in 3 s at 8 substeps (ODE and Bullet, at one step, 10.5 cm); turned, 0.3 cm, whether the
        // table is kinematic or a motor turns it. The inverse inertia stays the step's first. A
        // round shape's arm stays, as its touching point is not a point of the body. The pass
        // works on the turned arms; the record keeps the step's first ones.
        Vec3W firstArmA, firstArmB;
        const bool turning = params.friction && c.turnsArms;
        if (turning) {
            firstArmA = c.centerA;
            firstArmB = c.centerB;
            c.centerA = turnedArm(c.turnArmA, a.dq, firstArmA);
            c.centerB = turnedArm(c.turnArmB, b.dq, firstArmB);
        }
        // Friction first, so non-penetration has the last word in each pass. Its bound: through
        // soft rows the last normal impulses; through rigid ones each point's impulse as its row
        // will leave it, and what the rows then leave caps it (clampFrictionToLoad). Against the
        // last impulses alone, an impact (whose impulse comes in one relax pass, then leaves as
        // the bodies part) got no friction at the default of one pass per substep: a ball landing
        // obliquely kept sliding unspun.
        FloatW rowBias[4];  // predictLoad: each point's rigidBias
        if (params.friction) {
            FloatW load[4];
            for (int k = 0; k < c.pointCount; ++k) {
                const WideContactPoint& cp = c.points[k];
                load[k] = cp.normalImpulse;
                if (predictLoad) {
                    const FloatW s = separation(c, cp, a, b, dp);
                    rowBias[k] = rigidBias(rigid, s);
                    const FloatW vn = dot(relativeVelocity(a, b, cp.anchorA, cp.anchorB), c.normal);
                    load[k] = max(cp.normalImpulse - cp.normalMass * (vn + rowBias[k]), zero());
                }
            }
            solveFriction(c, a, b, load, kAllLanes);
        }

        const bool softRows = useBias && params.soft;
        const PassRows rows{rigid, invH, maxPush, softRows ? c.biasRate : zero(), softRows ? c.massScale : one,
                            softRows ? c.impulseScale : zero(), predictLoad, softRows, rowBias};
        // PGS alternates the order of a manifold's points from pass to pass: always first, the
        // first point of a symmetric face (a box on a box) takes more than its share and the pair
        // starts to turn; a 10-box stack toppled at 1 substep (drift 2.9 m; 3.3 cm alternating). The soft
        // step keeps one order: its relax passes already even the points out, and alternating
        // there opened a ragdoll pile's joints (31 -> 73 mm).
        const bool reverse = !params.soft && c.reverse;
        c.reverse = !c.reverse;
        const MaskW again = sweepNormalRows<true>(c, a, b, dp, rows, reverse, kAllLanes, endOfSubstep);
        if (!noLane(again)) sweepAgain(c, a, b, dp, rows, reverse, again, params.friction, endOfSubstep);
        if (predictLoad && (!useBias || endOfSubstep)) clampFrictionToLoad(c, a, b);
        scatterVelocities(states, c.bodyA, c.writeA, a);
        scatterVelocities(states, c.bodyB, c.writeB, b);
        if (endOfSubstep) summarize(c, warm[i]);
        if (turning) {
            c.centerA = firstArmA;
            c.centerB = firstArmB;
        }
    }
}

ANYPHYS_KERNEL Vec3 laneOf(const Vec3W& v, int lane) { return {v.x[lane], v.y[lane], v.z[lane]}; }

// The lanes whose body shock propagation pins in this pass (restitution_rows.hpp).
template <class NormalOf>
ANYPHYS_KERNEL PinnedLanes pinnedBodies(const WideContact& c, const WideContactCold& cold, const RestitutionRows& rows,
                                        const BodyW& a, const BodyW& b, const Vec3* supports, NormalOf normalOf) {
    const PinnedLanes supported = supportedLanes(c, supports, rows.bounced | rows.anyHeld, normalOf);
    if (supported.none()) return supported;
    FloatW speedA[4], speedB[4];  // each body's normal velocity at each point
    for (int j = 0; j < c.pointCount; ++j) {
        speedA[j] = dot(a.v + cross(a.w, c.points[j].anchorA), c.normal);
        speedB[j] = dot(b.v + cross(b.w, c.points[j].anchorB), c.normal);
    }
    return pinnedLanes(supported, stoppedLanes(rows, cold, c.pointCount, speedA, speedB));
}

ANYPHYS_KERNEL SavedMasses<WideContact> pinMasses(WideContact& c, const PinnedLanes& pinned) {
    FloatW shareA[4], shareB[4];  // each body's part of a point's inverse effective mass
    for (int j = 0; j < c.pointCount; ++j) {
        const Vec3W rnA = cross(c.points[j].anchorA, c.normal), rnB = cross(c.points[j].anchorB, c.normal);
        shareA[j] = c.invMassA + dot(rnA, c.invIA * rnA);
        shareB[j] = c.invMassB + dot(rnB, c.invIB * rnB);
    }
    return pinBodies(c, pinned, shareA, shareB);
}

ANYPHYS_KERNEL bool restitutionImpl(WideContact* contacts, WideContactCold* colds, int count, SolverState* states,
                                    Vec3* supports, const ContactSolveParams& params) {
    const FloatW threshold = splat(-params.restitutionThreshold);
    bool found = false;
    for (int i = 0; i < count; ++i) {
        WideContact& c = contacts[i];
        WideContactCold& cold = colds[i];
        const RestitutionRows rows = restitutionRows(c, cold, states, threshold);
        if (rows.none()) continue;
        found = true;
        markInBounce(states, c.bodyA, c.writeA, c.bodyB, c.writeB, rows.bounced);
        BodyW a = gatherVelocities(states, c.bodyA), b = gatherVelocities(states, c.bodyB);
        const auto normalOf = [&c](int lane) { return laneOf(c.normal, lane); };  // scalar: no wide value passes
        const PinnedLanes pinned = pinnedBodies(c, cold, rows, a, b, supports, normalOf);
        const bool pinning = !pinned.none();
        SavedMasses<WideContact> saved{};
        if (pinning) saved = pinMasses(c, pinned);
        FloatW load[4];
        // Friction acts through the whole impact: a ball still sliding as it rebounds takes mu
        // times the bounce's impulse too (as ODE, Bullet and Box2D give it; without this, a ball
        // landing at 3 m/s each way with e = 1 and mu = 0.1 left at 2.7 m/s where they give 2.4).
        // In every pass: the normal rows even out the face's tilt, and friction then stops the
        // slide the tilt had left at the face, which after a single friction row came back as spin.
        // A lane that only holds gets one pass a round (its rows settle over the rounds): the
        // holding reaches down a pile, and 16 passes on each of its records were wasted work.
        const int passes = noLane(rows.bounced) ? 1 : kRestitutionPasses;
        const RestitutionRows later = rowsOfLanes(rows, rows.bounced);
        for (int pass = 0; pass < passes; ++pass) {
            for (int j = 0; j < c.pointCount; ++j) {
                WideContactPoint& cp = c.points[j];
                const FloatW vn = dot(relativeVelocity(a, b, cp.anchorA, cp.anchorB), c.normal);
                const FloatW applied = restitutionRowImpulse(pass == 0 ? rows : later, j, cp, cold, vn);
                load[j] = cp.normalImpulse;
                applyImpulse(a, b, c, cp.anchorA, cp.anchorB, applied * c.normal);
            }
            if (params.friction && !noLane(rows.bounced)) solveFriction(c, a, b, load, rows.bounced);
        }
        if (pinning) unpinBodies(c, saved);
        scatterVelocities(states, c.bodyA, c.writeA, a);
        scatterVelocities(states, c.bodyB, c.writeB, b);
        const MaskW pushed = heldRowsThatPushed(rows, cold, c.pointCount);
        markInBounce(states, c.bodyA, c.writeA, c.bodyB, c.writeB, pushed);
        propagateSupport(c, supports, pushed, normalOf);
    }
    return found;
}

#if ANYPHYS_HAS_AVX2_KERNELS
ANYPHYS_AVX2 void summarizeAvx2(const WideContact* c, WideWarmStart* w, int n) { summarizeImpl(c, w, n); }
ANYPHYS_AVX2 void warmStartAvx2(const WideWarmStart* w, int n, SolverState* s) { warmStartImpl(w, n, s); }
ANYPHYS_AVX2 void solveAvx2(WideContact* c, WideWarmStart* w, int n, SolverState* s, const ContactSolveParams& p, bool bias,
                            bool end) {
    solveImpl(c, w, n, s, p, bias, end);
}
ANYPHYS_AVX2 bool restitutionAvx2(WideContact* c, WideContactCold* cold, int n, SolverState* s, Vec3* supports,
                                   const ContactSolveParams& p) {
    return restitutionImpl(c, cold, n, s, supports, p);
}
#endif

void summarizeBase(const WideContact* c, WideWarmStart* w, int n) { summarizeImpl(c, w, n); }
void warmStartBase(const WideWarmStart* w, int n, SolverState* s) { warmStartImpl(w, n, s); }
void solveBase(WideContact* c, WideWarmStart* w, int n, SolverState* s, const ContactSolveParams& p, bool bias, bool end) {
    solveImpl(c, w, n, s, p, bias, end);
}
bool restitutionBase(WideContact* c, WideContactCold* cold, int n, SolverState* s, Vec3* supports,
                     const ContactSolveParams& p) {
    return restitutionImpl(c, cold, n, s, supports, p);
}

bool detectAvx2() {
#if ANYPHYS_HAS_AVX2_KERNELS
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

bool& avx2Enabled() {
    static bool enabled = detectAvx2();
    return enabled;
}

}  // namespace

bool contactKernelsUseAvx2() { return avx2Enabled(); }

bool setContactKernelsAvx2(bool enable) {
    avx2Enabled() = enable && detectAvx2();
    return avx2Enabled();
}

void summarizeImpulses(const WideContact* contacts, WideWarmStart* warm, int count) {
#if ANYPHYS_HAS_AVX2_KERNELS
    if (avx2Enabled()) return summarizeAvx2(contacts, warm, count);
#endif
    summarizeBase(contacts, warm, count);
}

void warmStartContacts(const WideWarmStart* warm, int count, SolverState* states) {
#if ANYPHYS_HAS_AVX2_KERNELS
    if (avx2Enabled()) return warmStartAvx2(warm, count, states);
#endif
    warmStartBase(warm, count, states);
}

void solveContacts(WideContact* contacts, WideWarmStart* warm, int count, SolverState* states,
                   const ContactSolveParams& params, bool useBias, bool endOfSubstep) {
#if ANYPHYS_HAS_AVX2_KERNELS
    if (avx2Enabled()) return solveAvx2(contacts, warm, count, states, params, useBias, endOfSubstep);
#endif
    solveBase(contacts, warm, count, states, params, useBias, endOfSubstep);
}

bool applyRestitution(WideContact* contacts, WideContactCold* cold, int count, SolverState* states, Vec3* supports,
                      const ContactSolveParams& params) {
#if ANYPHYS_HAS_AVX2_KERNELS
    if (avx2Enabled()) return restitutionAvx2(contacts, cold, count, states, supports, params);
#endif
    return restitutionBase(contacts, cold, count, states, supports, params);
}

}  // namespace anyphys::native

// The planar contact kernels that run every pass (warm start, solve and relax, restitution), built
// for the x86-64 baseline and for AVX2 like contact_solve.cpp, same bits either way. Three
// degrees of freedom per body: x, y and the angle about Z (see planar_contact.hpp).
#include "solver/planar_contact.hpp"

#include <cstddef>

#include "solver/manifold_sweeps.hpp"
#include "solver/restitution_math.hpp"
#include "solver/restitution_rows.hpp"
#include "solver/rigid_bias.hpp"
#include "solver/isa_kernels.hpp"
#include "solver/state_runs.hpp"



namespace anyphys::native {

using namespace wide;

namespace {

struct PlanarBodyW {
    FloatW vx, vy, w;
    FloatW vz;        // read with the others and written back as read (zero in a planar world)
    FloatW dpx, dpy;  // displacement since the step began
    FloatW c, s;      // cosine and sine of the turn since the step began
};

// What the passes read of a body: two runs of SolverState (state_runs.hpp).
constexpr std::size_t kPlanarVelocityRun = offsetof(SolverState, w) + 2 * kDouble;  // w[2], v[0], v[1], v[2]
constexpr std::size_t kPlanarMotionRun = offsetof(SolverState, turn);  // turn[0], turn[1], dp[0], dp[1]
static_assert(offsetof(SolverState, v) == kPlanarVelocityRun + kDouble && offsetof(SolverState, dp) == kPlanarMotionRun + 2 * kDouble,
              "SolverState's planar runs moved");

ANYPHYS_KERNEL PlanarBodyW gatherPlanarVelocities(const SolverState* states, const std::int32_t* index) {
    PlanarBodyW b{};
    gatherRuns(states, index, kPlanarVelocityRun, b.w, b.vx, b.vy, b.vz);
    return b;
}

ANYPHYS_KERNEL PlanarBodyW gatherPlanarMotion(const SolverState* states, const std::int32_t* index) {
    PlanarBodyW b = gatherPlanarVelocities(states, index);
    gatherRuns(states, index, kPlanarMotionRun, b.c, b.s, b.dpx, b.dpy);
    return b;
}

ANYPHYS_KERNEL void scatterVelocities(SolverState* states, const std::int32_t* index, const bool* write,
                                      const PlanarBodyW& b) {
    scatterRuns(states, index, write, kPlanarVelocityRun, 4 * kDouble, b.w, b.vx, b.vy, b.vz);
}

// A record's friction arms, kept while a pass works on turned ones.
struct FrictionArms {
    FloatW ax, ay, bx, by;
};

// The friction arm (x, y) in the lanes `turn` marks, turned as `body` has since the step began.
ANYPHYS_KERNEL void turnArm(const bool (&turn)[kLanes], const PlanarBodyW& body, FloatW& x, FloatW& y) {
    const MaskW lanes = laneMask(turn);
    const FloatW tx = body.c * x - body.s * y, ty = body.s * x + body.c * y;
    x = select(lanes, tx, x);
    y = select(lanes, ty, y);
}

// Applies the impulse (px, py) at anchors r on A (negated) and on B.
ANYPHYS_KERNEL void applyImpulse(PlanarBodyW& a, PlanarBodyW& b, const PlanarContact& c, FloatW rAx, FloatW rAy,
                                 FloatW rBx, FloatW rBy, FloatW px, FloatW py) {
    a.vx -= c.invMassA * px;
    a.vy -= c.invMassA * py;
    a.w -= c.invIA * (rAx * py - rAy * px);
    b.vx += c.invMassB * px;
    b.vy += c.invMassB * py;
    b.w += c.invIB * (rBx * py - rBy * px);
}

// Normal velocity of B relative to A at anchors rA, rB: n . ((vB + wB x rB) - (vA + wA x rA)).
ANYPHYS_KERNEL FloatW normalVelocity(const PlanarBodyW& a, const PlanarBodyW& b, FloatW nx, FloatW ny, FloatW rAx,
                                     FloatW rAy, FloatW rBx, FloatW rBy) {
    const FloatW dvx = (b.vx - b.w * rBy) - (a.vx - a.w * rAy);
    const FloatW dvy = (b.vy + b.w * rBx) - (a.vy + a.w * rAx);
    return nx * dvx + ny * dvy;
}

// Friction at the manifold's centre along the tangent (-ny, nx), in [-mu N, mu N] with N the sum
// of the points' loads (each point's normal impulse as the pass sees it); lanes outside `lanes`
// keep their impulse.
ANYPHYS_KERNEL void solveFriction(PlanarContact& c, PlanarBodyW& a, PlanarBodyW& b, const FloatW* load, MaskW lanes) {
    FloatW totalNormal = zero();
    for (int j = 0; j < c.pointCount; ++j) totalNormal += load[j];
    const FloatW tx = -c.normalY, ty = c.normalX;
    const FloatW vt = normalVelocity(a, b, tx, ty, c.centerAx, c.centerAy, c.centerBx, c.centerBy);
    const FloatW maxImpulse = c.friction * totalNormal;
    const FloatW old = c.frictionImpulse;
    c.frictionImpulse = select(lanes, clamp(old - c.tangentMass * vt, -maxImpulse, maxImpulse), old);
    const FloatW P = c.frictionImpulse - old;
    applyImpulse(a, b, c, c.centerAx, c.centerAy, c.centerBx, c.centerBy, P * tx, P * ty);
}

// Takes back friction beyond mu times the normal impulses the pass left (as in 3D).
ANYPHYS_KERNEL void clampFrictionToLoad(PlanarContact& c, PlanarBodyW& a, PlanarBodyW& b) {
    FloatW totalNormal = zero();
    for (int j = 0; j < c.pointCount; ++j) totalNormal += c.points[j].normalImpulse;
    const FloatW maxImpulse = c.friction * totalNormal;
    const FloatW old = c.frictionImpulse;
    c.frictionImpulse = clamp(old, -maxImpulse, maxImpulse);
    const FloatW P = c.frictionImpulse - old;
    applyImpulse(a, b, c, c.centerAx, c.centerAy, c.centerBx, c.centerBy, -P * c.normalY, P * c.normalX);
}

// The accumulated impulses summed into one impulse and one moment per body, as the changes of
// velocity the warm start applies.
ANYPHYS_KERNEL void summarize(const PlanarContact& c, PlanarWarmStart& out) {
    const FloatW nx = c.normalX, ny = c.normalY;
    const FloatW f = c.frictionImpulse;
    FloatW normalTotal = zero();
    // Moments r x P of the friction impulse f (-ny, nx) and of each point's impulse l (nx, ny).
    FloatW momentA = f * (c.centerAx * nx + c.centerAy * ny), momentB = f * (c.centerBx * nx + c.centerBy * ny);
    for (int j = 0; j < c.pointCount; ++j) {
        const PlanarContactPoint& cp = c.points[j];
        normalTotal += cp.normalImpulse;
        momentA += cp.normalImpulse * (cp.anchorAx * ny - cp.anchorAy * nx);
        momentB += cp.normalImpulse * (cp.anchorBx * ny - cp.anchorBy * nx);
    }
    const FloatW px = normalTotal * nx - f * ny, py = normalTotal * ny + f * nx;
    copyLaneBodies(c, out);
    out.vxA = c.invMassA * px;
    out.vyA = c.invMassA * py;
    out.wA = c.invIA * momentA;
    out.vxB = c.invMassB * px;
    out.vyB = c.invMassB * py;
    out.wB = c.invIB * momentB;
}

ANYPHYS_KERNEL void summarizeImpl(const PlanarContact* contacts, PlanarWarmStart* warm, int count) {
    for (int i = 0; i < count; ++i) summarize(contacts[i], warm[i]);
}

ANYPHYS_KERNEL void warmStartImpl(const PlanarWarmStart* warm, int count, SolverState* states) {
    for (int i = 0; i < count; ++i) {
        if (i + kRecordsAhead < count) prefetchStates(states, warm[i + kRecordsAhead].bodyA, warm[i + kRecordsAhead].bodyB, kCacheLine);
        const PlanarWarmStart& c = warm[i];
        PlanarBodyW a = gatherPlanarVelocities(states, c.bodyA), b = gatherPlanarVelocities(states, c.bodyB);
        a.vx -= c.vxA;
        a.vy -= c.vyA;
        a.w -= c.wA;
        b.vx += c.vxB;
        b.vy += c.vyB;
        b.w += c.wB;
        scatterVelocities(states, c.bodyA, c.writeA, a);
        scatterVelocities(states, c.bodyB, c.writeB, b);
    }
}

// Current separation of a point from the bodies' motion since the step began.
ANYPHYS_KERNEL FloatW separation(const PlanarContact& c, const PlanarContactPoint& cp, const PlanarBodyW& a,
                                 const PlanarBodyW& b, FloatW dpx, FloatW dpy) {
    const FloatW movedX = dpx + (b.c * cp.anchorBx - b.s * cp.anchorBy) - (a.c * cp.anchorAx - a.s * cp.anchorAy);
    const FloatW movedY = dpy + (b.s * cp.anchorBx + b.c * cp.anchorBy) - (a.s * cp.anchorAx + a.c * cp.anchorAy);
    return c.normalX * movedX + c.normalY * movedY + cp.baseSeparation;
}

/// Point k's row in this pass: its velocity bias and softness, the same every sweep of the pass.
ANYPHYS_KERNEL void rowOf(const PassRows& p, const PlanarContact& c, int k, const PlanarBodyW& a, const PlanarBodyW& b, FloatW dpx,
                          FloatW dpy, FloatW& bias, FloatW& massScale, FloatW& impulseScale) {
    massScale = splat(1.0);
    impulseScale = zero();
    if (p.predictLoad) {
        bias = p.rowBias[k];
    } else if (p.soft) {
        const FloatW s = separation(c, c.points[k], a, b, dpx, dpy);
        // A speculative point allows the approach to close exactly the gap this substep.
        const MaskW speculative = s > zero();
        bias = select(speculative, s * p.invH, max(p.biasRate * s, p.maxPush));
        massScale = select(speculative, splat(1.0), p.massScale);
        impulseScale = select(speculative, zero(), p.impulseScale);
    } else {  // a rigid row: the relax pass; PGS (Baumgarte)
        bias = rigidBias(p.rigid, separation(c, c.points[k], a, b, dpx, dpy));
    }
}

// One sweep of a manifold's normal rows; after the first, only in `lanes` (the others keep their
// impulses). Returns the lanes where the first sweep moved a point by much (manifold_sweeps.hpp).
template <bool kFirst>
ANYPHYS_KERNEL MaskW sweepNormalRows(PlanarContact& c, PlanarBodyW& a, PlanarBodyW& b, FloatW dpx, FloatW dpy, const PassRows& rows,
                                     bool reverse, MaskW lanes, bool endOfSubstep) {
    MaskW moved{};
    for (int n = 0; n < c.pointCount; ++n) {
        const int k = reverse ? c.pointCount - 1 - n : n;
        PlanarContactPoint& cp = c.points[k];
        FloatW bias, massScale, impulseScale;
        rowOf(rows, c, k, a, b, dpx, dpy, bias, massScale, impulseScale);
        const FloatW vn = normalVelocity(a, b, c.normalX, c.normalY, cp.anchorAx, cp.anchorAy, cp.anchorBx, cp.anchorBy);
        const FloatW impulse = -cp.normalMass * massScale * (vn + bias) - impulseScale * cp.normalImpulse;
        FloatW total = max(cp.normalImpulse + impulse, zero());
        if constexpr (!kFirst) total = select(lanes, total, cp.normalImpulse);
        const FloatW applied = total - cp.normalImpulse;
        if constexpr (kFirst) moved = moved | movedMuch(applied, cp.normalMass);
        cp.normalImpulse = total;
        cp.maxImpulse = max(cp.maxImpulse, total);
        if (endOfSubstep) cp.stepImpulse += kFirst ? total : applied;  // the substep's final impulse
        applyImpulse(a, b, c, cp.anchorAx, cp.anchorAy, cp.anchorBx, cp.anchorBy, applied * c.normalX, applied * c.normalY);
    }
    return moved;
}

// The later sweeps of the lanes an impact moved where no joint holds a body (manifold_sweeps.hpp):
// the normal rows (with more than one point), then friction and the normal rows in turn.
ANYPHYS_KERNEL void sweepAgain(PlanarContact& c, PlanarBodyW& a, PlanarBodyW& b, FloatW dpx, FloatW dpy, const PassRows& rows,
                               bool reverse, MaskW moved, bool friction, bool endOfSubstep) {
    const MaskW again = moved & laneMask(c.unjointed);
    if (noLane(again)) return;
    const MaskW normalAgain = again & laneMask(c.multiPoint);
    const bool anyNormalAgain = !noLane(normalAgain);
    if (anyNormalAgain)
        for (int sweep = 1; sweep < kMaxNormalSweeps; ++sweep)
            sweepNormalRows<false>(c, a, b, dpx, dpy, rows, reverse, normalAgain, endOfSubstep);
    if (!friction) return;
    for (int sweep = 1; sweep < kMaxFrictionSweeps; ++sweep) {
        FloatW load[4];
        for (int k = 0; k < c.pointCount; ++k) load[k] = c.points[k].normalImpulse;
        solveFriction(c, a, b, load, again);
        if (anyNormalAgain) sweepNormalRows<false>(c, a, b, dpx, dpy, rows, reverse, normalAgain, endOfSubstep);
    }
}

ANYPHYS_KERNEL void solveImpl(PlanarContact* contacts, PlanarWarmStart* warm, int count, SolverState* states,
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
        if (i + kRecordsAhead < count) {  // as the 3D passes do (prefetch.hpp)
            prefetchStates(states, contacts[i + kRecordsAhead].bodyA, contacts[i + kRecordsAhead].bodyB, sizeof(SolverState));
            if (params.prefetchRecords) prefetchBytes<true>(&contacts[i + kRecordsAhead], sizeof(PlanarContact));
        }
        PlanarContact& c = contacts[i];
        PlanarBodyW a = gatherPlanarMotion(states, c.bodyA), b = gatherPlanarMotion(states, c.bodyB);
        const FloatW dpx = b.dpx - a.dpx, dpy = b.dpy - a.dpy;
        // A kinematic or turning body's friction arm turns with it, as in 3D (contact_solve.cpp): the pass
        // works on the turned arms and the record keeps the step's first ones.
        FrictionArms first;
        const bool turning = params.friction && c.turnsArms;
        if (turning) {
            first = {c.centerAx, c.centerAy, c.centerBx, c.centerBy};
            turnArm(c.turnArmA, a, c.centerAx, c.centerAy);
            turnArm(c.turnArmB, b, c.centerBx, c.centerBy);
        }
        // Friction first; non-penetration has the last word in each pass. Bounded as in 3D: by the
        // last normal impulses through soft rows, by the impulses rigid rows will leave (so an
        // impact gets its friction), then capped by what they left.
        FloatW rowBias[4];  // predictLoad: each point's rigidBias
        if (params.friction) {
            FloatW load[4];
            for (int k = 0; k < c.pointCount; ++k) {
                const PlanarContactPoint& cp = c.points[k];
                load[k] = cp.normalImpulse;
                if (predictLoad) {
                    const FloatW s = separation(c, cp, a, b, dpx, dpy);
                    rowBias[k] = rigidBias(rigid, s);
                    const FloatW vn =
                        normalVelocity(a, b, c.normalX, c.normalY, cp.anchorAx, cp.anchorAy, cp.anchorBx, cp.anchorBy);
                    load[k] = max(cp.normalImpulse - cp.normalMass * (vn + rowBias[k]), zero());
                }
            }
            solveFriction(c, a, b, load, kAllLanes);
        }
        const bool softRows = useBias && params.soft;
        const PassRows rows{rigid, invH, maxPush, softRows ? c.biasRate : zero(), softRows ? c.massScale : one,
                            softRows ? c.impulseScale : zero(), predictLoad, softRows, rowBias};
        // PGS alternates the order of the points from pass to pass, as the 3D path does.
        const bool reverse = !params.soft && c.reverse;
        c.reverse = !c.reverse;
        const MaskW moved = sweepNormalRows<true>(c, a, b, dpx, dpy, rows, reverse, kAllLanes, endOfSubstep);
        if (!noLane(moved)) sweepAgain(c, a, b, dpx, dpy, rows, reverse, moved, params.friction, endOfSubstep);
        if (predictLoad && (!useBias || endOfSubstep)) clampFrictionToLoad(c, a, b);
        scatterVelocities(states, c.bodyA, c.writeA, a);
        scatterVelocities(states, c.bodyB, c.writeB, b);
        if (endOfSubstep) summarize(c, warm[i]);
        if (turning) {
            c.centerAx = first.ax;
            c.centerAy = first.ay;
            c.centerBx = first.bx;
            c.centerBy = first.by;
        }
    }
}

// As in 3D (contact_solve.cpp).
template <class NormalOf>
ANYPHYS_KERNEL PinnedLanes pinnedBodies(const PlanarContact& c, const PlanarContactCold& cold, const RestitutionRows& rows,
                                        const PlanarBodyW& a, const PlanarBodyW& b, const Vec3* supports, NormalOf normalOf) {
    const PinnedLanes supported = supportedLanes(c, supports, rows.bounced | rows.anyHeld, normalOf);
    if (supported.none()) return supported;
    FloatW speedA[4], speedB[4];
    for (int j = 0; j < c.pointCount; ++j) {
        const PlanarContactPoint& cp = c.points[j];
        speedA[j] = c.normalX * (a.vx - a.w * cp.anchorAy) + c.normalY * (a.vy + a.w * cp.anchorAx);
        speedB[j] = c.normalX * (b.vx - b.w * cp.anchorBy) + c.normalY * (b.vy + b.w * cp.anchorBx);
    }
    return pinnedLanes(supported, stoppedLanes(rows, cold, c.pointCount, speedA, speedB));
}

ANYPHYS_KERNEL SavedMasses<PlanarContact> pinMasses(PlanarContact& c, const PinnedLanes& pinned) {
    FloatW shareA[4], shareB[4];
    for (int j = 0; j < c.pointCount; ++j) {
        const PlanarContactPoint& cp = c.points[j];
        const FloatW rnA = cp.anchorAx * c.normalY - cp.anchorAy * c.normalX;
        const FloatW rnB = cp.anchorBx * c.normalY - cp.anchorBy * c.normalX;
        shareA[j] = c.invMassA + c.invIA * rnA * rnA;
        shareB[j] = c.invMassB + c.invIB * rnB * rnB;
    }
    return pinBodies(c, pinned, shareA, shareB);
}

ANYPHYS_KERNEL bool restitutionImpl(PlanarContact* contacts, PlanarContactCold* colds, int count, SolverState* states,
                                    Vec3* supports, const ContactSolveParams& params) {
    const FloatW threshold = splat(-params.restitutionThreshold);
    bool found = false;
    for (int i = 0; i < count; ++i) {
        PlanarContact& c = contacts[i];
        PlanarContactCold& cold = colds[i];
        const RestitutionRows rows = restitutionRows(c, cold, states, threshold);
        if (rows.none()) continue;
        found = true;
        markInBounce(states, c.bodyA, c.writeA, c.bodyB, c.writeB, rows.bounced);
        PlanarBodyW a = gatherPlanarVelocities(states, c.bodyA), b = gatherPlanarVelocities(states, c.bodyB);
        const auto normalOf = [&c](int lane) { return Vec3(c.normalX[lane], c.normalY[lane], 0.0); };  // as in 3D
        const PinnedLanes pinned = pinnedBodies(c, cold, rows, a, b, supports, normalOf);
        const bool pinning = !pinned.none();
        SavedMasses<PlanarContact> saved{};
        if (pinning) saved = pinMasses(c, pinned);
        FloatW load[4];
        // Friction through the whole impact, the bounce included, in every pass (as in 3D).
        const int passes = noLane(rows.bounced) ? 1 : kRestitutionPasses;  // as in 3D
        const RestitutionRows later = rowsOfLanes(rows, rows.bounced);
        for (int pass = 0; pass < passes; ++pass) {
            for (int j = 0; j < c.pointCount; ++j) {
                PlanarContactPoint& cp = c.points[j];
                const FloatW vn = normalVelocity(a, b, c.normalX, c.normalY, cp.anchorAx, cp.anchorAy, cp.anchorBx, cp.anchorBy);
                const FloatW applied = restitutionRowImpulse(pass == 0 ? rows : later, j, cp, cold, vn);
                load[j] = cp.normalImpulse;
                applyImpulse(a, b, c, cp.anchorAx, cp.anchorAy, cp.anchorBx, cp.anchorBy, applied * c.normalX,
                             applied * c.normalY);
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
ANYPHYS_AVX2 void summarizeAvx2(const PlanarContact* c, PlanarWarmStart* w, int n) { summarizeImpl(c, w, n); }
ANYPHYS_AVX2 void warmStartAvx2(const PlanarWarmStart* w, int n, SolverState* s) { warmStartImpl(w, n, s); }
ANYPHYS_AVX2 void solveAvx2(PlanarContact* c, PlanarWarmStart* w, int n, SolverState* s, const ContactSolveParams& p,
                            bool bias, bool end) {
    solveImpl(c, w, n, s, p, bias, end);
}
ANYPHYS_AVX2 bool restitutionAvx2(PlanarContact* c, PlanarContactCold* cold, int n, SolverState* s, Vec3* supports,
                                   const ContactSolveParams& p) {
    return restitutionImpl(c, cold, n, s, supports, p);
}
#endif

void summarizeBase(const PlanarContact* c, PlanarWarmStart* w, int n) { summarizeImpl(c, w, n); }
void warmStartBase(const PlanarWarmStart* w, int n, SolverState* s) { warmStartImpl(w, n, s); }
void solveBase(PlanarContact* c, PlanarWarmStart* w, int n, SolverState* s, const ContactSolveParams& p, bool bias, bool end) {
    solveImpl(c, w, n, s, p, bias, end);
}
bool restitutionBase(PlanarContact* c, PlanarContactCold* cold, int n, SolverState* s, Vec3* supports,
                     const ContactSolveParams& p) {
    return restitutionImpl(c, cold, n, s, supports, p);
}

}  // namespace

void summarizePlanarImpulses(const PlanarContact* contacts, PlanarWarmStart* warm, int count) {
#if ANYPHYS_HAS_AVX2_KERNELS
    if (contactKernelsUseAvx2()) return summarizeAvx2(contacts, warm, count);
#endif
    summarizeBase(contacts, warm, count);
}

void warmStartPlanarContacts(const PlanarWarmStart* warm, int count, SolverState* states) {
#if ANYPHYS_HAS_AVX2_KERNELS
    if (contactKernelsUseAvx2()) return warmStartAvx2(warm, count, states);
#endif
    warmStartBase(warm, count, states);
}

void solvePlanarContacts(PlanarContact* contacts, PlanarWarmStart* warm, int count, SolverState* states,
                         const ContactSolveParams& params, bool useBias, bool endOfSubstep) {
#if ANYPHYS_HAS_AVX2_KERNELS
    if (contactKernelsUseAvx2()) return solveAvx2(contacts, warm, count, states, params, useBias, endOfSubstep);
#endif
    solveBase(contacts, warm, count, states, params, useBias, endOfSubstep);
}

bool applyPlanarRestitution(PlanarContact* contacts, PlanarContactCold* cold, int count, SolverState* states,
                            Vec3* supports, const ContactSolveParams& params) {
#if ANYPHYS_HAS_AVX2_KERNELS
    if (contactKernelsUseAvx2()) return restitutionAvx2(contacts, cold, count, states, supports, params);
#endif
    return restitutionBase(contacts, cold, count, states, supports, params);
}

}  // namespace anyphys::native

#include "solver/body_integration.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "anyphys/peers/gyroscopic.hpp"
#include "solver/contact_constraint.hpp"
#include "solver/isa_kernels.hpp"
#include "solver/prefetch.hpp"
#include "solver/state_runs.hpp"
#include "solver/wide.hpp"

namespace anyphys::native {

namespace {

// The turn of a substep, written once for one body (Q = QuatD) and for a lane each (Q = wide::QuatW)
// with the same operations in the same order, so both give the same bits. (Templates take the
// quaternion type: the wide scalar's alignment attribute would be dropped from a template argument.)
struct QuatD {
    double w, x, y, z;
};
template <class Q>
using Part = decltype(Q::w);  // double, or a lane of each body

/// Largest |r|^2 of a turn the series serves: a half angle under 1e-2.
constexpr double kSeriesReach = 4e-4;

/// Rotation by the vector r for |r|^2 < kSeriesReach, from |r|^2 alone: series of cos(half) and
/// sin(half) / |r| to the 1e-17 level, no root. Constants are multiplied: the compiler keeps a
/// division by 12 a division.
template <class Q>
[[gnu::always_inline]] inline Q smallTurn(Part<Q> rx, Part<Q> ry, Part<Q> rz, Part<Q> angleSquared) {
    using T = Part<Q>;
    const T h2 = 0.25 * angleSquared;
    const T c = 1.0 - h2 * 0.5 * (1.0 - h2 * (1.0 / 12.0) * (1.0 - h2 * (1.0 / 30.0)));
    const T s = 0.5 * (1.0 - h2 * (1.0 / 6.0) * (1.0 - h2 * (1.0 / 20.0)));
    return {c, s * rx, s * ry, s * rz};
}

template <class Q>
[[gnu::always_inline]] inline Q product(const Q& a, const Q& b) {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

template <class Q>
[[gnu::always_inline]] inline Part<Q> squaredNorm(const Q& q) {
    return q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
}

/// The product of two unit quaternions is unit to rounding: one Newton step towards
/// 1 / sqrt(n2) restores it to rounding too (its error is quadratic in n2 - 1), with no root or
/// division. Farther off than kNewtonReach the caller normalises in full.
constexpr double kNewtonReach = 1e-6;

template <class Q>
[[gnu::always_inline]] inline Q scaled(const Q& q, Part<Q> scale) {
    return {scale * q.w, scale * q.x, scale * q.y, scale * q.z};
}

QuatD renormalizedProduct(const QuatD& q) {
    const double n2 = squaredNorm(q);
    if (std::abs(n2 - 1.0) > kNewtonReach) return scaled(q, 1.0 / std::sqrt(n2));
    return scaled(q, 1.5 - 0.5 * n2);
}

/// dq's turn about Z as (cos, sin): dq = (cos t/2, 0, 0, sin t/2) gives cos t = 1 - 2 z^2,
/// sin t = 2 w z (planar worlds' contact passes read them).
template <class Q>
[[gnu::always_inline]] inline void setTurn(Part<Q>& cosine, Part<Q>& sine, const Q& dq) {
    cosine = 1.0 - 2.0 * dq.z * dq.z;
    sine = 2.0 * dq.w * dq.z;
}

/// Lane k holds the state s + k.
constexpr auto kConsecutive = [] {
    std::array<std::int32_t, wide::kLanes> index{};
    for (int k = 0; k < wide::kLanes; ++k) index[static_cast<std::size_t>(k)] = k;
    return index;
}();
constexpr auto kEveryLane = [] {
    std::array<bool, wide::kLanes> all{};
    all.fill(true);
    return all;
}();

/// The runs at `offset` of the kLanes states from `s`, as four fields of every lane.
[[gnu::always_inline]] inline void loadLanes(const SolverState* s, std::size_t offset, wide::FloatW& a, wide::FloatW& b,
                                             wide::FloatW& c, wide::FloatW& d) {
    wide::gatherRuns(s, kConsecutive.data(), offset, a, b, c, d);
}

[[gnu::always_inline]] inline void storeLanes(SolverState* s, std::size_t offset, wide::FloatW a, wide::FloatW b,
                                              wide::FloatW c, wide::FloatW d) {
    wide::scatterRuns(s, kConsecutive.data(), kEveryLane.data(), offset, 4 * sizeof(double), a, b, c, d);
}

/// integratePositions for the kLanes states from `s`; false, with nothing written, when a lane
/// turns too far for the series or needs a full normalisation (the caller does those one by one).
[[gnu::always_inline]] inline bool integrateLanePositions(SolverState* s, double h) {
    using namespace wide;
    FloatW wx, wy, wz, vx, vy, vz, cosine, sine, px, py, pz, qw, qx, qy, qz, inBounce;
    loadLanes(s, 0, wx, wy, wz, vx);
    loadLanes(s, 4 * kDouble, vy, vz, cosine, sine);
    loadLanes(s, 8 * kDouble, px, py, pz, qw);
    loadLanes(s, 12 * kDouble, qx, qy, qz, inBounce);
    const FloatW rx = h * wx, ry = h * wy, rz = h * wz;
    const FloatW angleSquared = rx * rx + ry * ry + rz * rz;
    if (!noLane(angleSquared >= kSeriesReach)) return false;
    const QuatW dq = product(smallTurn<QuatW>(rx, ry, rz, angleSquared), QuatW{qw, qx, qy, qz});
    const FloatW n2 = squaredNorm(dq);
    const FloatW offUnit = n2 - 1.0;
    if (!noLane(offUnit > kNewtonReach) || !noLane(offUnit < -kNewtonReach)) return false;
    const QuatW unit = scaled(dq, 1.5 - 0.5 * n2);
    setTurn(cosine, sine, unit);
    px = px + h * vx, py = py + h * vy, pz = pz + h * vz;
    storeLanes(s, 4 * kDouble, vy, vz, cosine, sine);
    storeLanes(s, 8 * kDouble, px, py, pz, unit.w);
    storeLanes(s, 12 * kDouble, unit.x, unit.y, unit.z, inBounce);
    return true;
}

}  // namespace

Quat rotationFromVector(const Vec3& r) {
    const double angleSquared = r.x() * r.x() + r.y() * r.y() + r.z() * r.z();
    // A resting body turns by micro-radians per substep: the series needs no root, where the
    // library sin / cos, or even the root and the division, took more than the rest of its
    // integration (perf: displaceBody was 10 % of the 1 000-box drop).
    if (angleSquared < kSeriesReach) {
        const QuatD q = smallTurn<QuatD>(r.x(), r.y(), r.z(), angleSquared);
        return Quat(q.w, q.x, q.y, q.z);
    }
    const double angle = std::sqrt(angleSquared);
    const double s = std::sin(0.5 * angle) / angle;
    return Quat(std::cos(0.5 * angle), s * r.x(), s * r.y(), s * r.z());
}

Quat renormalized(const Quat& q) {
    const QuatD unit = renormalizedProduct({q.w(), q.x(), q.y(), q.z()});
    return Quat(unit.w, unit.x, unit.y, unit.z);
}

void integrateVelocities(const SolverBody* bodies, SolverState* states, int begin, int end, double h) {
    constexpr int kBodiesAhead = 8;  // about as far ahead as kRecordsAhead in the contact passes
    for (int i = begin; i < end; ++i) {
        if (i + kBodiesAhead < end) {
            prefetchBytes(&bodies[i + kBodiesAhead], offsetof(SolverBody, invMass));  // what this loop reads
            prefetchBytes<true>(&states[i + kBodiesAhead], kCacheLine);              // v and w
        }
        const SolverBody& b = bodies[i];
        if (!b.dynamic) continue;
        SolverState& s = states[i];
        Vec3 v(s.v[0], s.v[1], s.v[2]), w(s.w[0], s.w[1], s.w[2]);
        // Damping in two halves around the forces (Strang splitting): exact decay with no other
        // force, and a terminal speed a / c to second order in c h, where one whole factor after
        // (or before) the forces is off by c h / 2 either way.
        v *= b.linearHalfDampingFactor;
        w *= b.angularHalfDampingFactor;
        v += h * b.linearAcceleration;
        w += h * b.angularAcceleration;
        if (b.gyroscopic != GyroscopicMode::None) {
            const Quat q = (Quat(s.dq[0], s.dq[1], s.dq[2], s.dq[3]) * b.orientation0).normalized();
            if (b.gyroscopic == GyroscopicMode::Implicit)
                w = gyroscopic::solveImplicit(w, q, b.inertia, h);
            else
                w += h * gyroscopic::acceleration(w, q, b.inertia);
        }
        v *= b.linearHalfDampingFactor;
        w *= b.angularHalfDampingFactor;
        for (int k = 0; k < 3; ++k) {
            s.v[k] = v[k];
            s.w[k] = w[k];
        }
    }
}

void displaceBody(SolverState& s, const Vec3& move, const Vec3& turn) {
    for (int k = 0; k < 3; ++k) s.dp[k] += move[k];
    const Quat r = rotationFromVector(turn);
    const QuatD dq = renormalizedProduct(product(QuatD{r.w(), r.x(), r.y(), r.z()}, QuatD{s.dq[0], s.dq[1], s.dq[2], s.dq[3]}));
    s.dq[0] = dq.w;
    s.dq[1] = dq.x;
    s.dq[2] = dq.y;
    s.dq[3] = dq.z;
    setTurn(s.turn[0], s.turn[1], dq);
}

namespace {

void integrateOnePosition(SolverState& s, double h) {
    displaceBody(s, h * Vec3(s.v[0], s.v[1], s.v[2]), h * Vec3(s.w[0], s.w[1], s.w[2]));
}

/// kLanes bodies at a time where the series and the Newton step serve them all (every resting or
/// slowly turning body): the same operations, so the same bits, as one at a time. Inlined into
/// each instruction set's entry point: built for SSE2, the lanes' vectors went through the
/// stack and the pass took longer than one body at a time.
ANYPHYS_KERNEL void integratePositionsImpl(SolverState* states, int begin, int end, double h) {
    int i = begin;
    for (; i + wide::kLanes <= end; i += wide::kLanes)
        if (!integrateLanePositions(states + i, h))
            for (int k = i; k < i + wide::kLanes; ++k) integrateOnePosition(states[k], h);
    for (; i < end; ++i) integrateOnePosition(states[i], h);
}

#if ANYPHYS_HAS_AVX2_KERNELS
ANYPHYS_AVX2 void integratePositionsAvx2(SolverState* states, int begin, int end, double h) {
    integratePositionsImpl(states, begin, end, h);
}
#endif

void integratePositionsBase(SolverState* states, int begin, int end, double h) {
    integratePositionsImpl(states, begin, end, h);
}

}  // namespace

void integratePositions(SolverState* states, int begin, int end, double h) {
#if ANYPHYS_HAS_AVX2_KERNELS
    // The contact kernels' choice (the CPU has AVX2 and no one turned it off): both give the same bits.
    if (contactKernelsUseAvx2()) return integratePositionsAvx2(states, begin, end, h);
#endif
    integratePositionsBase(states, begin, end, h);
}

}  // namespace anyphys::native

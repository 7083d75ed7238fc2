#pragma once
// Eight lanes of doubles, the unit of the wide contact solver: each lane holds one constraint of
// a graph colour, so the eight never share a dynamic body. A wide value is two halves of four on
// the compiler's vector extension, each one AVX register where the target has AVX and two SSE2
// registers otherwise; the lane count stays eight either way, so every target groups constraints
// alike. Why two halves: a pass is long chains of dependent arithmetic (each point's impulse moves
// the velocities the next point reads), and one record of four lanes left the core waiting on
// them (about one instruction a cycle on the 1 000-box drop); the halves are independent, so each
// step of a chain has two operations to overlap. A lane computes what it would alone (a record's
// decisions are per lane), so the lane count changes the speed, not the result.
// Only +, -, *, / and sqrt are used (no fused multiply-add): results are the same bits on every
// x86-64 target and match the scalar code lane by lane.
#include <cmath>
#include <cstdint>

namespace anyphys::native::wide {

inline constexpr int kLanes = 8;

// Aligned to 32 bytes explicitly: without AVX the compiler would align these to 16 only, and
// the AVX2 kernels' aligned loads would fault on data laid out by the baseline code.
/// Four doubles: one AVX register (two SSE2 ones); half a wide value, or a run of one body's
/// SolverState (state_runs.hpp).
using Run4 = double __attribute__((vector_size(32), aligned(32)));
using MaskRun = std::int64_t __attribute__((vector_size(32), aligned(32)));
// A lane of a wide value, reached through its halves' storage (vector types alias their elements).
using LaneDouble = double __attribute__((may_alias));
using LaneMask = std::int64_t __attribute__((may_alias));

// Every function here is always inlined: the kernels are built once per instruction set
// (contact_solve.cpp), and an inlined body takes its caller's instructions.
#define ANYPHYS_WIDE [[gnu::always_inline]] inline

/// Eight lanes: lanes 0 to 3 in `lo`, 4 to 7 in `hi`.
struct FloatW {
    Run4 lo, hi;
    ANYPHYS_WIDE double operator[](int k) const { return reinterpret_cast<const LaneDouble*>(this)[k]; }
    ANYPHYS_WIDE LaneDouble& operator[](int k) { return reinterpret_cast<LaneDouble*>(this)[k]; }
};
static_assert(sizeof(FloatW) == kLanes * sizeof(double), "FloatW's halves are its lanes");
/// All bits set in a lane where true.
struct MaskW {
    MaskRun lo, hi;
    ANYPHYS_WIDE std::int64_t operator[](int k) const { return reinterpret_cast<const LaneMask*>(this)[k]; }
    ANYPHYS_WIDE LaneMask& operator[](int k) { return reinterpret_cast<LaneMask*>(this)[k]; }
};

// The operators take their values by value: by const reference, the sanitizer build (-O1) kept
// every temporary in memory and checked it at each use, and its tests ran four to eight times
// longer. All are always inlined, so the release code is the same either way.
#define ANYPHYS_WIDE_ARITHMETIC(op)                                                                          \
    ANYPHYS_WIDE FloatW operator op(FloatW a, FloatW b) { return {a.lo op b.lo, a.hi op b.hi}; } \
    ANYPHYS_WIDE FloatW operator op(FloatW a, double b) { return {a.lo op b, a.hi op b}; }       \
    ANYPHYS_WIDE FloatW operator op(double a, FloatW b) { return {a op b.lo, a op b.hi}; }       \
    ANYPHYS_WIDE FloatW& operator op##=(FloatW& a, FloatW b) { return a = a op b; }
ANYPHYS_WIDE_ARITHMETIC(+)
ANYPHYS_WIDE_ARITHMETIC(-)
ANYPHYS_WIDE_ARITHMETIC(*)
ANYPHYS_WIDE_ARITHMETIC(/)
#undef ANYPHYS_WIDE_ARITHMETIC
ANYPHYS_WIDE FloatW operator-(FloatW a) { return {-a.lo, -a.hi}; }

#define ANYPHYS_WIDE_COMPARISON(op)                                                                        \
    ANYPHYS_WIDE MaskW operator op(FloatW a, FloatW b) { return {a.lo op b.lo, a.hi op b.hi}; } \
    ANYPHYS_WIDE MaskW operator op(FloatW a, double b) { return {a.lo op b, a.hi op b}; }
ANYPHYS_WIDE_COMPARISON(<)
ANYPHYS_WIDE_COMPARISON(>)
ANYPHYS_WIDE_COMPARISON(<=)
ANYPHYS_WIDE_COMPARISON(>=)
ANYPHYS_WIDE_COMPARISON(==)
ANYPHYS_WIDE_COMPARISON(!=)
#undef ANYPHYS_WIDE_COMPARISON

ANYPHYS_WIDE MaskW operator&(MaskW a, MaskW b) { return {a.lo & b.lo, a.hi & b.hi}; }
ANYPHYS_WIDE MaskW operator|(MaskW a, MaskW b) { return {a.lo | b.lo, a.hi | b.hi}; }
ANYPHYS_WIDE MaskW operator~(MaskW a) { return {~a.lo, ~a.hi}; }
ANYPHYS_WIDE MaskW& operator&=(MaskW& a, MaskW b) { return a = a & b; }
ANYPHYS_WIDE MaskW& operator|=(MaskW& a, MaskW b) { return a = a | b; }

inline constexpr MaskW kAllLanes = {{-1, -1, -1, -1}, {-1, -1, -1, -1}};

ANYPHYS_WIDE FloatW splat(double x) { return {Run4{x, x, x, x}, Run4{x, x, x, x}}; }
ANYPHYS_WIDE FloatW zero() { return FloatW{}; }
/// Bitwise blend: a vector `?:` would be split into scalar compares on SSE2.
ANYPHYS_WIDE Run4 select(MaskRun mask, Run4 ifTrue, Run4 ifFalse) {
    return reinterpret_cast<Run4>((reinterpret_cast<MaskRun>(ifTrue) & mask) | (reinterpret_cast<MaskRun>(ifFalse) & ~mask));
}
ANYPHYS_WIDE FloatW select(MaskW mask, FloatW ifTrue, FloatW ifFalse) {
    return {select(mask.lo, ifTrue.lo, ifFalse.lo), select(mask.hi, ifTrue.hi, ifFalse.hi)};
}
ANYPHYS_WIDE FloatW max(FloatW a, FloatW b) { return select(a > b, a, b); }
ANYPHYS_WIDE FloatW min(FloatW a, FloatW b) { return select(a < b, a, b); }
ANYPHYS_WIDE FloatW clamp(FloatW x, FloatW lo, FloatW hi) { return max(lo, min(x, hi)); }
/// Correctly rounded in every lane (IEEE), so every instruction set agrees.
ANYPHYS_WIDE FloatW sqrt(FloatW x) {
    return {Run4{__builtin_sqrt(x.lo[0]), __builtin_sqrt(x.lo[1]), __builtin_sqrt(x.lo[2]), __builtin_sqrt(x.lo[3])},
            Run4{__builtin_sqrt(x.hi[0]), __builtin_sqrt(x.hi[1]), __builtin_sqrt(x.hi[2]), __builtin_sqrt(x.hi[3])}};
}
ANYPHYS_WIDE bool noLane(MaskW m) {
    const MaskRun any = m.lo | m.hi;
    return (any[0] | any[1] | any[2] | any[3]) == 0;
}
ANYPHYS_WIDE bool allZero(FloatW x) { return noLane(x != 0.0); }

struct Vec3W {
    FloatW x, y, z;
};

ANYPHYS_WIDE Vec3W operator+(const Vec3W& a, const Vec3W& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
ANYPHYS_WIDE Vec3W operator-(const Vec3W& a, const Vec3W& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
ANYPHYS_WIDE Vec3W operator*(FloatW s, const Vec3W& a) { return {s * a.x, s * a.y, s * a.z}; }
ANYPHYS_WIDE FloatW dot(const Vec3W& a, const Vec3W& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
ANYPHYS_WIDE Vec3W cross(const Vec3W& a, const Vec3W& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// Per-axis scale (a planar body's inverse mass is zero along Z).
ANYPHYS_WIDE Vec3W scale(const Vec3W& s, const Vec3W& a) { return {s.x * a.x, s.y * a.y, s.z * a.z}; }

/// Symmetric 3x3 matrix (world inverse inertia).
struct SymMat3W {
    FloatW xx, xy, xz, yy, yz, zz;
};

ANYPHYS_WIDE Vec3W operator*(const SymMat3W& m, const Vec3W& v) {
    return {m.xx * v.x + m.xy * v.y + m.xz * v.z, m.xy * v.x + m.yy * v.y + m.yz * v.z,
            m.xz * v.x + m.yz * v.y + m.zz * v.z};
}

/// Symmetric 2x2 matrix (the tangent-plane mass of central friction).
/// x with the lanes of `clear` set to zero.
ANYPHYS_WIDE FloatW cleared(FloatW x, MaskW clear) { return select(clear, zero(), x); }
ANYPHYS_WIDE SymMat3W cleared(const SymMat3W& m, MaskW clear) {
    return {cleared(m.xx, clear), cleared(m.xy, clear), cleared(m.xz, clear),
            cleared(m.yy, clear), cleared(m.yz, clear), cleared(m.zz, clear)};
}

struct SymMat2W {
    FloatW xx, xy, yy;
};

/// A rotation as a unit quaternion (w, x, y, z).
struct QuatW {
    FloatW w, x, y, z;
};

/// q v q*, as v + 2 w (u x v) + 2 u x (u x v) with u the vector part.
ANYPHYS_WIDE Vec3W rotate(const QuatW& q, const Vec3W& v) {
    const Vec3W u{q.x, q.y, q.z};
    const Vec3W t = cross(u, v);
    const Vec3W t2{t.x + t.x, t.y + t.y, t.z + t.z};
    return v + q.w * t2 + cross(u, t2);
}

/// Rows to columns: on return r0 holds the first element of each row given, r1 the second, ...
/// (eight shuffles; one AVX register per row, or two SSE2 registers). __builtin_shufflevector:
/// GCC (12 on) and Clang both have it.
ANYPHYS_WIDE void transpose(Run4& r0, Run4& r1, Run4& r2, Run4& r3) {
    const Run4 t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6), t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
    const Run4 t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6), t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
    r0 = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
    r1 = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    r2 = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
    r3 = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

/// Two runs' lanes side by side, and the two halves of a wide value.
ANYPHYS_WIDE FloatW join(Run4 low, Run4 high) { return {low, high}; }
ANYPHYS_WIDE Run4 lowHalf(FloatW x) { return x.lo; }
ANYPHYS_WIDE Run4 highHalf(FloatW x) { return x.hi; }

}  // namespace anyphys::native::wide

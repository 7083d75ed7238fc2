#pragma once
// Four lanes of doubles, the unit of the wide contact solver: each lane holds one constraint of
// a graph colour, so the four never share a dynamic body. Built on the compiler's vector
// extension, which becomes one AVX register where the target has AVX and two SSE2 registers
// otherwise; the lane count stays four either way, so every target groups constraints alike.
// Only +, -, *, / and sqrt are used (no fused multiply-add): results are the same bits on every
// x86-64 target and match the scalar code lane by lane.
#include <cmath>
#include <cstdint>

namespace anyphys::native::wide {

inline constexpr int kLanes = 4;

// Aligned to 32 bytes explicitly: without AVX the compiler would align these to 16 only, and
// the AVX2 kernels' aligned loads would fault on data laid out by the baseline code.
using FloatW = double __attribute__((vector_size(32), aligned(32)));
using MaskW = std::int64_t __attribute__((vector_size(32), aligned(32)));  // all bits set where true

inline constexpr MaskW kAllLanes = {-1, -1, -1, -1};

// Every function here is always inlined: the kernels are built once per instruction set
// (contact_solve.cpp), and an inlined body takes its caller's instructions.
#define ANYPHYS_WIDE [[gnu::always_inline]] inline

ANYPHYS_WIDE FloatW splat(double x) { return FloatW{x, x, x, x}; }
ANYPHYS_WIDE FloatW zero() { return FloatW{0.0, 0.0, 0.0, 0.0}; }
/// Bitwise blend: a vector `?:` would be split into scalar compares on SSE2.
ANYPHYS_WIDE FloatW select(MaskW mask, FloatW ifTrue, FloatW ifFalse) {
    return reinterpret_cast<FloatW>((reinterpret_cast<MaskW>(ifTrue) & mask) | (reinterpret_cast<MaskW>(ifFalse) & ~mask));
}
ANYPHYS_WIDE FloatW max(FloatW a, FloatW b) { return select(a > b, a, b); }
ANYPHYS_WIDE FloatW min(FloatW a, FloatW b) { return select(a < b, a, b); }
ANYPHYS_WIDE FloatW clamp(FloatW x, FloatW lo, FloatW hi) { return max(lo, min(x, hi)); }
/// Correctly rounded in every lane (IEEE), so every instruction set agrees.
ANYPHYS_WIDE FloatW sqrt(FloatW x) {
    return FloatW{__builtin_sqrt(x[0]), __builtin_sqrt(x[1]), __builtin_sqrt(x[2]), __builtin_sqrt(x[3])};
}
ANYPHYS_WIDE bool allZero(FloatW x) { return x[0] == 0.0 && x[1] == 0.0 && x[2] == 0.0 && x[3] == 0.0; }
ANYPHYS_WIDE bool noLane(MaskW m) { return (m[0] | m[1] | m[2] | m[3]) == 0; }

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
ANYPHYS_WIDE void transpose(FloatW& r0, FloatW& r1, FloatW& r2, FloatW& r3) {
    const FloatW t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6), t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
    const FloatW t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6), t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
    r0 = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
    r1 = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    r2 = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
    r3 = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

}  // namespace anyphys::native::wide

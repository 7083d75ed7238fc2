#pragma once
// Conversions between anyphys value types and ODE's arrays. ODE must be built in double
// precision: the layer's state is double, and a float engine would round every exchange.
#include <ode/ode.h>

#include <type_traits>

#include "anyphys/math.hpp"

static_assert(std::is_same_v<dReal, double>, "the anyphys ODE backend needs ODE built in double precision");

namespace anyphys::ode {

inline Vec3 toVec3(const dReal* v) { return Vec3(v[0], v[1], v[2]); }
/// ODE quaternions are (w, x, y, z).
inline Quat toQuat(const dReal* q) { return Quat(q[0], q[1], q[2], q[3]); }

inline void toOde(const Quat& q, dQuaternion out) {
    out[0] = q.w();
    out[1] = q.x();
    out[2] = q.y();
    out[3] = q.z();
}

/// ODE rotation matrices are 3x4, row-major, the fourth column unused.
inline Mat3 toMat3(const dReal* r) {
    Mat3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m(i, j) = r[i * 4 + j];
    return m;
}

inline void toOde(const Mat3& m, dMatrix3 out) {
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) out[i * 4 + j] = m(i, j);
        out[i * 4 + 3] = 0.0;
    }
}

}  // namespace anyphys::ode

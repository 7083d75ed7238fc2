#pragma once
// Conversions between the layer's double-precision math and Bullet's btScalar.
//
// Precision: the backend links Debian's double build (`bullet-float64`, btScalar = double) by
// default, so results agree with the other backends to rounding. Built against the float build
// (ANYPHYS_BULLET_MODULE=bullet) every state the engine integrates carries float rounding
// (relative 6e-8: about 1e-6 m at 10 m from the origin), and three analytic contract tests miss
// their 1e-9 bounds. Values the engine did not change since the layer set them are reported
// exactly (BulletBodyPeer keeps the double it was given next to the btScalar it became).
#include <btBulletDynamicsCommon.h>

#include "anyphys/math.hpp"

namespace anyphys::bullet {

inline btVector3 toBt(const Vec3& v) {
    return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z())};
}
inline btQuaternion toBt(const Quat& q) {
    return {static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()), static_cast<btScalar>(q.z()),
            static_cast<btScalar>(q.w())};
}
inline btTransform toBt(const Transform& t) { return btTransform(toBt(t.orientation), toBt(t.position)); }
inline btTransform toBt(const Vec3& p, const Quat& q) { return btTransform(toBt(q), toBt(p)); }

inline Vec3 fromBt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
inline Quat fromBt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }

inline bool sameBt(const btVector3& a, const btVector3& b) { return a.x() == b.x() && a.y() == b.y() && a.z() == b.z(); }
inline bool sameBt(const btQuaternion& a, const btQuaternion& b) {
    return a.x() == b.x() && a.y() == b.y() && a.z() == b.z() && a.w() == b.w();
}

}  // namespace anyphys::bullet

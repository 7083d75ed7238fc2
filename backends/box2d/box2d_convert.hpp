#pragma once
// Conversions between the layer's 3D double-precision values and Box2D's 2D single-precision
// ones, and the constants every Box2D file shares.
#include <box2d/box2d.h>

#include <cmath>

#include "anyphys/math.hpp"

namespace anyphys::box2d {

/// Every fixture is half a b2_linearSlop larger than the shape it stands for. Box2D holds
/// resting contacts at b2_linearSlop of overlap (its position solver stops there), so with this
/// skin two resting shapes have their true surfaces just touching, and a stack does not sink by
/// a slop per box. Contact depths are reported against the true surfaces (see kPairSkin).
inline constexpr double kSkin = 0.5 * b2_linearSlop;
/// Skin of a pair: what Box2D's separation undercounts the true separation by.
inline constexpr double kPairSkin = 2.0 * kSkin;
/// A plane is a run of edges along its line (box2d_shapes.cpp): the middle one reaches this far
/// either side of the point nearest the origin, and each next one is twice as long as the last,
/// so an edge's ends are never much farther from the origin than the bodies on it (Box2D's float
/// edge test measures from them), and the run covers every coordinate a world admits.
inline constexpr double kPlaneMiddleHalfLength = 1000.0;

inline b2Vec2 toB2(const Vec3& v) { return b2Vec2(static_cast<float>(v.x()), static_cast<float>(v.y())); }
inline Vec3 fromB2(const b2Vec2& v, double z = 0.0) { return Vec3(v.x, v.y, z); }

/// The angle of the rotation's twist about Z (swing-twist decomposition): exact for rotations
/// about Z, the nearest planar angle otherwise.
inline double twistAngle(const Quat& q) { return 2.0 * std::atan2(q.z(), q.w()); }
inline Quat aboutZ(double angle) { return Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())); }

/// How a peer frame (centre of mass, principal axes) sits on the planar Box2D body that carries
/// it. In a planar scene the layer's principal axes are usually the body axes turned about Z,
/// and then `rotation` is the identity and `height` zero; but the eigen decomposition may order
/// the axes so that the peer frame is not a rotation about Z, and a convex hull uneven in z puts
/// the centre of mass off the plane. Both are kept as a constant offset so states round-trip.
struct Embedding {
    Quat rotation = Quat::Identity();  ///< peer frame orientation in the Box2D body frame
    double height = 0.0;               ///< m, z of the peer frame origin (constant)

    /// The Box2D angle and the offset for a peer pose.
    static Embedding of(const Transform& peerPose, double& angle) {
        angle = twistAngle(peerPose.orientation);
        Embedding e;
        e.rotation = (aboutZ(-angle) * peerPose.orientation).normalized();
        if (std::abs(e.rotation.x()) < 1e-12 && std::abs(e.rotation.y()) < 1e-12 && std::abs(e.rotation.z()) < 1e-12)
            e.rotation = Quat::Identity();
        e.height = peerPose.position.z();
        return e;
    }
    bool planar() const { return rotation.isApprox(Quat::Identity(), 1e-12); }
    /// A pose given in the peer frame, expressed in the Box2D body frame.
    Transform toBody(const Transform& local) const {
        return {Vec3(0, 0, height) + rotation * local.position, rotation * local.orientation};
    }
    /// The peer orientation for a Box2D angle, and back.
    Quat peerOrientation(double angle) const { return (aboutZ(angle) * rotation).normalized(); }
    double bodyAngle(const Quat& peerOrientation) const { return twistAngle(peerOrientation * rotation.conjugate()); }
};

}  // namespace anyphys::box2d

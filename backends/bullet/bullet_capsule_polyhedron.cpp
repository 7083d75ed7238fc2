#include "bullet_capsule_polyhedron.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>
#include <BulletCollision/CollisionShapes/btPolyhedralConvexShape.h>

#include <array>
#include <new>

#include "bullet_carry_impulses.hpp"

namespace anyphys::bullet {
namespace {

// The most a capsule reaching over a face's edge may lean towards the face (the sine of its angle
// to it): the point over the edge, between the ends, is measured straight down from the core,
// r (1/cos - 1) short of its surface when leaning, 0.25 mm for a 0.2 m radius at this limit.
// Leaning more (a capsule tipping off an edge), it goes to Bullet's test, whose point follows the
// edge. Over the face whole, a capsule's lowest points are its ends' at any lean.
constexpr btScalar kMostLean = 0.05;

// A hull's neighbouring face closer to this one's direction than twice the most lean (the cosine
// of that angle, 1 - 2 sin^2): a capsule leaning over the edge between them may touch it with the
// end it holds beyond the edge, which the line over this face misses. A box's neighbours stand
// square to its faces.
constexpr btScalar kNearlyInLine = 1 - 2 * kMostLean * kMostLean;

// The face of a box the capsule's centre lies farthest outside of, in the box's frame.
class BoxFace {
public:
    BoxFace(const btBoxShape& box, const btVector3& centre) : half_(box.getHalfExtentsWithMargin()) {
        for (int j = 1; j < 3; ++j)
            if (btFabs(centre[j]) - half_[j] > btFabs(centre[axis_]) - half_[axis_]) axis_ = j;
        side_ = centre[axis_] < 0 ? btScalar(-1) : btScalar(1);
        normal_[axis_] = side_;
    }

    const btVector3& normal() const { return normal_; }  // outward
    btScalar height(const btVector3& p) const { return side_ * p[axis_] - half_[axis_]; }  // above the face's plane
    btVector3 onFace(const btVector3& p) const {  // below p on the face's plane
        btVector3 q = p;
        q[axis_] = side_ * half_[axis_];
        return q;
    }
    bool clearBeyondEdge(const btVector3&, btScalar) const { return true; }

    // The segment e0 + t (e1 - e0), t in [0, 1], clipped to |x_j| <= half_j on the two other axes:
    // false when no part of it lies over the face.
    bool clip(const btVector3& e0, const btVector3& e1, btScalar& t0, btScalar& t1) const {
        t0 = 0;
        t1 = 1;
        const btVector3 along = e1 - e0;
        for (int j = 0; j < 3; ++j) {
            if (j == axis_) continue;
            if (btFabs(along[j]) < SIMD_EPSILON) {
                if (btFabs(e0[j]) > half_[j]) return false;
                continue;
            }
            btScalar enter = (-half_[j] - e0[j]) / along[j];
            btScalar leave = (half_[j] - e0[j]) / along[j];
            if (enter > leave) btSwap(enter, leave);
            t0 = btMax(t0, enter);
            t1 = btMin(t1, leave);
        }
        return t0 <= t1;
    }

private:
    btVector3 half_;
    btVector3 normal_{0, 0, 0};
    int axis_ = 0;
    btScalar side_ = 1;
};

// The face of a hull the capsule's centre lies farthest outside of, in the hull's frame: a face
// of the shrunk polyhedron, its plane pushed out by the margin. Its polygon's vertices are in
// order around it (Bullet merges coplanar triangles into one polygon: a cube hull has 6 faces).
class HullFace {
public:
    HullFace(const btConvexPolyhedron& hull, btScalar margin, const btVector3& centre) : hull_(hull), margin_(margin) {
        btScalar farthest = -BT_LARGE_FLOAT;
        for (int f = 0; f < hull.m_faces.size(); ++f) {
            const btScalar h = planeHeight(f, centre);
            if (h > farthest) {
                farthest = h;
                face_ = f;
            }
        }
        const btScalar* plane = hull.m_faces[face_].m_plane;
        normal_.setValue(plane[0], plane[1], plane[2]);
    }

    const btVector3& normal() const { return normal_; }
    btScalar height(const btVector3& p) const { return planeHeight(face_, p); }
    btVector3 onFace(const btVector3& p) const { return p - height(p) * normal_; }

    // Whether `end`, beyond this face's edge, lies `reach` or more above every face nearly in line
    // with this one.
    bool clearBeyondEdge(const btVector3& end, btScalar reach) const {
        for (int f = 0; f < hull_.m_faces.size(); ++f) {
            if (f == face_) continue;
            const btScalar* plane = hull_.m_faces[f].m_plane;
            if (normal_.dot(btVector3(plane[0], plane[1], plane[2])) > kNearlyInLine && planeHeight(f, end) < reach) return false;
        }
        return true;
    }

    // The segment e0 + t (e1 - e0), t in [0, 1], clipped to the face's polygon by the plane
    // through each edge square to the face: false when no part of it lies over the face.
    bool clip(const btVector3& e0, const btVector3& e1, btScalar& t0, btScalar& t1) const {
        const btAlignedObjectArray<int>& corners = hull_.m_faces[face_].m_indices;
        const int n = corners.size();
        if (n < 3) return false;
        btVector3 middle(0, 0, 0);  // inside the convex polygon: tells each edge's inward side
        for (int k = 0; k < n; ++k) middle += hull_.m_vertices[corners[k]];
        middle /= btScalar(n);
        t0 = 0;
        t1 = 1;
        const btVector3 along = e1 - e0;
        for (int k = 0; k < n; ++k) {
            const btVector3& a = hull_.m_vertices[corners[k]];
            btVector3 inward = normal_.cross(hull_.m_vertices[corners[(k + 1) % n]] - a);
            if (inward.dot(middle - a) < 0) inward = -inward;
            const btScalar start = inward.dot(e0 - a), rate = inward.dot(along);
            if (rate == 0) {
                if (start < 0) return false;
                continue;
            }
            if (rate > 0)
                t0 = btMax(t0, -start / rate);
            else
                t1 = btMin(t1, -start / rate);
        }
        return t0 <= t1;
    }

private:
    btScalar planeHeight(int f, const btVector3& p) const {  // above face f's plane, margin included
        const btScalar* plane = hull_.m_faces[f].m_plane;
        return btVector3(plane[0], plane[1], plane[2]).dot(p) + plane[3] - margin_;
    }

    const btConvexPolyhedron& hull_;
    btScalar margin_;
    int face_ = 0;
    btVector3 normal_;
};

// Where a capsule, its core from e0 to e1 and its centre in the shape's frame, lies over `face`:
// the points on the face under both ends of the part of its core over the face, those within
// `threshold`, and their distances. -1 when it does not lie over the face (or its core goes
// through it); else the number of points, 0 to 2.
struct Line {
    std::array<btVector3, 2> onFace;
    std::array<btScalar, 2> distance;
};
template <class Face>
int lineOverFace(const Face& face, const btVector3& e0, const btVector3& e1, const btVector3& centre, btScalar radius,
                 btScalar threshold, Line& line) {
    // Above the face, neither end of its core through it.
    if (face.height(centre) <= 0 || face.height(e0) <= -radius || face.height(e1) <= -radius) return -1;
    btScalar t0 = 0, t1 = 0;
    if (!face.clip(e0, e1, t0, t1)) return -1;
    // Both ends over the face: the face is the nearest part of the shape to each, and the ends'
    // spheres hold the capsule's lowest points however it leans, so a capsule landing on one end
    // gets the point under its other end as that end swings down. Clipped at an edge, the core
    // beyond the edge may come nearer the edge than its point over the edge: nearly parallel only.
    const bool clipped = t0 > 0 || t1 < 1;
    if (clipped && btFabs(face.normal().dot(e1 - e0)) > kMostLean * (e1 - e0).length()) return -1;
    if ((t0 > 0 && !face.clearBeyondEdge(e0, radius + threshold)) || (t1 < 1 && !face.clearBeyondEdge(e1, radius + threshold)))
        return -1;
    int count = 0;
    for (const btScalar t : {t0, t1}) {
        if (count == 1 && t1 - t0 < SIMD_EPSILON) break;  // the clipped segment is a point
        const btVector3 core = e0 + t * (e1 - e0);
        const btScalar distance = face.height(core) - radius;
        if (distance >= threshold) continue;
        // However deep its sphere, a core point above the face is nearest the point below it
        // (GJK's one deepest point would leave the other end none); through it, Bullet's test.
        if (face.height(core) <= 0) return -1;
        line.onFace[count] = face.onFace(core);
        line.distance[count] = distance;
        ++count;
    }
    return count;
}

}  // namespace

CapsulePolyhedronAlgorithm::CapsulePolyhedronAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                                                       const btCollisionObjectWrapper* body0,
                                                       const btCollisionObjectWrapper* body1, bool polyhedronFirst,
                                                       btConvexPenetrationDepthSolver* depthSolver)
    : OwnManifoldWithFallback(info, body0, body1, depthSolver), polyhedronFirst_(polyhedronFirst) {}

bool CapsulePolyhedronAlgorithm::collideOverFace(const btCollisionObjectWrapper* capsuleWrap,
                                                 const btCollisionObjectWrapper* polyhedronWrap, btManifoldResult* result) {
    const auto* capsule = static_cast<const btCapsuleShape*>(capsuleWrap->getCollisionShape());
    const btCollisionShape* shape = polyhedronWrap->getCollisionShape();
    const btTransform& pose = polyhedronWrap->getWorldTransform();
    const btTransform inShape = pose.inverseTimes(capsuleWrap->getWorldTransform());
    btVector3 halfSegment(0, 0, 0);
    halfSegment[capsule->getUpAxis()] = capsule->getHalfHeight();
    const btVector3 e0 = inShape * halfSegment, e1 = inShape * -halfSegment;
    const btVector3& centre = inShape.getOrigin();
    const btScalar radius = capsule->getRadius();
    const btScalar threshold = manifold_->getContactBreakingThreshold();

    Line line;
    int count = -1;
    btVector3 normal;
    if (shape->getShapeType() == BOX_SHAPE_PROXYTYPE) {
        const BoxFace face(*static_cast<const btBoxShape*>(shape), centre);
        count = lineOverFace(face, e0, e1, centre, radius, threshold, line);
        normal = face.normal();
    } else {  // a hull (registered for CONVEX_HULL_SHAPE_PROXYTYPE)
        const auto* hull = static_cast<const btPolyhedralConvexShape*>(shape);
        const btConvexPolyhedron* polyhedron = hull->getConvexPolyhedron();
        if (!polyhedron || polyhedron->m_faces.size() == 0) return false;  // no faces made: Bullet's test
        const HullFace face(*polyhedron, hull->getMargin(), centre);
        count = lineOverFace(face, e0, e1, centre, radius, threshold, line);
        normal = face.normal();
    }
    if (count < 0) return false;
    const btVector3 worldNormal = pose.getBasis() * normal;  // from the box or hull to the capsule

    result->setPersistentManifold(manifold_);
    std::array<btManifoldPoint, MANIFOLD_CACHE_SIZE> old;
    const bool wholeLine = count == 2;
    const int oldCount = wholeLine ? manifold_->getNumContacts() : 0;
    for (int i = 0; i < oldCount; ++i) old[i] = manifold_->getContactPoint(i);
    if (wholeLine) manifold_->clearManifold();
    // In the manifold's order: the normal on the second body, pointing to the first, and the
    // point on the second body's surface.
    for (int i = 0; i < count; ++i) {
        const btVector3 onShape = pose * line.onFace[i];
        if (polyhedronFirst_)
            result->addContactPoint(-worldNormal, onShape + line.distance[i] * worldNormal, line.distance[i]);
        else
            result->addContactPoint(worldNormal, onShape, line.distance[i]);
    }
    if (oldCount > 0) carryImpulses(*manifold_, old.data(), oldCount);
    return true;
}

void CapsulePolyhedronAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                                  const btDispatcherInfo& dispatchInfo, btManifoldResult* result) {
    if (!manifold_) return;
    const btCollisionObjectWrapper* capsuleWrap = polyhedronFirst_ ? body1 : body0;
    const btCollisionObjectWrapper* polyhedronWrap = polyhedronFirst_ ? body0 : body1;
    if (!collideOverFace(capsuleWrap, polyhedronWrap, result)) fallback_->processCollision(body0, body1, dispatchInfo, result);
    result->setPersistentManifold(manifold_);
    result->refreshContactPoints();
}

btCollisionAlgorithm* CapsulePolyhedronAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                                                       const btCollisionObjectWrapper* body0,
                                                                                       const btCollisionObjectWrapper* body1) {
    return newPooledAlgorithm<CapsulePolyhedronAlgorithm>(info, body0, body1, m_swapped, &depthSolver);
}

}  // namespace anyphys::bullet

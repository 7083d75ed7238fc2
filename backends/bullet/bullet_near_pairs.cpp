// WorldPeer::reportNearPair for Bullet. Bullet keeps a pair's contact points only while they are
// within the manifold's breaking threshold, 0.02 times the shapes' angular motion disc (about
// their bounding radius): 17 mm for a box of half extent 0.5, but 2.5 mm for one of 0.05 and less
// for smaller shapes, so a small body's pair would end well inside the layer's exit band. The
// layer asks here about such a pair.
//
// Two convex shapes (or compounds of them) are measured by GJK on each pair of parts, margins
// included. Bullet's own closest-points query (contactPairTest) would clip the faces of two
// polyhedra, which sees a hull's shrunk core: a hull 9.5 mm above a box measured 10.5 mm, its
// 1 mm margin more. A plane or a mesh partner goes through that query, which is exact there.
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include "bullet_convert.hpp"
#include "bullet_world.hpp"

namespace anyphys::bullet {
namespace {

/// Appends one measured point to the body pair's report, opening the pair at its first point.
class NearPairWriter {
public:
    NearPairWriter(const BulletBodyPeer& a, const BulletBodyPeer& b, ContactReport& out) : a_(a), b_(b), out_(out) {}

    /// Whether child `childA` of A and `childB` of B may touch (sensors and filters per child).
    bool collide(int childA, int childB) const {
        const ChildSurface& sa = a_.surface(childA);
        const ChildSurface& sb = b_.surface(childB);
        return !sa.trigger && !sb.trigger && layersCollide(sa.layer, sa.mask, sb.layer, sb.mask);
    }

    /// `normal` from A to B; `distance` between the true surfaces (negative: overlapping).
    void add(const Vec3& normal, const Vec3& point, double distance) {
        if (!found) out_.addPair(a_.userData(), b_.userData(), false, normal);
        found = true;
        out_.addPoint({point, -distance, 0.0});
    }

    bool found = false;

private:
    const BulletBodyPeer& a_;
    const BulletBodyPeer& b_;
    ContactReport& out_;
};

/// Bullet's closest points within the query's threshold, for pairs with a plane or a mesh.
class NearPoints final : public btCollisionWorld::ContactResultCallback {
public:
    NearPoints(const btCollisionObject& a, NearPairWriter& writer, double reach) : a_(a), writer_(writer) {
        m_closestDistanceThreshold = static_cast<btScalar>(reach);
    }

    btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper* w0, int, int index0,
                             const btCollisionObjectWrapper*, int, int index1) override {
        if (p.getDistance() > m_closestDistanceThreshold) return 0;
        // The query may hand the bodies over in either order; the indices name compound children.
        const bool aFirst = w0->getCollisionObject() == &a_;
        if (!writer_.collide(aFirst ? index0 : index1, aFirst ? index1 : index0)) return 0;
        // Bullet's normal points from the second object to the first.
        const Vec3 firstToSecond = -fromBt(p.m_normalWorldOnB);
        const Vec3 point = 0.5 * (fromBt(p.getPositionWorldOnA()) + fromBt(p.getPositionWorldOnB()));
        writer_.add(aFirst ? firstToSecond : -firstToSecond, point, p.getDistance());
        return 0;
    }

private:
    const btCollisionObject& a_;
    NearPairWriter& writer_;
};

}  // namespace

bool BulletWorld::convexParts(const btCollisionObject& object, std::vector<ConvexPart>& parts) {
    parts.clear();
    const btCollisionShape* shape = object.getCollisionShape();
    if (shape->isConvex()) {
        parts.push_back({static_cast<const btConvexShape*>(shape), object.getWorldTransform(), 0});
        return true;
    }
    if (!shape->isCompound()) return false;
    const auto* compound = static_cast<const btCompoundShape*>(shape);
    for (int i = 0; i < compound->getNumChildShapes(); ++i) {
        const btCollisionShape* child = compound->getChildShape(i);
        if (!child->isConvex()) return false;
        parts.push_back({static_cast<const btConvexShape*>(child), object.getWorldTransform() * compound->getChildTransform(i), i});
    }
    return true;
}

bool BulletWorld::reportNearPair(BodyPeer& a, BodyPeer& b, double reach, ContactReport& out) {
    auto& bodyA = static_cast<BulletBodyPeer&>(a);
    auto& bodyB = static_cast<BulletBodyPeer&>(b);
    // The pairs the broad phase would pair (contacts on, no joint between them, layers), of
    // bodies in the world.
    btBroadphaseProxy* proxyA = bodyA.rigidBody().getBroadphaseHandle();
    btBroadphaseProxy* proxyB = bodyB.rigidBody().getBroadphaseHandle();
    if (proxyA == nullptr || proxyB == nullptr || !filter_.needBroadphaseCollision(proxyA, proxyB)) return false;
    NearPairWriter writer(bodyA, bodyB, out);
    if (!convexParts(bodyA.rigidBody(), nearPartsA_) || !convexParts(bodyB.rigidBody(), nearPartsB_)) {
        NearPoints near(bodyA.rigidBody(), writer, reach);
        world_->contactPairTest(&bodyA.rigidBody(), &bodyB.rigidBody(), near);
        return writer.found;
    }
    for (const ConvexPart& partA : nearPartsA_)
        for (const ConvexPart& partB : nearPartsB_) {
            if (!writer.collide(partA.child, partB.child)) continue;
            btVoronoiSimplexSolver simplex;
            btGjkEpaPenetrationDepthSolver penetration;  // overlapping parts: EPA's depth
            btGjkPairDetector gjk(partA.shape, partB.shape, &simplex, &penetration);
            btGjkPairDetector::ClosestPointInput input;
            input.m_transformA = partA.pose;
            input.m_transformB = partB.pose;
            btPointCollector closest;
            gjk.getClosestPoints(input, closest, nullptr);
            if (!closest.m_hasResult || closest.m_distance > reach) continue;
            // The collector's point lies on B, its normal points from B to A.
            const Vec3 normal = -fromBt(closest.m_normalOnBInWorld);
            const Vec3 onB = fromBt(closest.m_pointInWorld);
            writer.add(normal, onB - 0.5 * closest.m_distance * normal, closest.m_distance);
        }
    return writer.found;
}

}  // namespace anyphys::bullet

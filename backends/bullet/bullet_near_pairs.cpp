// WorldPeer::reportNearPair for Bullet. Bullet keeps a pair's contact points only while they are
// within the manifold's breaking threshold, 0.02 times the shapes' angular motion disc (about
// their bounding radius): 17 mm for a box of half extent 0.5, but 2.5 mm for one of 0.05 and less
// for smaller shapes, so a small body's pair would end well inside the layer's exit band. The
// layer asks here about such a pair; Bullet's own closest-points query answers it.
#include "bullet_convert.hpp"
#include "bullet_world.hpp"

namespace anyphys::bullet {
namespace {

/// The closest points of two bodies within the query's threshold (btCollisionWorld::
/// contactPairTest), between children that collide, appended to the report as one pair of A then
/// B with its normal from A to B.
class NearPoints final : public btCollisionWorld::ContactResultCallback {
public:
    NearPoints(const BulletBodyPeer& a, const BulletBodyPeer& b, double reach, ContactReport& out)
        : a_(a), b_(b), out_(out) {
        m_closestDistanceThreshold = static_cast<btScalar>(reach);
    }

    btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper* w0, int, int index0,
                             const btCollisionObjectWrapper*, int, int index1) override {
        if (p.getDistance() > m_closestDistanceThreshold) return 0;
        // The query may hand the bodies over in either order; the indices name compound children.
        const bool aFirst = w0->getCollisionObject() == &a_.rigidBody();
        const ChildSurface& sa = a_.surface(aFirst ? index0 : index1);
        const ChildSurface& sb = b_.surface(aFirst ? index1 : index0);
        if (sa.trigger || sb.trigger || !layersCollide(sa.layer, sa.mask, sb.layer, sb.mask)) return 0;
        // Bullet's normal points from the second object to the first.
        const Vec3 normalFirstToSecond = -fromBt(p.m_normalWorldOnB);
        if (!found) out_.addPair(a_.userData(), b_.userData(), false, aFirst ? normalFirstToSecond : -normalFirstToSecond);
        found = true;
        const Vec3 point = 0.5 * (fromBt(p.getPositionWorldOnA()) + fromBt(p.getPositionWorldOnB()));
        out_.addPoint({point, -static_cast<double>(p.getDistance()), 0.0});
        return 0;
    }

    bool found = false;

private:
    const BulletBodyPeer& a_;
    const BulletBodyPeer& b_;
    ContactReport& out_;
};

}  // namespace

bool BulletWorld::reportNearPair(BodyPeer& a, BodyPeer& b, double reach, ContactReport& out) {
    auto& bodyA = static_cast<BulletBodyPeer&>(a);
    auto& bodyB = static_cast<BulletBodyPeer&>(b);
    // The pairs the broad phase would pair (contacts on, no joint between them, layers), of
    // bodies in the world.
    btBroadphaseProxy* proxyA = bodyA.rigidBody().getBroadphaseHandle();
    btBroadphaseProxy* proxyB = bodyB.rigidBody().getBroadphaseHandle();
    if (proxyA == nullptr || proxyB == nullptr || !filter_.needBroadphaseCollision(proxyA, proxyB)) return false;
    NearPoints near(bodyA, bodyB, reach, out);
    world_->contactPairTest(&bodyA.rigidBody(), &bodyB.rigidBody(), near);
    return near.found;
}

}  // namespace anyphys::bullet

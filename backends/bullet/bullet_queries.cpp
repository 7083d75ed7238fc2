// Ray casts and shape overlap through Bullet's collision world, filtered like the layer wants:
// bodies on a layer in the mask, sensors skipped.
#include <algorithm>

#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include "bullet_convert.hpp"
#include "bullet_ray_round.hpp"
#include "bullet_world.hpp"

namespace anyphys::bullet {
namespace {

const BulletBodyPeer* peerOf(const btCollisionObject* object) {
    return static_cast<const BulletBodyPeer*>(object->getUserPointer());
}

bool queryable(const btBroadphaseProxy* proxy, std::uint32_t mask) {
    const BulletBodyPeer* peer = peerOf(static_cast<const btCollisionObject*>(proxy->m_clientObject));
    return peer != nullptr && !peer->trigger() && (peer->layer() & mask) != 0;
}

class RayHits final : public btCollisionWorld::RayResultCallback {
public:
    RayHits(const Vec3& origin, const Vec3& direction, double maxDistance, bool closestOnly, std::uint32_t mask)
        : origin_(origin), direction_(direction), maxDistance_(maxDistance), closestOnly_(closestOnly), mask_(mask) {}

    bool needsCollision(btBroadphaseProxy* proxy) const override { return queryable(proxy, mask_); }

    btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool normalInWorldSpace) override {
        // A compound's child (its index in m_triangleIndex) may be a sensor or off the mask.
        const int child = r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -1;
        const ChildSurface& surface = peerOf(r.m_collisionObject)->surface(child);
        if (surface.trigger || (surface.layer & mask_) == 0) return m_closestHitFraction;
        if (startsBelow(*r.m_collisionObject)) return m_closestHitFraction;
        const btVector3 n = normalInWorldSpace ? r.m_hitNormalLocal
                                               : r.m_collisionObject->getWorldTransform().getBasis() * r.m_hitNormalLocal;
        double distance = static_cast<double>(r.m_hitFraction) * maxDistance_;
        Vec3 normal = fromBt(n).normalized();
        btScalar fraction = r.m_hitFraction;
        if (const std::optional<RoundShape> round = roundShapeHit(*r.m_collisionObject, child)) {
            const std::optional<RayEntry> entry = rayIntoCapsule(origin_, direction_, maxDistance_, round->a, round->b, round->radius);
            if (!entry) return m_closestHitFraction;  // Bullet's cast grazed it
            distance = entry->distance;
            normal = entry->normal;
            fraction = static_cast<btScalar>(distance / maxDistance_);
        }
        const PeerRayHit hit{peerOf(r.m_collisionObject)->userData(), origin_ + distance * direction_, normal, distance};
        m_collisionObject = r.m_collisionObject;
        if (closestOnly_) {
            if (!hits.empty() && hits.front().distance <= distance) return m_closestHitFraction;
            hits.assign(1, hit);
            m_closestHitFraction = fraction;  // only nearer hits from now on
            return fraction;
        }
        hits.push_back(hit);
        return m_closestHitFraction;  // keep looking along the whole ray
    }

    std::vector<PeerRayHit> hits;

private:
    // A sphere or capsule as its axis segment (a sphere's: one point) and radius, world frame.
    struct RoundShape {
        Vec3 a, b;
        double radius;
    };
    // The sphere or capsule hit (a compound's child: `child`); none for other shapes.
    static std::optional<RoundShape> roundShapeHit(const btCollisionObject& object, int child) {
        const btCollisionShape* shape = object.getCollisionShape();
        btTransform pose = object.getWorldTransform();
        if (shape->getShapeType() == COMPOUND_SHAPE_PROXYTYPE && child >= 0) {
            const auto& compound = *static_cast<const btCompoundShape*>(shape);
            pose = pose * compound.getChildTransform(child);
            shape = compound.getChildShape(child);
        }
        if (shape->getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
            const Vec3 centre = fromBt(pose.getOrigin());
            return RoundShape{centre, centre, static_cast<double>(static_cast<const btSphereShape*>(shape)->getRadius())};
        }
        if (shape->getShapeType() != CAPSULE_SHAPE_PROXYTYPE) return std::nullopt;
        const auto& capsule = *static_cast<const btCapsuleShape*>(shape);
        btVector3 half(0, 0, 0);
        half[capsule.getUpAxis()] = capsule.getHalfHeight();
        return RoundShape{fromBt(pose * half), fromBt(pose * -half), static_cast<double>(capsule.getRadius())};
    }

    // A plane is solid below its surface: a ray starting there does not hit it, as a ray starting
    // inside any other shape does not (Bullet answers a plane from either side).
    bool startsBelow(const btCollisionObject& object) const {
        const btCollisionShape* shape = object.getCollisionShape();
        if (shape->getShapeType() != STATIC_PLANE_PROXYTYPE) return false;
        const auto& plane = *static_cast<const btStaticPlaneShape*>(shape);
        const btTransform& xf = object.getWorldTransform();
        const btVector3 n = xf.getBasis() * plane.getPlaneNormal();
        return fromBt(n).dot(origin_ - fromBt(xf.getOrigin())) < static_cast<double>(plane.getPlaneConstant());
    }

    Vec3 origin_, direction_;
    double maxDistance_;
    bool closestOnly_;
    std::uint32_t mask_;
};

// Whether two boxes overlap, by Bullet's exact box-box test (btBoxBoxDetector reports points only
// where the boxes overlap; it sees the true extents, margins included).
bool boxesOverlap(const btBoxShape& a, const btTransform& poseA, const btBoxShape& b, const btTransform& poseB) {
    struct AnyPoint final : btDiscreteCollisionDetectorInterface::Result {
        bool found = false;
        void setShapeIdentifiersA(int, int) override {}
        void setShapeIdentifiersB(int, int) override {}
        void addContactPoint(const btVector3&, const btVector3&, btScalar depth) override { found = found || depth <= 0; }
    } any;
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = poseA;
    input.m_transformB = poseB;
    btBoxBoxDetector(&a, &b).getClosestPoints(input, any, nullptr);
    return any.found;
}

class OverlapHits final : public btCollisionWorld::ContactResultCallback {
public:
    OverlapHits(const btCollisionObject* query, std::uint32_t mask) : query_(query), mask_(mask) {}

    // A box against a box is answered here, exactly: contactTest would run GJK on the shapes
    // rounded by their margins, and a cube's corner 2.9 cm into a box's face did not overlap it
    // (a box's margin, up to 4 cm, rounds its corners). Other pairs go on to contactTest.
    bool needsCollision(btBroadphaseProxy* proxy) const override {
        if (!queryable(proxy, mask_)) return false;
        const auto* other = static_cast<const btCollisionObject*>(proxy->m_clientObject);
        const btCollisionShape* mine = query_->getCollisionShape();
        const btCollisionShape* theirs = other->getCollisionShape();
        if (mine->getShapeType() != BOX_SHAPE_PROXYTYPE || theirs->getShapeType() != BOX_SHAPE_PROXYTYPE) return true;
        if (boxesOverlap(*static_cast<const btBoxShape*>(mine), query_->getWorldTransform(),
                         *static_cast<const btBoxShape*>(theirs), other->getWorldTransform()))
            found.push_back(peerOf(other)->userData());  // a single shape: its surface is the body's
        return false;
    }

    btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper* w0, int, int index0,
                             const btCollisionObjectWrapper* w1, int, int index1) override {
        if (p.getDistance() > 0) return 0;  // near, not overlapping
        const bool queryFirst = w0->getCollisionObject() == query_;
        const btCollisionObject* other = queryFirst ? w1->getCollisionObject() : w0->getCollisionObject();
        const BulletBodyPeer* peer = peerOf(other);
        if (peer == nullptr) return 0;
        // The child it overlaps may be a sensor or off the mask (a compound's children differ).
        const ChildSurface& surface = peer->surface(queryFirst ? index1 : index0);
        if (!surface.trigger && (surface.layer & mask_) != 0) found.push_back(peer->userData());
        return 0;
    }

    mutable std::vector<std::uint64_t> found;  // needsCollision adds the box pairs

private:
    const btCollisionObject* query_;
    std::uint32_t mask_;
};

}  // namespace

std::vector<PeerRayHit> BulletWorld::raycast(const Vec3& origin, const Vec3& direction, double maxDistance,
                                             bool closestOnly, std::uint32_t mask) {
    refreshBounds();
    RayHits hits(origin, direction, maxDistance, closestOnly, mask);
    world_->rayTest(toBt(origin), toBt(origin + maxDistance * direction), hits);
    // Bullet's plane is two triangles around the ray's midpoint, meeting under a ray straight down.
    sortAndMergeSeamHits(hits.hits);
    return std::move(hits.hits);
}

std::vector<std::uint64_t> BulletWorld::overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                                std::uint32_t mask) {
    refreshBounds();
    ShapeSet shape(shapes);
    btCollisionObject query;
    query.setCollisionShape(shape.root());
    query.setWorldTransform(toBt(pose));
    OverlapHits hits(&query, mask);
    world_->contactTest(&query, hits);
    std::sort(hits.found.begin(), hits.found.end());
    hits.found.erase(std::unique(hits.found.begin(), hits.found.end()), hits.found.end());
    return std::move(hits.found);
}

}  // namespace anyphys::bullet

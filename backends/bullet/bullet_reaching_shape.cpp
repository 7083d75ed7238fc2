#include "bullet_reaching_shape.hpp"

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

namespace anyphys::bullet {
namespace {

template <class Shape, class... Args>
std::unique_ptr<btCollisionShape> reaching(btScalar margin, Args&&... args) {
    auto shape = std::make_unique<ReachingShape<Shape>>(std::forward<Args>(args)...);
    if (margin >= 0) shape->setMargin(margin);
    shape->measureReach();
    return shape;
}

}  // namespace

std::unique_ptr<btCollisionShape> reachingSphere(btScalar radius) { return reaching<btSphereShape>(-1, radius); }

std::unique_ptr<btCollisionShape> reachingBox(const btVector3& halfExtents, btScalar margin) {
    return reaching<btBoxShape>(margin, halfExtents);
}

std::unique_ptr<btCollisionShape> reachingCapsule(btScalar radius, btScalar coreLength) {
    return reaching<btCapsuleShape>(-1, radius, coreLength);
}

}  // namespace anyphys::bullet

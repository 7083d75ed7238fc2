#pragma once

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <memory>
#include <utility>

namespace anyphys::bullet {

/// A shape whose bounding box can reach out by its contact breaking threshold (below).
class Reaching {
public:
    virtual void setReaching(bool on) = 0;

protected:
    ~Reaching() = default;
};

/// A Bullet convex shape whose bounding box, while reaching, extends as far as its contacts are
/// kept: the manifold's breaking threshold (gContactBreakingThreshold times the shape's angular
/// motion disc, about its bounding radius).
///
/// Bullet tests a convex against a triangle mesh's triangles only where the convex's bounding box
/// (grown by the mesh's margin) overlaps them. The layer's meshes have margin 0, as a margin
/// thickens every triangle and bodies would rest that far above the surface; so no triangle was
/// tested before the shapes overlapped, and a body ending a step a hair above the mesh and falling
/// faster than that hair per step sank a whole step's travel into it (a sphere 0.24 mm above the
/// floor at 3.55 m/s went 6.2 cm deep). Over a box or a plane the same body is held by Bullet's
/// positive-distance contacts, those within the breaking threshold; a bounding box grown by that
/// threshold gives meshes the same contacts, without moving any surface. The larger boxes also
/// make more broad-phase pairs (a 5 050-box pile stepped 21 % slower, with the same result), so
/// the world turns reaching on only while it holds a mesh.
template <class Shape>
class ReachingShape final : public Shape, public Reaching {
public:
    template <class... Args>
    explicit ReachingShape(Args&&... args) : Shape(std::forward<Args>(args)...) {}

    /// Call once the shape is complete (points, margin): measures its disc and reach as it is.
    void measureReach() {
        reach_ = 0;
        disc_ = Shape::getAngularMotionDisc();
        reachDistance_ = disc_ * gContactBreakingThreshold;
    }

    void setReaching(bool on) override { reach_ = on ? reachDistance_ : btScalar(0); }

    void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override {
        Shape::getAabb(t, aabbMin, aabbMax);
        const btVector3 grow(reach_, reach_, reach_);
        aabbMin -= grow;
        aabbMax += grow;
    }

    /// The disc of the shape without the grown box, so the manifold's breaking threshold (and
    /// with it every contact Bullet keeps) is what it would be for the plain shape.
    btScalar getAngularMotionDisc() const override { return disc_ > 0 ? disc_ : Shape::getAngularMotionDisc(); }

private:
    btScalar reach_ = 0;          // what the box grows by now
    btScalar reachDistance_ = 0;  // what it grows by while reaching
    btScalar disc_ = 0;
};

/// The primitives, each with its reach measured (built in bullet_reaching_shape.cpp).
std::unique_ptr<btCollisionShape> reachingSphere(btScalar radius);
std::unique_ptr<btCollisionShape> reachingBox(const btVector3& halfExtents, btScalar margin);
std::unique_ptr<btCollisionShape> reachingCapsule(btScalar radius, btScalar coreLength);

/// A hull to add points to; call measureReach() once it is complete.
using ReachingHull = ReachingShape<btConvexHullShape>;

}  // namespace anyphys::bullet

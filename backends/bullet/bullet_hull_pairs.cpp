#include "bullet_hull_pairs.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>
#include <BulletCollision/CollisionShapes/btPolyhedralConvexShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include <array>
#include <new>

#include "bullet_carry_impulses.hpp"

namespace anyphys::bullet {
namespace {

// A whole face: the clipped polygon of the two faces that meet, a box's or a cube hull's four
// corners. Fewer points are an edge or a corner (a tipping or rocking hull), or one triangle of a
// face made of several nearly coplanar ones (a cube hull with noise of 0.001 of its size in its
// points, resting on a box, rocked at 0.17 m/s when taking three as whole): those merge with the
// old points as Bullet does, which keeps the other triangles' points while within the breaking
// threshold.
constexpr int kWholeHullFace = 4;

// GJK's closest points: the normal on the second body (towards the first), the point on its
// surface and their distance, margins included (negative when overlapping).
struct Closest final : btDiscreteCollisionDetectorInterface::Result {
    btVector3 normalOnB, pointOnB;
    btScalar distance = 0;
    bool found = false;

    void setShapeIdentifiersA(int, int) override {}
    void setShapeIdentifiersB(int, int) override {}
    void addContactPoint(const btVector3& normal, const btVector3& point, btScalar depth) override {
        normalOnB = normal;
        pointOnB = point;
        distance = depth;
        found = true;
    }
};

// The clipping's points, before they reach the manifold.
struct Clipped final : btDiscreteCollisionDetectorInterface::Result {
    explicit Clipped(btAlignedObjectArray<HullPairAlgorithm::Scratch::Found>& into) : found(into) {}
    btAlignedObjectArray<HullPairAlgorithm::Scratch::Found>& found;

    void setShapeIdentifiersA(int, int) override {}
    void setShapeIdentifiersB(int, int) override {}
    void addContactPoint(const btVector3& normal, const btVector3& point, btScalar depth) override {
        found.push_back({normal, point, depth});
    }
};

// The margin outside a shape's polyhedron: a hull's points are its core (Bullet's margin lies
// outside them), a box's polyhedron is the whole box (its margin lies inside).
btScalar marginOutside(const btConvexShape& shape) {
    return shape.getShapeType() == BOX_SHAPE_PROXYTYPE ? btScalar(0) : shape.getMargin();
}

// How far apart two polyhedra lie along `axis` (a unit vector from the second towards the first):
// negative when they overlap along it.
btScalar separation(const btConvexPolyhedron& p0, const btTransform& t0, const btConvexPolyhedron& p1,
                    const btTransform& t1, const btVector3& axis) {
    const btVector3 local0 = axis * t0.getBasis(), local1 = axis * t1.getBasis();  // the axis in each frame
    btScalar low0 = BT_LARGE_FLOAT, high1 = -BT_LARGE_FLOAT;
    for (int i = 0; i < p0.m_vertices.size(); ++i) low0 = btMin(low0, local0.dot(p0.m_vertices[i]));
    for (int i = 0; i < p1.m_vertices.size(); ++i) high1 = btMax(high1, local1.dot(p1.m_vertices[i]));
    return low0 + axis.dot(t0.getOrigin()) - high1 - axis.dot(t1.getOrigin());
}

// The outward normal, in the world, of the polyhedron's face most along `direction`.
btVector3 faceMostAlong(const btConvexPolyhedron& p, const btTransform& t, const btVector3& direction) {
    const btVector3 local = direction * t.getBasis();  // in its frame
    int best = 0;
    for (int f = 1; f < p.m_faces.size(); ++f)
        if (btVector3(p.m_faces[f].m_plane[0], p.m_faces[f].m_plane[1], p.m_faces[f].m_plane[2]).dot(local) >
            btVector3(p.m_faces[best].m_plane[0], p.m_faces[best].m_plane[1], p.m_faces[best].m_plane[2]).dot(local))
            best = f;
    return t.getBasis() * btVector3(p.m_faces[best].m_plane[0], p.m_faces[best].m_plane[1], p.m_faces[best].m_plane[2]);
}

}  // namespace

HullPairAlgorithm::HullPairAlgorithm(const btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
                                     const btCollisionObjectWrapper* body1, btConvexPenetrationDepthSolver* depthSolver,
                                     Scratch* scratch)
    : OwnManifoldWithFallback(info, body0, body1, depthSolver), depthSolver_(depthSolver), scratch_(scratch) {}

bool HullPairAlgorithm::collidePolyhedra(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                         const btDispatcherInfo& dispatchInfo, btManifoldResult* result) {
    const auto* shape0 = static_cast<const btPolyhedralConvexShape*>(body0->getCollisionShape());
    const auto* shape1 = static_cast<const btPolyhedralConvexShape*>(body1->getCollisionShape());
    const btConvexPolyhedron* poly0 = shape0->getConvexPolyhedron();
    const btConvexPolyhedron* poly1 = shape1->getConvexPolyhedron();
    if (!poly0 || !poly1 || poly0->m_faces.size() == 0 || poly1->m_faces.size() == 0) return false;

    // GJK between the shapes with their margins, for the normal and the distance, as Bullet's test.
    const btScalar threshold = manifold_->getContactBreakingThreshold() + result->m_closestPointDistanceThreshold;
    btVoronoiSimplexSolver simplex;
    btGjkPairDetector gjk(shape0, shape1, &simplex, depthSolver_);
    btGjkPairDetector::ClosestPointInput input;
    input.m_transformA = body0->getWorldTransform();
    input.m_transformB = body1->getWorldTransform();
    const btScalar farthest = shape0->getMargin() + shape1->getMargin() + threshold;
    input.m_maximumDistanceSquared = farthest * farthest;
    Closest closest;
    gjk.getClosestPoints(input, closest, dispatchInfo.m_debugDraw);
    if (!closest.found) return true;  // apart beyond the threshold

    // GJK's point on the second polyhedron, as Bullet reports it: distances are between the
    // polyhedra (a hull resting on a face sits with its core, not its margin, at the face: 1 mm
    // deep, bullet_shapes.cpp).
    const btVector3 pointOnB = closest.pointOnB - marginOutside(*shape1) * closest.normalOnB;

    // GJK's normal is arbitrary where the cores just touch, as a hull resting on a face does: a
    // cube hull sliding over a hull slab got (0.84, -0.54, -0.03) at distance 0 and was thrown
    // up. So, as a separating-axis test restricted to a few axes, the polyhedra's separation is
    // measured along GJK's normal and along the faces the clipping would take for it and for the
    // manifold's last normal (the first's face most against it, the second's most along it), and
    // the axis along which they lie farthest apart is kept: a face contact gets its face's
    // normal, an edge or a corner GJK's.
    const btTransform& t0 = input.m_transformA;
    const btTransform& t1 = input.m_transformB;
    btVector3 normal = closest.normalOnB;
    btScalar distance = separation(*poly0, t0, *poly1, t1, normal);
    const auto tryAxis = [&](const btVector3& axis) {
        const btScalar apart = separation(*poly0, t0, *poly1, t1, axis);
        if (apart > distance) {
            distance = apart;
            normal = axis;
        }
    };
    const btVector3 gjkNormal = closest.normalOnB;
    tryAxis(-faceMostAlong(*poly0, t0, -gjkNormal));
    tryAxis(faceMostAlong(*poly1, t1, gjkNormal));
    if (manifold_->getNumContacts() > 0) {
        const btVector3 last = manifold_->getContactPoint(0).m_normalWorldOnB;
        tryAxis(-faceMostAlong(*poly0, t0, -last));
        tryAxis(faceMostAlong(*poly1, t1, last));
    }

    // Clipping the faces that meet: the second body's face most along the normal against the
    // first's most against it, keeping points from the deepest out to the threshold. Bullet clips
    // only when the cores overlap (distance < 0), here within the threshold (see the header).
    btAlignedObjectArray<Scratch::Found>& found = scratch_->found;
    found.resize(0);
    if (distance < threshold) {
        Clipped clipped(found);
        btPolyhedralContactClipping::clipHullAgainstHull(normal, *poly0, *poly1, input.m_transformA,
                                                         input.m_transformB, distance - threshold, threshold,
                                                         scratch_->clipIn, scratch_->clipOut, clipped);
    }

    result->setPersistentManifold(manifold_);
    const bool wholeFace = found.size() >= kWholeHullFace;
    std::array<btManifoldPoint, MANIFOLD_CACHE_SIZE> old;
    const int oldCount = wholeFace ? manifold_->getNumContacts() : 0;
    for (int i = 0; i < oldCount; ++i) old[i] = manifold_->getContactPoint(i);
    if (wholeFace) {
        manifold_->clearManifold();  // GJK's point lies on the face: the face's points say it all
    } else {
        result->addContactPoint(normal, pointOnB, distance);
    }
    // A face of more than four points (hulls' polygons, two squares crossed) is reduced to four
    // by the manifold as Bullet does: the deepest point and the largest area.
    for (int i = 0; i < found.size(); ++i) result->addContactPoint(found[i].normalOnB, found[i].pointOnB, found[i].distance);
    if (oldCount > 0) carryImpulses(*manifold_, old.data(), oldCount);
    return true;
}

void HullPairAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                         const btDispatcherInfo& dispatchInfo, btManifoldResult* result) {
    if (!manifold_) return;
    if (!collidePolyhedra(body0, body1, dispatchInfo, result)) fallback_->processCollision(body0, body1, dispatchInfo, result);
    result->setPersistentManifold(manifold_);
    result->refreshContactPoints();
}

btCollisionAlgorithm* HullPairAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                                             const btCollisionObjectWrapper* body0,
                                                                             const btCollisionObjectWrapper* body1) {
    return newPooledAlgorithm<HullPairAlgorithm>(info, body0, body1, &depthSolver, &scratch);
}

}  // namespace anyphys::bullet

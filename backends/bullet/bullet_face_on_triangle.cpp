#include "bullet_face_on_triangle.hpp"

#include <BulletCollision/BroadphaseCollision/btQuantizedBvh.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>
#include <BulletCollision/CollisionShapes/btPolyhedralConvexShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleInfoMap.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <array>
#include <cmath>

#include "bullet_own_manifold.hpp"

namespace anyphys::bullet {
namespace {

// How far a face (a capsule's axis) may turn out of the triangle's plane and still be taken as
// lying on it. Its far side then stands up to sin(10 deg) = 17 % of its width off the plane, and
// only the points within the breaking threshold are added: a face tipped onto its edge gives
// that edge, as Bullet's box-box test does. Beyond it the body stands on an edge or a corner, for
// which Bullet's GJK point is right.
const btScalar kMaxTiltSin = btSin(btRadians(10));
const btScalar kMaxTiltCos = btCos(btRadians(10));

// An edge shared with a neighbour turned by less than this lies in one plane with it: the
// neighbour's clipping gives the support beyond the edge. Bullet's btGenerateInternalEdgeInfo
// stores exactly 0 below 0.01 rad (its planar epsilon, 1e-4 on the squared sine); a corner 0.5 m
// past such an edge stands at most 5 mm off the neighbour's plane, still added there within the
// breaking threshold.
constexpr btScalar kFlatEdge = 0.01;

// The triangle's edge planes are moved this much outward for the clipping, so that a face corner
// lying on an edge between two triangles is kept by both (rounding could otherwise put it a hair
// outside each) rather than by neither: the second copy replaces the first in the manifold. 1 um:
// above float's rounding at metres (Bullet may be built in float, CMakeLists.txt), far below any
// contact's size.
constexpr btScalar kEdgeTolerance = 1e-6;

// A face's vertices, and three more at most from the three clipping planes.
constexpr int kMaxFaceVertices = 32;
constexpr int kMaxClipped = kMaxFaceVertices + 3;

// A clipped polygon's vertex: where it is, and which of the triangle's edges (bit k: from corner k
// to corner k+1) it lies on; none for the body's own corners.
struct Vertex {
    btVector3 at;
    unsigned onEdges;
};

struct Polygon {
    std::array<Vertex, kMaxClipped> vertices;
    int count = 0;
};

// Keeps the part of `in` on the inner side of a triangle's edge plane (through `through`, its unit
// normal `inward`) into `out`, tagging the new vertices with `edgeBit`. A polygon of two vertices
// is a segment (a capsule's line): not closed.
void clipByEdge(const Polygon& in, const btVector3& inward, const btVector3& through, unsigned edgeBit, Polygon& out) {
    out.count = 0;
    const auto inside = [&](const btVector3& p) { return (p - through).dot(inward) + kEdgeTolerance; };
    if (in.count == 2) {  // a segment: its inner part
        const Vertex& a = in.vertices[0];
        const Vertex& b = in.vertices[1];
        const btScalar da = inside(a.at), db = inside(b.at);
        if (da < 0 && db < 0) return;
        const auto crossing = [&] {
            return Vertex{a.at + (b.at - a.at) * (da / (da - db)), edgeBit | (a.onEdges & b.onEdges)};
        };
        out.vertices[out.count++] = da >= 0 ? a : crossing();
        out.vertices[out.count++] = db >= 0 ? b : crossing();
        return;
    }
    for (int i = 0; i < in.count; ++i) {
        const Vertex& a = in.vertices[i];
        const Vertex& b = in.vertices[(i + 1) % in.count];
        const btScalar da = inside(a.at), db = inside(b.at);
        if (da >= 0) out.vertices[out.count++] = a;
        if ((da >= 0) != (db >= 0))  // crosses the plane: a new vertex on this edge (and on any both share)
            out.vertices[out.count++] = {a.at + (b.at - a.at) * (da / (da - db)), edgeBit | (a.onEdges & b.onEdges)};
    }
}

// The triangle's edges that bound its mesh's flat region (bit k for the edge from corner k): those
// without a neighbour, or with one turned out of the plane. All three when the mesh has no
// connectivity (btGenerateInternalEdgeInfo, bullet_shapes.cpp).
unsigned supportingEdges(const btCollisionObjectWrapper* triangle) {
    const btCollisionShape* mesh = triangle->getCollisionObject()->getCollisionShape();
    if (mesh->getShapeType() != TRIANGLE_MESH_SHAPE_PROXYTYPE) return 7;
    const btTriangleInfoMap* edges = static_cast<const btBvhTriangleMeshShape*>(mesh)->getTriangleInfoMap();
    if (edges == nullptr) return 7;
    const int key = (triangle->m_partId << (31 - MAX_NUM_PARTS_IN_BITS)) | triangle->m_index;  // as Bullet keys them
    const btTriangleInfo* info = edges->find(btHashInt(key));
    if (info == nullptr) return 7;
    const btScalar angles[3] = {info->m_edgeV0V1Angle, info->m_edgeV1V2Angle, info->m_edgeV2V0Angle};
    unsigned bounding = 0;
    for (int k = 0; k < 3; ++k)
        if (!(btFabs(angles[k]) < kFlatEdge)) bounding |= 1u << k;
    return bounding;
}

// The body's face (a capsule's axis) lying on a plane of normal `up`, in the world, moved out to
// the body's surface (a hull's margin, a capsule's or a sphere's radius); false when none lies within
// 10 deg of the plane.
bool faceAgainst(const btCollisionObjectWrapper* body, const btVector3& up, Polygon& face) {
    const btCollisionShape* shape = body->getCollisionShape();
    const btTransform& pose = body->getWorldTransform();
    face.count = 0;
    if (shape->getShapeType() == SPHERE_SHAPE_PROXYTYPE) {  // its lowest point, a face of one vertex
        face.vertices[0] = {pose.getOrigin() - up * static_cast<const btSphereShape*>(shape)->getRadius(), 0};
        face.count = 1;
        return true;
    }
    if (shape->getShapeType() == CAPSULE_SHAPE_PROXYTYPE) {
        const auto* capsule = static_cast<const btCapsuleShape*>(shape);
        const btVector3 axis = pose.getBasis().getColumn(capsule->getUpAxis());
        if (btFabs(axis.dot(up)) > kMaxTiltSin) return false;
        const btVector3 lowest = pose.getOrigin() - up * capsule->getRadius();
        face.vertices[0] = {lowest + axis * capsule->getHalfHeight(), 0};
        face.vertices[1] = {lowest - axis * capsule->getHalfHeight(), 0};
        face.count = 2;
        return true;
    }
    if (shape->getShapeType() != BOX_SHAPE_PROXYTYPE && shape->getShapeType() != CONVEX_HULL_SHAPE_PROXYTYPE) return false;
    const btConvexPolyhedron* polyhedron = static_cast<const btPolyhedralConvexShape*>(shape)->getConvexPolyhedron();
    if (polyhedron == nullptr || polyhedron->m_faces.size() == 0) return false;
    const btVector3 down = -up * pose.getBasis();  // in the body's frame
    int best = 0;
    btScalar bestAlong = -BT_LARGE_FLOAT;
    for (int f = 0; f < polyhedron->m_faces.size(); ++f) {
        const btScalar* plane = polyhedron->m_faces[f].m_plane;
        const btScalar along = btVector3(plane[0], plane[1], plane[2]).dot(down);
        if (along > bestAlong) {
            bestAlong = along;
            best = f;
        }
    }
    const btFace& chosen = polyhedron->m_faces[best];
    if (bestAlong < kMaxTiltCos || chosen.m_indices.size() > kMaxFaceVertices) return false;
    // A hull's polyhedron is its core, its margin outside; a box's is the whole box (bullet_shapes.cpp).
    const btScalar margin = shape->getShapeType() == BOX_SHAPE_PROXYTYPE ? btScalar(0) : shape->getMargin();
    for (int i = 0; i < chosen.m_indices.size(); ++i)
        face.vertices[face.count++] = {pose * polyhedron->m_vertices[chosen.m_indices[i]] - up * margin, 0};
    return true;
}

}  // namespace

FaceOnTriangleAlgorithm::FaceOnTriangleAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                                                 btCollisionAlgorithmCreateFunc* bullets)
    : btCollisionAlgorithm(info), manifold_(info.m_manifold), bullets_(bullets) {}

bool FaceOnTriangleAlgorithm::collideFace(const btCollisionObjectWrapper* body, const btCollisionObjectWrapper* triangle,
                                          btManifoldResult* result) {
    if (triangle->getCollisionShape()->getShapeType() != TRIANGLE_SHAPE_PROXYTYPE) return false;
    const auto* shape = static_cast<const btTriangleShape*>(triangle->getCollisionShape());
    const btTransform& meshPose = triangle->getWorldTransform();
    const btVector3 corners[3] = {meshPose * shape->m_vertices1[0], meshPose * shape->m_vertices1[1],
                                  meshPose * shape->m_vertices1[2]};
    btVector3 up = (corners[1] - corners[0]).cross(corners[2] - corners[0]);  // the front (Bullet's calcNormal)
    if (up.length2() < SIMD_EPSILON * SIMD_EPSILON) return false;          // degenerate: no plane
    up.normalize();
    if ((body->getWorldTransform().getOrigin() - corners[0]).dot(up) <= 0) return false;  // behind: single-sided
    Polygon clipped[2];
    if (!faceAgainst(body, up, clipped[0])) return false;

    int current = 0;
    for (int k = 0; k < 3 && clipped[current].count > 0; ++k) {
        const btVector3 inward = up.cross(corners[(k + 1) % 3] - corners[k]).normalized();
        clipByEdge(clipped[current], inward, corners[k], 1u << k, clipped[1 - current]);
        current = 1 - current;
    }

    const unsigned bounding = supportingEdges(triangle);
    // The face misses the triangle. Inside a flat region its neighbours hold the face; next to a
    // boundary or a bend the body may still touch the triangle's edge with its side: Bullet's test.
    if (clipped[current].count == 0) return bounding == 0;
    const btScalar threshold = manifold_->getContactBreakingThreshold() + result->m_closestPointDistanceThreshold;
    const Polygon& support = clipped[current];
    for (int i = 0; i < support.count; ++i) {
        const Vertex& v = support.vertices[i];
        // An inner corner of a flat region's cut (see the header) supports nothing the face's own
        // corners do not.
        if (v.onEdges != 0 && (v.onEdges & bounding) == 0) continue;
        const btScalar distance = (v.at - corners[0]).dot(up);
        if (distance >= threshold) continue;
        result->addContactPoint(up, v.at - up * distance, distance);  // the normal and point on the triangle
    }
    return true;
}

void FaceOnTriangleAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                               const btDispatcherInfo& dispatchInfo, btManifoldResult* result) {
    if (manifold_ != nullptr && collideFace(body0, body1, result)) return;
    // Bullet's own test, made for this triangle and step as Bullet makes it (btConvexTriangleCallback).
    btCollisionAlgorithmConstructionInfo info(m_dispatcher, 0);
    info.m_manifold = manifold_;
    btCollisionAlgorithm* bullets = bullets_->CreateCollisionAlgorithm(info, body0, body1);
    bullets->processCollision(body0, body1, dispatchInfo, result);
    bullets->~btCollisionAlgorithm();
    m_dispatcher->freeCollisionAlgorithm(bullets);
}

btCollisionAlgorithm* FaceOnTriangleAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                                                    const btCollisionObjectWrapper*,
                                                                                    const btCollisionObjectWrapper*) {
    return newPooledAlgorithm<FaceOnTriangleAlgorithm>(info, bullets);
}

}  // namespace anyphys::bullet

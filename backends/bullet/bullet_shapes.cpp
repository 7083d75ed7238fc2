#include "bullet_shapes.hpp"

#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <LinearMath/btGeometryUtil.h>

#include <algorithm>
#include <limits>

#include "bullet_convert.hpp"
#include "bullet_reaching_shape.hpp"

namespace anyphys::bullet {
namespace {

// Bullet keeps a collision margin around convex shapes for robust GJK. For boxes it lies inside
// the box (the corners are rounded by it), so the size is exact; it is kept to a tenth of the
// thinnest half extent so small boxes stay boxes.
constexpr double kBoxMargin = 0.04;
// Hull margins lie outside the points, so hulls are shrunk by their margin first (their surface
// then stays where the layer put it); at most a quarter of the hull's inner radius. Kept small:
// hull-hull contacts use the polyhedral clipping path (initializePolyhedralFeatures), which sees
// the shrunk hulls without their margins, so two hulls rest 2 x margin too deep (measured: a
// cube on a convex slab 2 cm low at 0.01, 2 mm at 0.001).
constexpr double kHullMargin = 0.001;

bool isIdentity(const Transform& t) {
    return t.position.squaredNorm() == 0.0 && t.orientation.coeffs() == Quat::Identity().coeffs();
}

double hullInnerRadius(const HullData& hull) {
    double inner = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < hull.faceNormals.size(); ++f)
        inner = std::min(inner, hull.faceOffsets[f] - hull.faceNormals[f].dot(hull.centroid));
    return inner;
}

// The hull moved inwards by `margin` on every face, so that hull + margin is the layer's hull.
btAlignedObjectArray<btVector3> shrunkHull(const HullData& hull, double margin) {
    btAlignedObjectArray<btVector3> planes, vertices;
    for (std::size_t f = 0; f < hull.faceNormals.size(); ++f) {
        btVector3 plane = toBt(hull.faceNormals[f]);
        plane.setW(static_cast<btScalar>(-(hull.faceOffsets[f] - margin)));  // n . x + w = 0
        planes.push_back(plane);
    }
    btGeometryUtil::getVerticesFromPlaneEquations(planes, vertices);
    return vertices;
}

}  // namespace

ShapeSet::ShapeSet(const std::vector<PeerShape>& shapes) {
    coreExtent_ = std::numeric_limits<double>::infinity();
    std::vector<std::pair<btCollisionShape*, bool>> built;  // shape, pose absorbed into it
    for (const PeerShape& s : shapes) {
        bool absorbed = false;
        built.emplace_back(build(s, absorbed), absorbed);
    }
    if (built.size() == 1 && (built[0].second || isIdentity(shapes[0].local))) {
        root_ = built[0].first;
        return;
    }
    compound_ = std::make_unique<btCompoundShape>(/*enableDynamicAabbTree=*/built.size() > 8,
                                                  static_cast<int>(built.size()));
    for (std::size_t i = 0; i < built.size(); ++i)
        compound_->addChildShape(built[i].second ? btTransform::getIdentity() : toBt(shapes[i].local), built[i].first);
    root_ = compound_.get();
    const SurfaceSummary summary = summarize(shapes);
    if (summary.anyTrigger && !summary.allTriggers) {
        solidPart_ = std::make_unique<btCompoundShape>(false, static_cast<int>(built.size()));
        for (std::size_t i = 0; i < built.size(); ++i)
            if (!shapes[i].isTrigger)
                solidPart_->addChildShape(compound_->getChildTransform(static_cast<int>(i)), built[i].first);
    }
}

ShapeSet::~ShapeSet() = default;

btCollisionShape* ShapeSet::build(const PeerShape& ps, bool& absorbedPose) {
    const ShapeDef& d = ps.def;
    std::unique_ptr<btCollisionShape> shape;
    switch (d.type) {
        case ShapeType::Sphere: {
            shape = reachingSphere(static_cast<btScalar>(d.radius));
            coreExtent_ = std::min(coreExtent_, d.radius);
            break;
        }
        case ShapeType::Box: {
            shape = reachingBox(toBt(d.halfExtents),
                                static_cast<btScalar>(std::min(kBoxMargin, 0.1 * d.halfExtents.minCoeff())));
            // Face clipping against hulls (as hull-hull, below): through GJK's one point per
            // step a hull cube resting 5 cm short of a box table's edge walked off it.
            static_cast<btBoxShape*>(shape.get())->initializePolyhedralFeatures();
            coreExtent_ = std::min(coreExtent_, d.halfExtents.minCoeff());
            break;
        }
        case ShapeType::Capsule: {  // along Y; Bullet's height is the core segment's length
            shape = reachingCapsule(static_cast<btScalar>(d.radius), static_cast<btScalar>(2 * d.halfHeight));
            coreExtent_ = std::min(coreExtent_, d.radius);
            break;
        }
        case ShapeType::Plane: {
            // Planes are infinite: the local pose folds into the plane's normal and offset.
            const double length = d.normal.norm();
            const Vec3 n = ps.local.orientation * (d.normal / length);
            const double offset = d.offset / length + n.dot(ps.local.position);
            shape = std::make_unique<btStaticPlaneShape>(toBt(n), static_cast<btScalar>(offset));
            absorbedPose = true;
            break;
        }
        case ShapeType::Convex: {
            const HullData& hull = *ps.hull;
            const double inner = hullInnerRadius(hull);
            const double margin = std::min(kHullMargin, 0.25 * inner);
            btAlignedObjectArray<btVector3> points = shrunkHull(hull, margin);
            auto convex = std::make_unique<ReachingHull>();
            if (points.size() >= 4) {
                for (int i = 0; i < points.size(); ++i) convex->addPoint(points[i], false);
                convex->setMargin(static_cast<btScalar>(margin));
            } else {  // degenerate after shrinking: the hull itself, with a negligible margin
                for (const Vec3& v : hull.vertices) convex->addPoint(toBt(v), false);
                convex->setMargin(static_cast<btScalar>(1e-4));
            }
            convex->recalcLocalAabb();
            convex->initializePolyhedralFeatures();  // face-based manifolds (stable resting contact)
            convex->measureReach();
            shape = std::move(convex);
            coreExtent_ = std::min(coreExtent_, inner);
            break;
        }
        case ShapeType::Mesh: {
            // The local pose folds into the vertices, so the mesh is always the body's own shape,
            // never a compound's child: Bullet's edge adjustment finds the triangles' edge info
            // through the collision object's shape.
            auto mesh = std::make_unique<Mesh>();
            mesh->vertices.reserve(d.vertices.size() * 3);
            for (const Vec3& v : d.vertices) {
                const Vec3 placed = ps.local.orientation * v + ps.local.position;
                for (int k = 0; k < 3; ++k) mesh->vertices.push_back(static_cast<btScalar>(placed[k]));
            }
            mesh->indices.assign(d.indices.begin(), d.indices.end());
            mesh->array = std::make_unique<btTriangleIndexVertexArray>(
                static_cast<int>(mesh->indices.size() / 3), mesh->indices.data(), static_cast<int>(3 * sizeof(int)),
                static_cast<int>(d.vertices.size()), mesh->vertices.data(), static_cast<int>(3 * sizeof(btScalar)));
            auto bvh = std::make_unique<btBvhTriangleMeshShape>(mesh->array.get(), /*useQuantizedAabbCompression=*/true);
            bvh->setMargin(0);  // triangles are exact; the other shape's margin keeps GJK robust
            // Bullet collides each triangle alone, so a body sliding over a flat mesh meets the
            // shared edges ahead of it as walls (a 0.5 m box at 5 m/s kept 1.0 m/s after 2 s, spun
            // at 9.7 rad/s and was thrown 16 cm up). The angle at every shared edge lets the
            // contact callback correct those normals; edges with no neighbour keep theirs.
            mesh->edges = std::make_unique<btTriangleInfoMap>();
            // Only bends under 60 deg: sharper creases are walls and steps, where each triangle's
            // own contacts are right, and at a right angle Bullet read a concave crease as convex:
            // the floor's points beside a mesh wall were turned along the floor, into the wall (a
            // box sliding into it at 5 m/s went 11 cm deep, 6 cm with the wall's own contacts).
            mesh->edges->m_maxEdgeAngleThreshold = static_cast<btScalar>(SIMD_PI / 3);
            btGenerateInternalEdgeInfo(bvh.get(), mesh->edges.get());
            meshes_.push_back(std::move(mesh));
            absorbedPose = true;
            hasMesh_ = true;
            shape = std::move(bvh);
            break;
        }
        case ShapeType::Compound:  // flattened by the layer
            break;
    }
    if (auto* reaching = dynamic_cast<Reaching*>(shape.get())) reaching_.push_back(reaching);
    children_.push_back(std::move(shape));
    return children_.back().get();
}

void ShapeSet::setReaching(bool on) {
    if (reaching_.empty()) return;
    for (Reaching* shape : reaching_) shape->setReaching(on);
    if (compound_) {  // the compound keeps its children's boxes: refresh them
        for (int i = 0; i < compound_->getNumChildShapes(); ++i)
            compound_->updateChildTransform(i, compound_->getChildTransform(i), /*shouldRecalculateLocalAabb=*/false);
        compound_->recalculateLocalAabb();
    }
}

}  // namespace anyphys::bullet

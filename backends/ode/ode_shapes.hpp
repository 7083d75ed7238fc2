#pragma once
// Collision shapes as ODE geoms. ODE does not copy convex or mesh arrays, so each geom lives
// with the arrays it points into, and both die together.
#include <ode/ode.h>

#include <memory>
#include <vector>

#include "anyphys/peers/shape_data.hpp"
#include "ode_mesh_edges.hpp"

namespace anyphys::ode {

/// False for shape pairs ODE cannot collide safely: convex against triangle mesh, whose collider
/// in Debian's ODE 0.16 (libccd's dCollideConvexTrimeshTrianglesCCD over OPCODE) crashes. Such
/// pairs never touch. From the layer's shape types: the near callback asks it of every candidate
/// pair, without calls into ODE.
inline bool collidable(ShapeType a, ShapeType b) {
    return !((a == ShapeType::Convex && b == ShapeType::Mesh) || (a == ShapeType::Mesh && b == ShapeType::Convex));
}

/// A geom's surface as the layer resolved it (a compound child's own, else the body's).
struct GeomSurface {
    std::uint32_t material = 0;
    std::uint32_t layer = 1;
    std::uint32_t mask = 0xFFFFFFFFu;
    bool trigger = false;
};

class OdeBody;

class OdeShape {
public:
    /// Builds the geom of `shape` in `space` (0: in no space, e.g. a query probe). Not placed yet.
    /// The geom's data (and its twin's) is this shape (shapeOfGeom).
    explicit OdeShape(const PeerShape& shape, dSpaceID space);
    ~OdeShape();
    OdeShape(const OdeShape&) = delete;
    OdeShape& operator=(const OdeShape&) = delete;

    dGeomID geom() const { return geom_; }
    ShapeType type() const { return type_; }
    const GeomSurface& surface() const { return surface_; }
    /// Convex shapes: the hull, in the geom's frame; null for other shapes.
    const HullData* hull() const { return hull_.get(); }
    /// The body the geom belongs to; null for a query probe.
    OdeBody* owner() const { return owner_; }
    void setOwner(OdeBody* body) { owner_ = body; }

    /// A second geom of the same shape in no space and on no body, made on first use, for
    /// colliding the shape at a pose of its own (ode_contact_completion.hpp); null for shapes
    /// that never need one (spheres, planes, meshes).
    dGeomID twin() const;

    /// Meshes: which of their triangles' edges are real (ode_mesh_edges.hpp); null for other shapes.
    const MeshEdges* meshEdges() const { return meshEdges_.get(); }
    /// Meshes: a ray in no space and on no body, made on first use, that measures how far a
    /// shape reaches below a triangle (collideWithMesh); null for other shapes.
    dGeomID probeRay() const;

    /// Whether a face of the shape, where its geom is now, has an outward normal within
    /// `cosine` of `direction` (world frame, unit). Boxes and hulls; false for other shapes.
    bool hasFaceAlong(const Vec3& direction, double cosine) const;

    /// Attaches the geom to a moving body at its pose in the body frame.
    void attach(dBodyID body);
    /// Places the geom of a static body (or a query probe) whose frame is at `bodyPose`.
    void place(const Transform& bodyPose);

    /// m: how far the shape's surface lies from the body frame's origin at least, along any
    /// direction (continuous collision stops a fast body this far before its hit point, so it
    /// then overlaps and ODE's discrete contact takes over).
    double coreExtent() const { return coreExtent_; }

private:
    /// The geom's pose in the body frame: the shape's own, with ODE's capsule axis (z) turned
    /// onto the layer's (y).
    Transform geomLocal() const;

    dGeomID geom_ = nullptr;
    mutable dGeomID twin_ = nullptr;
    OdeBody* owner_ = nullptr;
    std::shared_ptr<const HullData> hull_;
    ShapeType type_;
    GeomSurface surface_;
    Transform local_;
    double coreExtent_ = 0.0;
    // plane: n . x = offset in the body frame
    Vec3 planeNormal_ = Vec3::UnitY();
    double planeOffset_ = 0.0;
    // convex: ODE reads these arrays in place
    std::vector<dReal> convexPlanes_;
    std::vector<dReal> convexPoints_;
    std::vector<unsigned int> convexPolygons_;
    // mesh
    std::vector<dReal> meshVertices_;
    std::vector<dTriIndex> meshIndices_;
    dTriMeshDataID meshData_ = nullptr;
    std::unique_ptr<const MeshEdges> meshEdges_;
    mutable dGeomID probeRay_ = nullptr;
};

/// The shape whose geom (or twin) `geom` is; null for other geoms (rays).
inline const OdeShape* shapeOfGeom(dGeomID geom) { return static_cast<const OdeShape*>(dGeomGetData(geom)); }

/// The body owning `geom`; null for a ray or a query probe.
inline OdeBody* bodyOfGeom(dGeomID geom) {
    const OdeShape* shape = shapeOfGeom(geom);
    return shape ? shape->owner() : nullptr;
}

}  // namespace anyphys::ode

#include "ode_shapes.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "ode_math.hpp"

namespace anyphys::ode {
namespace {

// ODE capsules lie along their local z axis; the layer's along y. Turning by -90 degrees about x
// maps z onto y.
const Quat kCapsuleTurn(Eigen::AngleAxisd(-std::numbers::pi / 2, Vec3::UnitX()));

// Distance from the frame origin to the nearest point of the shape's surface from inside: the
// inner radius about the body frame origin, 0 if the origin is outside the shape.
double innerRadius(const PeerShape& s) {
    const Vec3 c = s.local.orientation.conjugate() * -s.local.position;  // body origin, shape frame
    switch (s.def.type) {
        case ShapeType::Sphere: return std::max(0.0, s.def.radius - c.norm());
        case ShapeType::Box: return std::max(0.0, (s.def.halfExtents - c.cwiseAbs()).minCoeff());
        case ShapeType::Capsule: {
            const Vec3 onAxis(0, std::clamp(c.y(), -s.def.halfHeight, s.def.halfHeight), 0);
            return std::max(0.0, s.def.radius - (c - onAxis).norm());
        }
        case ShapeType::Convex: {
            double inner = std::numeric_limits<double>::infinity();
            for (std::size_t f = 0; f < s.hull->faceNormals.size(); ++f)
                inner = std::min(inner, s.hull->faceOffsets[f] - s.hull->faceNormals[f].dot(c));
            return std::max(0.0, inner);
        }
        default: return 0.0;
    }
}

// The mesh as ODE gets it: only the vertices some triangle uses, numbered in the order the
// triangles first use them (the triangles keep their order, so ODE's triangle indices are the
// layer's). ODE's edge preprocessing (dGeomTriMeshDataPreprocess2) asserts that a mesh has no
// more vertices than triangle corners and aborts the process otherwise, and a layer mesh may list
// vertices no triangle uses (the API fuzzer found one).
void keepReferencedVertices(const std::vector<Vec3>& vertices, const std::vector<std::uint32_t>& indices,
                            std::vector<dReal>& odeVertices, std::vector<dTriIndex>& odeIndices) {
    constexpr dTriIndex kUnused = std::numeric_limits<dTriIndex>::max();
    std::vector<dTriIndex> renumbered(vertices.size(), kUnused);
    odeVertices.clear();
    odeIndices.clear();
    odeIndices.reserve(indices.size());
    for (const std::uint32_t i : indices) {
        if (renumbered[i] == kUnused) {
            renumbered[i] = static_cast<dTriIndex>(odeVertices.size() / 3);
            odeVertices.insert(odeVertices.end(), {vertices[i].x(), vertices[i].y(), vertices[i].z()});
        }
        odeIndices.push_back(renumbered[i]);
    }
}

}  // namespace

OdeShape::OdeShape(const PeerShape& shape, dSpaceID space)
    : type_(shape.def.type), surface_{shape.material, shape.layer, shape.mask, shape.isTrigger}, local_(shape.local) {
    const ShapeDef& d = shape.def;
    coreExtent_ = innerRadius(shape);
    switch (d.type) {
        case ShapeType::Sphere: geom_ = dCreateSphere(space, d.radius); break;
        case ShapeType::Box:
            geom_ = dCreateBox(space, 2 * d.halfExtents.x(), 2 * d.halfExtents.y(), 2 * d.halfExtents.z());
            break;
        case ShapeType::Capsule: geom_ = dCreateCapsule(space, d.radius, 2 * d.halfHeight); break;
        case ShapeType::Plane:
            planeNormal_ = d.normal.normalized();
            planeOffset_ = d.offset / d.normal.norm();
            geom_ = dCreatePlane(space, planeNormal_.x(), planeNormal_.y(), planeNormal_.z(), planeOffset_);
            break;
        case ShapeType::Convex: {
            const HullData& h = *shape.hull;
            for (std::size_t f = 0; f < h.faces.size(); ++f) {
                const Vec3& n = h.faceNormals[f];
                convexPlanes_.insert(convexPlanes_.end(), {n.x(), n.y(), n.z(), h.faceOffsets[f]});
                convexPolygons_.push_back(static_cast<unsigned int>(h.faces[f].size()));
                for (int v : h.faces[f]) convexPolygons_.push_back(static_cast<unsigned int>(v));
            }
            for (const Vec3& v : h.vertices) convexPoints_.insert(convexPoints_.end(), {v.x(), v.y(), v.z()});
            geom_ = dCreateConvex(space, convexPlanes_.data(), static_cast<unsigned int>(h.faces.size()),
                                  convexPoints_.data(), static_cast<unsigned int>(h.vertices.size()),
                                  convexPolygons_.data());
            break;
        }
        case ShapeType::Mesh: {
            keepReferencedVertices(d.vertices, d.indices, meshVertices_, meshIndices_);
            meshData_ = dGeomTriMeshDataCreate();
            dGeomTriMeshDataBuildDouble(meshData_, meshVertices_.data(), 3 * sizeof(dReal),
                                        static_cast<int>(meshVertices_.size() / 3), meshIndices_.data(),
                                        static_cast<int>(meshIndices_.size()), 3 * sizeof(dTriIndex));
            // ODE's own edge flags: the capsule-trimesh collider then tests each shared edge and
            // corner once and a concave one never (its only reader; ode_mesh_edges.hpp).
            dGeomTriMeshDataPreprocess2(meshData_, 1u << dTRIDATAPREPROCESS_BUILD_CONCAVE_EDGES, nullptr);
            geom_ = dCreateTriMesh(space, meshData_, nullptr, nullptr, nullptr);
            meshEdges_ = std::make_unique<const MeshEdges>(d.vertices, d.indices);
            break;
        }
        case ShapeType::Compound: break;  // the layer flattens compounds: never reaches a backend
    }
    if (d.type == ShapeType::Convex) hull_ = shape.hull;
    if (geom_) dGeomSetData(geom_, this);
}

OdeShape::~OdeShape() {
    if (probeRay_) dGeomDestroy(probeRay_);
    if (twin_) dGeomDestroy(twin_);
    if (geom_) dGeomDestroy(geom_);
    if (meshData_) dGeomTriMeshDataDestroy(meshData_);  // after the geom that reads it
}

dGeomID OdeShape::twin() const {
    if (twin_) return twin_;
    switch (type_) {  // the sizes as the geom has them
        case ShapeType::Box: {
            dVector3 lengths;
            dGeomBoxGetLengths(geom_, lengths);
            twin_ = dCreateBox(nullptr, lengths[0], lengths[1], lengths[2]);
            break;
        }
        case ShapeType::Capsule: {
            dReal radius = 0, length = 0;
            dGeomCapsuleGetParams(geom_, &radius, &length);
            twin_ = dCreateCapsule(nullptr, radius, length);
            break;
        }
        case ShapeType::Convex:  // the same arrays: ODE reads them in place
            twin_ = dCreateConvex(nullptr, convexPlanes_.data(), static_cast<unsigned int>(convexPlanes_.size() / 4),
                                  convexPoints_.data(), static_cast<unsigned int>(convexPoints_.size() / 3),
                                  convexPolygons_.data());
            break;
        default: break;
    }
    if (twin_) dGeomSetData(twin_, const_cast<OdeShape*>(this));
    return twin_;
}

dGeomID OdeShape::probeRay() const {
    if (!probeRay_ && type_ == ShapeType::Mesh) probeRay_ = dCreateRay(nullptr, 1.0);  // placed at each use
    return probeRay_;
}

bool OdeShape::hasFaceAlong(const Vec3& direction, double cosine) const {
    if (type_ != ShapeType::Box && type_ != ShapeType::Convex) return false;
    dQuaternion q;
    dGeomGetQuaternion(geom_, q);
    const Vec3 local = toQuat(q).conjugate() * direction;  // in the geom's frame
    if (type_ == ShapeType::Box) return local.cwiseAbs().maxCoeff() >= cosine;
    for (std::size_t f = 0; f + 3 < convexPlanes_.size(); f += 4)
        if (Vec3(convexPlanes_[f], convexPlanes_[f + 1], convexPlanes_[f + 2]).dot(local) >= cosine) return true;
    return false;
}

Transform OdeShape::geomLocal() const {
    Transform t = local_;
    if (type_ == ShapeType::Capsule) t.orientation = local_.orientation * kCapsuleTurn;
    return t;
}

void OdeShape::attach(dBodyID body) {
    dGeomSetBody(geom_, body);
    const Transform t = geomLocal();
    // Offsets cost a transform per geom and step: only where the shape is off the body frame.
    if (!t.position.isZero(0)) dGeomSetOffsetPosition(geom_, t.position.x(), t.position.y(), t.position.z());
    if (!t.orientation.coeffs().isApprox(Quat::Identity().coeffs(), 0.0)) {
        dQuaternion q;
        toOde(t.orientation, q);
        dGeomSetOffsetQuaternion(geom_, q);
    }
}

void OdeShape::place(const Transform& bodyPose) {
    const Transform t = geomLocal();
    const Vec3 position = bodyPose.position + bodyPose.orientation * t.position;
    const Quat orientation = (bodyPose.orientation * t.orientation).normalized();
    if (type_ == ShapeType::Plane) {
        // Planes are non-placeable in ODE: their world equation moves instead.
        const Vec3 n = orientation * planeNormal_;
        dGeomPlaneSetParams(geom_, n.x(), n.y(), n.z(), planeOffset_ + n.dot(position));
        return;
    }
    dGeomSetPosition(geom_, position.x(), position.y(), position.z());
    dQuaternion q;
    toOde(orientation, q);
    dGeomSetQuaternion(geom_, q);
}

}  // namespace anyphys::ode

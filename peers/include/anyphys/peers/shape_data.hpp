#pragma once
// Shapes as the layer hands them to a backend: primitives only (compounds are flattened),
// placed in the peer body frame (centre of mass, principal axes), convex hulls already built.
#include <array>
#include <memory>
#include <vector>

#include "anyphys/defs.hpp"

namespace anyphys {

/// A convex polyhedron: the hull of a convex shape's points.
struct HullData {
    std::vector<Vec3> vertices;             ///< hull vertices, shape frame
    std::vector<std::vector<int>> faces;    ///< vertex indices per face, counter-clockwise seen from outside
    std::vector<Vec3> faceNormals;          ///< outward unit normal per face
    std::vector<double> faceOffsets;        ///< per face: normal.dot(x) == offset on its plane
    Vec3 centroid = Vec3::Zero();           ///< volume centroid, shape frame
    double volume = 0.0;                    ///< m^3
    Mat3 inertiaPerMass = Mat3::Zero();     ///< inertia tensor about the centroid per unit mass, shape frame
    /// Topology for collision, optional (computed on use when empty): each edge once as
    /// (v0, v1) with v0 < v1, and per edge the faces on its left and right, i.e. the face whose
    /// loop walks v0 -> v1 and the one walking v1 -> v0.
    std::vector<std::array<int, 2>> edges;
    std::vector<std::array<int, 2>> edgeFaces;
};

struct PeerShape {
    ShapeDef def;                            ///< a primitive (never compound); its own position/orientation are unused
    Transform local;                         ///< pose of the shape in the peer body frame
    std::shared_ptr<const HullData> hull;    ///< convex shapes only
};

}  // namespace anyphys

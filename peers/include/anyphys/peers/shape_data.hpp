#pragma once
// Shapes as the layer hands them to a backend: primitives only (compounds are flattened),
// placed in the peer body frame (centre of mass, principal axes), convex hulls already built.
#include <array>
#include <cstdint>
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
    // The shape's surface, resolved by the layer: a compound child's own values where it set
    // them, else the body's. Backends read these per shape, never the BodyDef's.
    std::uint32_t material = 0;              ///< row / column of the MaterialTable
    std::uint32_t layer = 1;                 ///< collision layer bits (layersCollide)
    std::uint32_t mask = 0xFFFFFFFFu;        ///< layers this shape collides with
    bool isTrigger = false;                  ///< a sensor: overlaps reported as triggers, no response
};

/// Summaries of a body's shapes for backends that filter whole bodies first (a broad phase
/// that pairs bodies, not shapes): a body pair may touch only if some shape pair may.
struct SurfaceSummary {
    std::uint32_t anyLayer = 0;    ///< union of the shapes' layers
    std::uint32_t anyMask = 0;     ///< union of the shapes' masks
    bool allTriggers = true;       ///< every shape is a sensor (the whole body never responds)
    bool anyTrigger = false;       ///< some shape is a sensor
    bool uniform = true;           ///< every shape has the same material, layer, mask and sensor flag
};

inline SurfaceSummary summarize(const std::vector<PeerShape>& shapes) {
    SurfaceSummary s;
    for (const PeerShape& p : shapes) {
        s.anyLayer |= p.layer;
        s.anyMask |= p.mask;
        s.allTriggers = s.allTriggers && p.isTrigger;
        s.anyTrigger = s.anyTrigger || p.isTrigger;
        const PeerShape& first = shapes.front();
        s.uniform = s.uniform && p.material == first.material && p.layer == first.layer && p.mask == first.mask &&
                    p.isTrigger == first.isTrigger;
    }
    if (shapes.empty()) s.allTriggers = false;
    return s;
}

}  // namespace anyphys

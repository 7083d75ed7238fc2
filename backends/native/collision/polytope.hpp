#pragma once
// A convex polyhedron placed in the world, as the polyhedral collision routines see it: boxes,
// hulls and mesh triangles (a triangle is a flat polyhedron with a front and a back face).
//
// Geometry stays in the shape's own frame and the pose is applied on use, so making one costs
// nothing and allocates nothing: a hull's arrays are viewed where the hull keeps them; the few
// numbers of a box or a triangle live inside the Polytope. (Its views may point into itself, so
// it can be neither copied nor moved; factories return it by guaranteed copy elision.)
#include <array>
#include <span>
#include <vector>

#include "anyphys/math.hpp"
#include "anyphys/peers/shape_data.hpp"

namespace anyphys::native {

struct Polytope {
    Polytope(const Polytope&) = delete;
    Polytope& operator=(const Polytope&) = delete;

    Mat3 rotation = Mat3::Identity();          // shape frame -> world
    Vec3 position = Vec3::Zero();
    std::span<const Vec3> vertices;            // shape frame
    std::span<const std::vector<int>> faces;   // vertex loops, counter-clockwise from outside
    std::span<const Vec3> normals;             // shape frame, outward, unit
    std::span<const double> offsets;           // shape frame: normals[f].dot(x) == offsets[f] on face f
    // Edges, each once as (v0, v1), and per edge the faces on its left (the face walking
    // v0 -> v1) and right. A flat triangle has no edge faces: its two faces meet at every edge.
    std::span<const std::array<int, 2>> edges;
    std::span<const std::array<int, 2>> edgeFaces;
    Vec3 center = Vec3::Zero();  // world, an interior point (centroid)
    bool isBox = false;          // vertex i has coordinate k positive when bit k of i is set
    bool oneSided = false;       // mesh triangle: pushes shapes out of its front only

    /// Largest distance from center to a vertex (m): the scale of tolerances. A hull's is
    /// measured on first use (a pair rejected early never needs it).
    double size() const;

    int vertexCount() const { return static_cast<int>(vertices.size()); }
    int faceCount() const { return static_cast<int>(faces.size()); }
    const std::vector<int>& face(int f) const { return faces[static_cast<std::size_t>(f)]; }
    /// Faces whose normals are separating axes: all, or the front of a one-sided triangle (a
    /// shape overlapping it is pushed out of the front, never through to the back).
    int axisFaceCount() const { return oneSided ? 1 : faceCount(); }
    /// A closed solid (every edge between two faces with distinct normals), not a flat triangle
    /// nor a hull with an edge only one face walks.
    bool closed() const { return !edgeFaces.empty(); }

    Vec3 vertex(int i) const { return position + rotation * vertices[static_cast<std::size_t>(i)]; }
    Vec3 normal(int f) const { return rotation * normals[static_cast<std::size_t>(f)]; }
    /// World offset of face f, given its world normal n = normal(f).
    double offset(int f, const Vec3& n) const { return offsets[static_cast<std::size_t>(f)] + n.dot(position); }
    double offset(int f) const { return offset(f, normal(f)); }

    /// Index of a vertex farthest along world direction d (the first one on ties).
    int support(const Vec3& d) const { return localSupport(rotation.transpose() * d); }
    /// The same for a direction in the shape frame.
    int localSupport(const Vec3& d) const;
    /// Lowest and highest value of d.dot(vertex), d in the world.
    std::array<double, 2> project(const Vec3& d) const {
        const std::array<double, 2> range = localProject(rotation.transpose() * d);
        const double shift = d.dot(position);
        return {range[0] + shift, range[1] + shift};
    }
    /// The same in the shape frame (vertices as they are stored).
    std::array<double, 2> localProject(const Vec3& d) const;
    /// The lowest value alone, in the shape frame.
    double localLowest(const Vec3& d) const;
    /// The centre in the shape frame.
    const Vec3& localCenter() const { return localCentroid_; }

private:
    friend Polytope makeHullPolytope(const HullData&, const Mat3&, const Vec3&);
    friend Polytope makeBoxPolytope(const Vec3&, const Mat3&, const Vec3&);
    friend Polytope makeTrianglePolytope(const Vec3&, const Vec3&, const Vec3&);
    struct HullTag {};
    struct BoxTag {};
    struct TriangleTag {};
    Polytope(HullTag, const HullData& hull, const Mat3& rotation, const Vec3& position);
    Polytope(BoxTag, const Vec3& halfExtents, const Mat3& rotation, const Vec3& center);
    Polytope(TriangleTag, const Vec3& a, const Vec3& b, const Vec3& c);

    std::array<Vec3, 8> ownVertices_{};  // box or triangle corners
    std::array<Vec3, 2> ownNormals_{};   // triangle front and back
    std::array<double, 6> ownOffsets_{};
    mutable double size_ = -1.0;         // < 0: not measured yet
    Vec3 localCentroid_ = Vec3::Zero();  // center in the shape frame
    // A hull made without its edge topology (hand-built HullData; buildConvexHull and
    // makeBoxHull always provide it) gets it computed here, the one allocating case.
    std::vector<std::array<int, 2>> ownEdges_, ownEdgeFaces_;
};

/// A hull (shape frame) at world pose (rotation, position).
Polytope makeHullPolytope(const HullData& hull, const Mat3& rotation, const Vec3& position);
/// A box of half sizes h with the given centre and rotation (columns: the box axes). Vertex i has
/// coordinate k positive when bit k of i is set; face 2k has normal +e_k and face 2k + 1 has
/// -e_k (the layout of makeBoxHull).
Polytope makeBoxPolytope(const Vec3& halfExtents, const Mat3& rotation, const Vec3& center);
/// A one-sided triangle (world, counter-clockwise seen from its front). Face 0 is the front,
/// face 1 the back.
Polytope makeTrianglePolytope(const Vec3& a, const Vec3& b, const Vec3& c);

/// Corner loops of the box faces, in the layout above.
const std::vector<std::vector<int>>& boxFaces();
/// Box edges: index 4 axis + k joins the two corners that differ in bit `axis` and whose other
/// two bits, read in increasing axis order, make the number k.
const std::vector<std::array<int, 2>>& boxEdges();

}  // namespace anyphys::native

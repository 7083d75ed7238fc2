#pragma once
// A convex polyhedron placed in the world, as the polyhedral collision routines see it: boxes,
// hulls and mesh triangles (a triangle is a flat polyhedron with a front and a back face).
#include <array>
#include <vector>

#include "anyphys/math.hpp"
#include "anyphys/peers/shape_data.hpp"

namespace anyphys::native {

struct Polytope {
    std::vector<Vec3> vertices;                            // world
    const std::vector<std::vector<int>>* faces = nullptr;  // vertex loops, counter-clockwise from outside
    std::vector<Vec3> normals;                             // world, outward, unit
    std::vector<double> offsets;                           // normals[f].dot(x) == offsets[f] on face f
    Vec3 center = Vec3::Zero();                            // an interior point (centroid)
    double size = 0.0;                                     // largest distance from center to a vertex (m)
    bool oneSided = false;                                 // mesh triangle: pushes shapes out of its front only

    // Edges, each once as (v0, v1), and per edge the faces on its left (the face walking
    // v0 -> v1) and right. Shared with static tables or the hull when precomputed, else owned.
    // A flat triangle has no edge faces: its two faces meet at every edge.
    const std::vector<std::array<int, 2>>* sharedEdges = nullptr;
    const std::vector<std::array<int, 2>>* sharedEdgeFaces = nullptr;
    std::vector<std::array<int, 2>> ownEdges, ownEdgeFaces;

    const std::vector<int>& face(int f) const { return (*faces)[f]; }
    int faceCount() const { return static_cast<int>(faces->size()); }
    /// Faces whose normals are separating axes: all, or the front of a one-sided triangle (a
    /// shape overlapping it is pushed out of the front, never through to the back).
    int axisFaceCount() const { return oneSided ? 1 : faceCount(); }
    const std::vector<std::array<int, 2>>& edges() const { return sharedEdges ? *sharedEdges : ownEdges; }
    const std::vector<std::array<int, 2>>& edgeFaces() const { return sharedEdgeFaces ? *sharedEdgeFaces : ownEdgeFaces; }
    /// A closed solid (every edge between two faces with distinct normals), not a flat triangle.
    bool closed() const { return !edgeFaces().empty(); }
    /// Index of a vertex farthest along d.
    int support(const Vec3& d) const;
    /// Lowest and highest value of d.dot(vertex).
    std::array<double, 2> project(const Vec3& d) const;
};

/// A hull (shape frame) at world pose xf.
Polytope makeHullPolytope(const HullData& hull, const Transform& xf);
/// A box of half sizes h at world pose xf. Vertex i has coordinate k positive when bit k of i is
/// set; face 2k has normal +e_k and face 2k + 1 has -e_k (the layout of makeBoxHull).
Polytope makeBoxPolytope(const Vec3& halfExtents, const Transform& xf);
/// The same with the pose as centre and rotation matrix (columns: the box axes).
Polytope makeBoxPolytope(const Vec3& halfExtents, const Vec3& center, const Mat3& rotation);
/// A one-sided triangle (world, counter-clockwise seen from its front). Face 0 is the front,
/// face 1 the back.
Polytope makeTrianglePolytope(const Vec3& a, const Vec3& b, const Vec3& c);

/// Corner loops of the box faces, in the layout above.
const std::vector<std::vector<int>>& boxFaces();
/// Box edges: index 4 axis + k joins the two corners that differ in bit `axis` and whose other
/// two bits, read in increasing axis order, make the number k.
const std::vector<std::array<int, 2>>& boxEdges();

}  // namespace anyphys::native

#pragma once
// A static triangle mesh prepared for collision: triangles, their normals and a bounding-volume
// hierarchy over them.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "anyphys/defs.hpp"
#include "collision/broad_phase.hpp"

namespace anyphys::native {

struct MeshData {
    std::vector<Vec3> vertices;                           // mesh frame
    std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
    std::vector<Vec3> normals;                            // unit, per triangle
    DynamicTree tree;                                     // proxies = triangle indices, tight boxes

    /// Builds from a validated mesh ShapeDef (vertices, indices).
    static std::shared_ptr<const MeshData> build(const ShapeDef& def);

    /// Calls visit(triangle) for triangles whose bounds overlap `box` (mesh frame); stop on false.
    void queryTriangles(const Aabb& box, FunctionRef<bool(int)> visit) const;

    /// The three corners of a triangle (mesh frame).
    std::array<Vec3, 3> triangleVertices(int triangle) const;
    /// Calls visit(triangle, maxDistance) for triangles whose bounds the ray meets (mesh frame);
    /// as DynamicTree::rayCast, visit returns the new clip distance (<= 0 stops).
    void rayCastTriangles(const Vec3& origin, const Vec3& dir, double maxDistance,
                          FunctionRef<double(int, double)> visit) const;
};

}  // namespace anyphys::native

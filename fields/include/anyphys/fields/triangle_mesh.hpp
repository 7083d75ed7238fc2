#pragma once
// A triangle mesh as the particle solvers see it: its triangles with unit normals, and a uniform
// grid over its bounds listing the triangles each cell touches, so a particle looks only at the
// triangles near its path. Meshes are static (validation allows them on static bodies only), so
// the grid is built once, with the body's field geometry, and never updated.
#include <array>
#include <cstdint>
#include <vector>

#include "anyphys/math.hpp"

namespace anyphys {

class TriangleMesh {
public:
    /// Triangles `indices` (three per triangle) over `vertices`, in the frame the caller chooses;
    /// degenerate triangles (no area, so no normal) are dropped.
    TriangleMesh(const std::vector<Vec3>& vertices, const std::vector<std::uint32_t>& indices);

    struct Triangle {
        Vec3 a, b, c;
        Vec3 normal;  ///< unit, (b - a) x (c - a): the side seen counter-clockwise
    };
    const std::vector<Triangle>& triangles() const { return triangles_; }
    const Vec3& boundsMin() const { return lo_; }
    const Vec3& boundsMax() const { return hi_; }

    /// The triangles whose grid cells overlap the box [lo, hi], each once, in index order (a
    /// superset of those the box touches; callers test the geometry).
    void candidates(const Vec3& lo, const Vec3& hi, std::vector<std::uint32_t>& out) const;

private:
    std::array<int, 3> cellOf(const Vec3& p) const;
    std::size_t cellIndex(int x, int y, int z) const;
    void buildGrid();

    std::vector<Triangle> triangles_;
    Vec3 lo_ = Vec3::Zero(), hi_ = Vec3::Zero();
    double cell_ = 1.0;
    std::array<int, 3> dims_{1, 1, 1};
    std::vector<std::uint32_t> cellStart_;  // cell -> first entry in cellTriangles_ (size cells + 1)
    std::vector<std::uint32_t> cellTriangles_;
};

}  // namespace anyphys

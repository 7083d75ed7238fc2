// The culling grid of a static triangle mesh: cells about the size of a typical triangle, each
// listing the triangles whose bounding boxes overlap it (counting sort into one flat array).
#include "anyphys/fields/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace anyphys {

TriangleMesh::TriangleMesh(const std::vector<Vec3>& vertices, const std::vector<std::uint32_t>& indices) {
    for (std::size_t k = 0; k + 2 < indices.size(); k += 3) {
        const Vec3 &a = vertices[indices[k]], &b = vertices[indices[k + 1]], &c = vertices[indices[k + 2]];
        const Vec3 twice = (b - a).cross(c - a);
        if (!(twice.norm() > 0.0)) continue;
        triangles_.push_back({a, b, c, twice.normalized()});
    }
    buildGrid();
}

void TriangleMesh::buildGrid() {
    if (triangles_.empty()) return;
    lo_ = hi_ = triangles_[0].a;
    double typical = 0.0;  // the mean of each triangle's longest box side
    for (const Triangle& t : triangles_) {
        const Vec3 tlo = t.a.cwiseMin(t.b).cwiseMin(t.c), thi = t.a.cwiseMax(t.b).cwiseMax(t.c);
        lo_ = lo_.cwiseMin(tlo);
        hi_ = hi_.cwiseMax(thi);
        typical += (thi - tlo).maxCoeff();
    }
    typical /= static_cast<double>(triangles_.size());
    const Vec3 extent = hi_ - lo_;
    // Cells of a typical triangle's size, but no more than a few per triangle (a mesh of a few
    // long slivers would otherwise get a huge grid): grow the cell until the count fits.
    cell_ = std::max(typical, 1e-9 * std::max(1.0, extent.maxCoeff()));
    const double limit = 4.0 * static_cast<double>(triangles_.size()) + 64.0;
    for (;;) {
        double cells = 1.0;
        for (int a = 0; a < 3; ++a) cells *= std::max(1.0, std::ceil(extent[a] / cell_));
        if (cells <= limit) break;
        cell_ *= 1.5;
    }
    for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / cell_)));
    const std::size_t cells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
    cellStart_.assign(cells + 1, 0);
    // Two passes over the triangles' cell ranges: count per cell, then fill.
    const auto forEachCell = [&](const Triangle& t, auto&& f) {
        const auto c0 = cellOf(t.a.cwiseMin(t.b).cwiseMin(t.c)), c1 = cellOf(t.a.cwiseMax(t.b).cwiseMax(t.c));
        for (int z = c0[2]; z <= c1[2]; ++z)
            for (int y = c0[1]; y <= c1[1]; ++y)
                for (int x = c0[0]; x <= c1[0]; ++x) f(cellIndex(x, y, z));
    };
    for (const Triangle& t : triangles_) forEachCell(t, [&](std::size_t c) { ++cellStart_[c + 1]; });
    for (std::size_t c = 0; c < cells; ++c) cellStart_[c + 1] += cellStart_[c];
    cellTriangles_.resize(cellStart_[cells]);
    std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
    for (std::uint32_t k = 0; k < triangles_.size(); ++k)
        forEachCell(triangles_[k], [&](std::size_t c) { cellTriangles_[fill[c]++] = k; });
}

std::array<int, 3> TriangleMesh::cellOf(const Vec3& p) const {
    std::array<int, 3> c{};
    for (int a = 0; a < 3; ++a) {
        const double x = std::floor((p[a] - lo_[a]) / cell_);
        c[a] = static_cast<int>(std::clamp(x, 0.0, static_cast<double>(dims_[a] - 1)));
    }
    return c;
}

std::size_t TriangleMesh::cellIndex(int x, int y, int z) const {
    return (static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x;
}

void TriangleMesh::candidates(const Vec3& lo, const Vec3& hi, std::vector<std::uint32_t>& out) const {
    out.clear();
    if (triangles_.empty() || (hi.array() < lo_.array()).any() || (lo.array() > hi_.array()).any()) return;
    const auto c0 = cellOf(lo), c1 = cellOf(hi);
    for (int z = c0[2]; z <= c1[2]; ++z)
        for (int y = c0[1]; y <= c1[1]; ++y)
            for (int x = c0[0]; x <= c1[0]; ++x) {
                const std::size_t c = cellIndex(x, y, z);
                out.insert(out.end(), cellTriangles_.begin() + cellStart_[c], cellTriangles_.begin() + cellStart_[c + 1]);
            }
    // A triangle spanning several cells is listed in each: once is enough.
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace anyphys

// The particle solvers' neighbour search: a uniform grid of cells as large as the search radius,
// stored in a hash table so it costs memory per particle, not per cell of the space they span.
#include <algorithm>
#include <cmath>

#include "anyphys/fields/particles.hpp"

namespace anyphys {

std::size_t ParticleGrid::bucketOf(long long x, long long y, long long z) const {
    // Large odd multipliers spread neighbouring cells over the table (Teschner et al. 2003).
    const auto h = static_cast<std::uint64_t>(x) * 73856093ull ^ static_cast<std::uint64_t>(y) * 19349663ull ^
                   static_cast<std::uint64_t>(z) * 83492791ull;
    return static_cast<std::size_t>(h) & mask_;
}

void ParticleGrid::build(const std::vector<Vec3>& points, double cell) {
    cell_ = cell;
    std::size_t buckets = 64;
    while (buckets < 2 * points.size()) buckets *= 2;
    mask_ = buckets - 1;
    start_.assign(buckets + 1, 0);
    seen_.assign(buckets, 0);
    query_ = 0;
    order_.resize(points.size());
    if (points.empty()) return;
    lo_ = hi_ = points[0];
    for (const Vec3& p : points) {
        lo_ = lo_.cwiseMin(p);
        hi_ = hi_.cwiseMax(p);
    }
    const auto cellOf = [&](double v) { return static_cast<long long>(std::floor(v / cell_)); };
    std::vector<std::uint32_t>& bucketOfPoint = scratch_;
    bucketOfPoint.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec3& p = points[i];
        bucketOfPoint[i] = static_cast<std::uint32_t>(bucketOf(cellOf(p.x()), cellOf(p.y()), cellOf(p.z())));
        ++start_[bucketOfPoint[i] + 1];
    }
    for (std::size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i) order_[fill[bucketOfPoint[i]]++] = static_cast<std::uint32_t>(i);
}

void ParticleGrid::neighbours(const std::vector<Vec3>& points, std::size_t i, double radius,
                              std::vector<std::uint32_t>& out) const {
    const Vec3& p = points[i];
    const double r2 = radius * radius;
    const Vec3 reach = Vec3::Constant(radius);
    forEachInBox(p - reach, p + reach, [&](std::uint32_t j) {
        if (j != i && (points[j] - p).squaredNorm() < r2) out.push_back(j);
    });
}

}  // namespace anyphys

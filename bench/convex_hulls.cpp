// Building a convex hull (quickhull, faces merged, checked; api/src/geometry/convex_hull.cpp)
// from n points on a unit sphere and n more inside it, radius 0.5: every sphere point is a
// vertex, so the hull has about 2n triangles and each stage meets its largest input.
//   convex_hull/<n>: one build, n = 1 000, 5 000, 20 000.
// A cost growing like n^2 shows as a 16x step between 5 000 and 20 000; n log n as about 4.6x.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "geometry/convex_hull.hpp"

namespace anyphys {
namespace {

std::vector<Vec3> sphereWithInterior(int n) {
    std::mt19937 rng(3);
    std::normal_distribution<double> gauss;
    std::vector<Vec3> points;
    // One draw per statement: the arguments of one call run in an order the compiler picks.
    const auto direction = [&] {
        const double x = gauss(rng);
        const double y = gauss(rng);
        const double z = gauss(rng);
        return Vec3(x, y, z).normalized();
    };
    for (int i = 0; i < n; ++i) points.push_back(direction());
    for (int i = 0; i < n; ++i) points.push_back(0.5 * direction());
    return points;
}

void convexHull(benchmark::State& state) {
    const std::vector<Vec3> points = sphereWithInterior(static_cast<int>(state.range(0)));
    std::size_t faces = 0;
    for (auto _ : state) {
        const auto hull = buildConvexHull(points);
        faces = hull->faces.size();
        benchmark::DoNotOptimize(hull);
    }
    state.counters["faces"] = static_cast<double>(faces);
    state.counters["points"] = static_cast<double>(points.size());
}

BENCHMARK(convexHull)->Name("convex_hull")->Arg(1000)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace anyphys

BENCHMARK_MAIN();

#include "outcome.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "box_overlap.hpp"

namespace anyphys::bench {
namespace {

bool finite(const BoxState& b) {
    return b.position.allFinite() && b.orientation.coeffs().allFinite() && b.velocity.allFinite();
}

/// Deepest box-box overlap. Boxes are swept in x order, so only neighbours within reach are
/// tested (50 000 boxes would be 1.25e9 pairs otherwise).
double deepestBoxOverlap(const std::vector<OrientedBox>& boxes) {
    constexpr double kReach = 2.0 * 0.8661;  // centres farther apart than 2 half diagonals cannot touch
    std::vector<std::size_t> order(boxes.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return boxes[a].center.x() < boxes[b].center.x(); });
    double deepest = 0.0;
    for (std::size_t i = 0; i < order.size(); ++i) {
        const OrientedBox& a = boxes[order[i]];
        for (std::size_t j = i + 1; j < order.size(); ++j) {
            const OrientedBox& b = boxes[order[j]];
            if (b.center.x() - a.center.x() > kReach) break;
            if ((a.center - b.center).squaredNorm() < kReach * kReach)
                deepest = std::max(deepest, boxPenetration(a, b));
        }
    }
    return deepest;
}

}  // namespace

Outcome assess(const ScenePlan& plan, const std::vector<BoxState>& boxes) {
    Outcome out;
    std::vector<OrientedBox> poses;
    poses.reserve(boxes.size());
    const Vec3 half = Vec3::Constant(kHalf);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const BoxState& b = boxes[i];
        if (!finite(b)) {
            ++out.nonFinite;
            continue;
        }
        const OrientedBox pose{b.position, b.orientation.normalized().toRotationMatrix(), half};
        out.groundPenetration = std::max(out.groundPenetration, groundPenetration(pose));
        poses.push_back(pose);
        const Vec3& start = plan.starts[i];
        const double move = std::hypot(b.position.x() - start.x(), b.position.z() - start.z());
        out.maxMove = std::max(out.maxMove, move);
        if (move > kMovedDistance) ++out.moved;
        out.maxSpeed = std::max(out.maxSpeed, b.velocity.norm());
    }
    out.penetration = std::max(out.groundPenetration, deepestBoxOverlap(poses));
    out.settled = out.nonFinite == 0 && out.maxSpeed < kSettledSpeed;
    return out;
}

}  // namespace anyphys::bench

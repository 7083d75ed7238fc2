#include "ode_ahead_sweep.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace anyphys::ode {
namespace {

// Shapes longer than this many times the median along the sweep's axis (a ground, a wall) are
// left out of the sorted list, where each would widen every moving shape's backward scan to its
// own length; every moving shape tests them directly instead.
constexpr double kBigExtent = 4.0;
// Testing a moving shape against every shape costs about as much as sorting two shapes (a
// comparison each per level of the sort): below this many moving shapes per bit of the count,
// the direct tests are cheaper.
constexpr std::size_t kFewMoversPerLog2 = 2;
constexpr std::uint32_t kNotSorted = std::numeric_limits<std::uint32_t>::max();

// Whether `a` grown by `reach` on every side overlaps `b`.
bool within(const SweptBounds& a, const SweptBounds& b, double reach) {
    for (int k = 0; k < 3; ++k)
        if (a.lo[k] - reach > b.hi[k] || b.lo[k] > a.hi[k] + reach) return false;
    return true;
}

bool apart(const SweptBounds& a, const SweptBounds& b) { return !within(a, b, 0.0); }

// The axis along which the shapes' centres spread most: the one that separates them best. Bounds
// infinite along an axis (a plane's half space) have no centre there.
int widestAxis(const std::vector<SweptBounds>& shapes) {
    double sum[3] = {0, 0, 0}, squares[3] = {0, 0, 0}, count[3] = {0, 0, 0};
    for (const SweptBounds& s : shapes)
        for (int k = 0; k < 3; ++k) {
            const double centre = 0.5 * (s.lo[k] + s.hi[k]);
            if (!std::isfinite(centre)) continue;
            sum[k] += centre;
            squares[k] += centre * centre;
            count[k] += 1.0;
        }
    int widest = 0;
    double most = -1.0;
    for (int k = 0; k < 3; ++k) {
        const double spread = count[k] > 0.0 ? squares[k] - sum[k] * sum[k] / count[k] : 0.0;
        if (spread > most) most = spread, widest = k;
    }
    return widest;
}

}  // namespace

const std::vector<AheadSweep::Pair>& AheadSweep::find(const std::vector<SweptBounds>& shapes) {
    pairs_.clear();
    movers_.clear();
    const auto n = static_cast<std::uint32_t>(shapes.size());
    for (std::uint32_t i = 0; i < n; ++i)
        if (shapes[i].reach > 0.0) movers_.push_back(i);
    if (movers_.empty()) return pairs_;
    const auto consider = [&](std::uint32_t mover, std::uint32_t other) {
        const SweptBounds& a = shapes[mover];
        const SweptBounds& b = shapes[other];
        if (other == mover || !within(a, b, a.reach) || !apart(a, b)) return;
        // Both move and each reaches the other: listed from the first (its own scan finds it).
        if (b.reach > 0.0 && other < mover && within(b, a, b.reach)) return;
        pairs_.emplace_back(mover, other);
    };
    // A few moving shapes among many (a box dropped on a sleeping pile): each tested against every
    // shape costs less than sorting them all.
    if (movers_.size() < kFewMoversPerLog2 * std::bit_width(n)) {
        for (const std::uint32_t m : movers_)
            for (std::uint32_t j = 0; j < n; ++j) consider(m, j);
        std::sort(pairs_.begin(), pairs_.end());
        return pairs_;
    }

    const int axis = widestAxis(shapes);
    const auto extent = [&](std::uint32_t i) { return shapes[i].hi[axis] - shapes[i].lo[axis]; };
    extents_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) extents_[i] = extent(i);
    std::nth_element(extents_.begin(), extents_.begin() + n / 2, extents_.end());
    const double median = extents_[n / 2];
    const double bigAbove = median > 0.0 ? kBigExtent * median : std::numeric_limits<double>::infinity();
    sorted_.clear();
    big_.clear();
    double widest = 0.0;  // of the sorted shapes, along the axis: how far back a scan must look
    for (std::uint32_t i = 0; i < n; ++i) {
        if (extent(i) > bigAbove) {
            big_.push_back(i);
        } else {
            sorted_.push_back(i);
            widest = std::max(widest, extent(i));
        }
    }
    std::sort(sorted_.begin(), sorted_.end(), [&](std::uint32_t a, std::uint32_t b) {
        return shapes[a].lo[axis] < shapes[b].lo[axis] || (shapes[a].lo[axis] == shapes[b].lo[axis] && a < b);
    });
    positionOf_.assign(n, kNotSorted);
    for (std::uint32_t p = 0; p < sorted_.size(); ++p) positionOf_[sorted_[p]] = p;

    for (const std::uint32_t m : movers_) {
        const SweptBounds& a = shapes[m];
        const std::uint32_t p = positionOf_[m];
        if (p == kNotSorted) {  // a big shape that moves (a platform): against every shape
            for (std::uint32_t j = 0; j < n; ++j) consider(m, j);
            continue;
        }
        for (std::size_t q = p + 1; q < sorted_.size() && shapes[sorted_[q]].lo[axis] <= a.hi[axis] + a.reach; ++q)
            consider(m, sorted_[q]);
        for (std::size_t q = p; q-- > 0 && shapes[sorted_[q]].lo[axis] >= a.lo[axis] - widest - a.reach;)
            consider(m, sorted_[q]);
        for (const std::uint32_t b : big_) consider(m, b);
    }
    std::sort(pairs_.begin(), pairs_.end());
    return pairs_;
}

}  // namespace anyphys::ode

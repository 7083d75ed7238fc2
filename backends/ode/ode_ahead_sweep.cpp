#include "ode_ahead_sweep.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <tuple>

namespace anyphys::ode {
namespace {

// Shapes longer than this many times the median (a ground, a wall) are left out of the sorted
// list, where each would widen every moving shape's columns and backward scan to its own length;
// every moving shape tests them directly instead.
constexpr double kBigExtent = 4.0;
// Testing a moving shape against every shape costs about as much as sorting two shapes (a
// comparison each per level of the sort): below this many moving shapes per bit of the count,
// the direct tests are cheaper.
constexpr std::size_t kFewMoversPerLog2 = 2;

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

    // Sorted along the axis the centres spread most, in columns across it as wide as the widest
    // shape plus the longest reach: a moving shape then meets only shapes whose bounds start in
    // its own column or the eight beside it, near it along the axis. (Along the axis alone, a box
    // in a 10 x 10 x 10 pile visited the hundred boxes of its slab.)
    const int axis = widestAxis(shapes), across1 = (axis + 1) % 3, across2 = (axis + 2) % 3;
    const auto size = [&](std::uint32_t i) {  // the longest side
        const SweptBounds& b = shapes[i];
        return std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
    };
    extents_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) extents_[i] = size(i);
    std::nth_element(extents_.begin(), extents_.begin() + n / 2, extents_.end());
    const double median = extents_[n / 2];
    const double bigAbove = median > 0.0 ? kBigExtent * median : std::numeric_limits<double>::infinity();
    sorted_.clear();
    big_.clear();
    double widest = 0.0, longestReach = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        if (size(i) > bigAbove) {
            big_.push_back(i);
        } else {
            sorted_.push_back(i);
            widest = std::max(widest, size(i));
        }
        longestReach = std::max(longestReach, shapes[i].reach);
    }
    const double column = widest + longestReach;
    if (!std::isfinite(column)) {  // most shapes unbounded (planes): nothing to sort them by
        for (const std::uint32_t m : movers_)
            for (std::uint32_t j = 0; j < n; ++j) consider(m, j);
        std::sort(pairs_.begin(), pairs_.end());
        return pairs_;
    }
    // Clamped so the conversion is defined however far out a shape is (columns then merge there).
    const auto columnAt = [&](double x) { return static_cast<std::int64_t>(std::clamp(std::floor(x / column), -1e15, 1e15)); };
    columnOf_.resize(n);
    for (const std::uint32_t i : sorted_) columnOf_[i] = {columnAt(shapes[i].lo[across1]), columnAt(shapes[i].lo[across2])};
    const auto key = [&](std::uint32_t i) { return std::tuple(columnOf_[i].first, columnOf_[i].second, shapes[i].lo[axis], i); };
    std::sort(sorted_.begin(), sorted_.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });

    for (const std::uint32_t m : movers_) {
        const SweptBounds& a = shapes[m];
        if (size(m) > bigAbove) {  // a big shape that moves (a platform): against every shape
            for (std::uint32_t j = 0; j < n; ++j) consider(m, j);
            continue;
        }
        const double from = a.lo[axis] - widest - a.reach, to = a.hi[axis] + a.reach;
        for (std::int64_t d1 = -1; d1 <= 1; ++d1)
            for (std::int64_t d2 = -1; d2 <= 1; ++d2) {
                const std::pair<std::int64_t, std::int64_t> beside{columnOf_[m].first + d1, columnOf_[m].second + d2};
                auto q = std::lower_bound(sorted_.begin(), sorted_.end(), beside, [&](std::uint32_t i, const auto& c) {
                    return columnOf_[i] < c || (columnOf_[i] == c && shapes[i].lo[axis] < from);
                });
                for (; q != sorted_.end() && columnOf_[*q] == beside && shapes[*q].lo[axis] <= to; ++q) consider(m, *q);
            }
        for (const std::uint32_t b : big_) consider(m, b);
    }
    std::sort(pairs_.begin(), pairs_.end());
    return pairs_;
}

}  // namespace anyphys::ode

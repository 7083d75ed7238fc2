#pragma once
// The look-ahead pass's broad phase (OdeWorld::collideAhead): the pairs whose bounds are apart
// now but which a moving shape reaches within the step.
//
// ODE's dSpaceCollide2 of one geom against a hash space tests every geom of the space (its source
// notes that this query leaves the hash unused), so asking it once per moving shape cost moving x
// all: half of a 4 000-box drop's step while the boxes fell.
// This sorts the bounds once along their widest axis, in columns across it, and each moving shape
// visits only the shapes beside it.
#include <cstdint>
#include <utility>
#include <vector>

namespace anyphys::ode {

/// A shape's bounds now, and how far it may reach within the step (0 for one that does not move).
struct SweptBounds {
    double lo[3], hi[3];  // m, world axes; infinite for a plane's half space, never NaN
    double reach;         // m
};

class AheadSweep {
public:
    using Pair = std::pair<std::uint32_t, std::uint32_t>;
    /// Pairs (i, j) of `shapes` whose bounds do not overlap but come within i's reach of each
    /// other on every axis (i moves). A pair either of whose shapes reaches the other is listed
    /// once, from the one listed first in `shapes` whose reach covers the gap; pairs come in
    /// order of i, then j. Valid until the next call.
    const std::vector<Pair>& find(const std::vector<SweptBounds>& shapes);

private:
    std::vector<std::uint32_t> sorted_, big_, movers_;
    std::vector<double> extents_;
    std::vector<std::pair<std::int64_t, std::int64_t>> columnOf_;  // by shape: its column across the sort axis
    std::vector<Pair> pairs_;
};

}  // namespace anyphys::ode

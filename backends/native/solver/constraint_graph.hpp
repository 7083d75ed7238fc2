#pragma once
// Graph colouring of one step's constraints: no colour holds two constraints on the same dynamic
// body, so the constraints of a colour can be solved at once, four to a SIMD register and on
// several workers, with the same result in any order. Static and kinematic bodies take no
// impulses and so never conflict.
//
// Greedy, in constraint order: each constraint takes the lowest colour that neither of its
// dynamic bodies uses yet (one bit scan over a mask per body). A constraint whose bodies already
// use every colour goes to the overflow, solved one constraint at a time after the colours. The
// order, and so every result, depends only on the constraint order.
#include <cstdint>
#include <span>
#include <vector>

#include "solver/contact_constraint.hpp"

namespace anyphys::native {

class ConstraintGraph {
public:
    static constexpr int kMaxColors = 32;

    struct Color {
        int firstLane = 0;  // into lanes()
        int laneCount = 0;
    };

    /// Colours `constraints` (solver body indices into `bodies`).
    void build(std::span<const ContactLane> constraints, std::span<const SolverBody> bodies);

    /// Non-empty colours in order, then (if any) the overflow as the last entry.
    const std::vector<Color>& colors() const { return colors_; }
    bool hasOverflow() const { return hasOverflow_; }
    /// Constraint indices grouped by colour.
    const std::vector<int>& lanes() const { return order_; }

private:
    std::vector<std::uint32_t> used_;  // per body: colours taken
    std::vector<std::int8_t> colorOf_; // per constraint; kMaxColors = overflow
    std::vector<int> order_;
    std::vector<Color> colors_;
    bool hasOverflow_ = false;
};

}  // namespace anyphys::native

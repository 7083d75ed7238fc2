#include "solver/constraint_graph.hpp"

#include <algorithm>
#include <array>
#include <bit>

namespace anyphys::native {

namespace {

// Bits of the order key to sort by: about one constraint per bucket, at most 64 Ki buckets.
int keyBits(std::size_t count) {
    int bits = 1;
    while (bits < 16 && (std::size_t(1) << bits) < count) ++bits;
    return bits;
}

}  // namespace

void ConstraintGraph::build(std::span<const ContactLane> constraints, std::span<const SolverBody> bodies) {
    used_.assign(bodies.size(), 0u);
    colorOf_.resize(constraints.size());
    // Visiting order: one counting-sort pass on the key's top bits (ties keep their order).
    const int bits = keyBits(constraints.size());
    bucketStart_.assign((std::size_t(1) << bits) + 1, 0);
    for (const ContactLane& c : constraints) ++bucketStart_[(c.orderKey >> (32 - bits)) + 1];
    for (std::size_t k = 1; k < bucketStart_.size(); ++k) bucketStart_[k] += bucketStart_[k - 1];
    visit_.resize(constraints.size());
    for (std::size_t i = 0; i < constraints.size(); ++i)
        visit_[bucketStart_[constraints[i].orderKey >> (32 - bits)]++] = static_cast<int>(i);
    std::array<int, kMaxColors + 1> count{};
    static_assert(kMaxColors == 32);
    // Colours open to constraints between two dynamic bodies; the top ones stay free for
    // constraints with static bodies.
    constexpr std::uint32_t kDynamicColors = (1u << 28) - 1;
    const auto takesImpulses = [&](std::int32_t body) { return body != kStaticBody && bodies[body].dynamic; };
    for (const int i : visit_) {
        const ContactLane& c = constraints[i];
        const bool a = takesImpulses(c.bodyA), b = takesImpulses(c.bodyB);
        const std::uint32_t used = (a ? used_[c.bodyA] : 0u) | (b ? used_[c.bodyB] : 0u);
        int color = kMaxColors;
        if (a && b) {
            const std::uint32_t free = ~used & kDynamicColors;
            if (free != 0) color = std::countr_zero(free);
        } else {
            // A constraint on one dynamic body (against the ground, say) takes the highest free
            // colour, so it is solved after the constraints between moving bodies: the support
            // has the last word in every pass, as in Box2D v3.
            const std::uint32_t free = ~used & ~1u;
            if (free != 0) color = 31 - std::countl_zero(free);
        }
        if (color < kMaxColors) {
            if (a) used_[c.bodyA] |= 1u << color;
            if (b) used_[c.bodyB] |= 1u << color;
        }
        colorOf_[i] = static_cast<std::int8_t>(color);
        ++count[color];
    }
    // Grouped by colour. Within a colour the constraints share no dynamic body, so their order
    // changes no result: they are placed by their first body's index, and the passes then read
    // the bodies' states nearly in sequence instead of in hash order (at 50 000 bodies the
    // states no longer fit in cache). The overflow is solved one constraint after another, so
    // it keeps the visiting order.
    std::array<int, kMaxColors + 1> start{};
    colors_.clear();
    int next = 0;
    for (int color = 0; color <= kMaxColors; ++color) {
        start[color] = next;
        if (count[color] > 0) colors_.push_back({next, count[color]});
        next += count[color];
    }
    hasOverflow_ = count[kMaxColors] > 0;
    order_.resize(constraints.size());
    sortByFirstBody(constraints, bodies.size());
    for (const int i : byBody_)
        if (colorOf_[i] < kMaxColors) order_[start[colorOf_[i]]++] = i;
    for (const int i : visit_)
        if (colorOf_[i] == kMaxColors) order_[start[kMaxColors]++] = i;
}

void ConstraintGraph::sortByFirstBody(std::span<const ContactLane> constraints, std::size_t bodyCount) {
    // Counting sort on the lower solver body index (a static partner has none).
    const auto firstBody = [](const ContactLane& c) {
        const std::uint32_t a = static_cast<std::uint32_t>(c.bodyA), b = static_cast<std::uint32_t>(c.bodyB);
        return std::min(a, b);  // kStaticBody (-1) is the largest as unsigned; both static cannot happen
    };
    bucketStart_.assign(bodyCount + 1, 0);
    for (const ContactLane& c : constraints) ++bucketStart_[firstBody(c) + 1];
    for (std::size_t k = 1; k < bucketStart_.size(); ++k) bucketStart_[k] += bucketStart_[k - 1];
    byBody_.resize(constraints.size());
    for (std::size_t i = 0; i < constraints.size(); ++i) byBody_[bucketStart_[firstBody(constraints[i])]++] = static_cast<int>(i);
}

}  // namespace anyphys::native

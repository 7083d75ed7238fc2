#pragma once
// Springs on one body add up: each may be soft enough to step explicitly alone while several
// together are not. So a backend steps a spring's stiffness explicitly only while
// k h^2 K n stays in range, n the sprung joints on the busier of the spring's two bodies
// (docs/architecture.md, beside the joint table). This counts n over any engine's body handles,
// for the ODE, Bullet and Box2D worlds; native counts over its body indices.
#include <algorithm>
#include <functional>
#include <vector>

namespace anyphys {

/// How many sprung joints each moving body has, rebuilt before each step. Keeps its capacity, so
/// a steady step does not allocate.
template <class Body>
class SpringsPerBody {
public:
    /// Starts a new count.
    void clear() { bodies_.clear(); }
    /// One body of a sprung joint. Add only bodies that move: a static or kinematic body is not
    /// set swinging by its springs, and a body never added counts 0.
    void add(const Body* body) { bodies_.push_back(body); }
    /// After the last add, before any query.
    void sort() { std::sort(bodies_.begin(), bodies_.end(), std::less<const Body*>{}); }
    bool empty() const { return bodies_.empty(); }

    /// The sprung joints on the busier of a and b: at least 1, the joint asking.
    int onBusierBody(const Body* a, const Body* b) const { return std::max({1, on(a), on(b)}); }

private:
    int on(const Body* body) const {
        const auto [first, last] = std::equal_range(bodies_.begin(), bodies_.end(), body, std::less<const Body*>{});
        return static_cast<int>(last - first);
    }

    std::vector<const Body*> bodies_;  // each sprung joint's moving bodies, sorted
};

}  // namespace anyphys

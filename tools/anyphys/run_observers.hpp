#pragma once
// Watchers of one sweep run that see the world after every step: the deepest contact and the
// widest joint gap over the run (the constraint errors a fast, loose setting trades for speed).
#include <optional>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::cli {

/// Largest contact depth over the run, from the contact events (enter and stay points).
class PenetrationWatch {
public:
    /// Measures only where contacts and their events are simulated; otherwise value() is empty.
    explicit PenetrationWatch(const World& world);
    void observe(const World& world);
    std::optional<double> value() const;

private:
    bool active_ = false;
    double worst_ = 0.0;
};

/// Largest joint gap over the run: for joints that hold a point together (fixed, ball, hinge,
/// cone) the distance between the anchor carried by body A and by body B (or the world); for a
/// slider, the part of that separation off its axis (sliding along it is the joint's motion).
/// Distance and wheel joints, which let the anchors part by design, are not measured.
class JointGapWatch {
public:
    /// Anchors are fixed in each body's frame from `states` (the bodies at creation, scene order).
    JointGapWatch(const Scene& scene, const std::vector<BodyState>& states);
    void observe(const std::vector<BodyState>& states);
    std::optional<double> value() const;  ///< empty when the scene has no measured joint

private:
    struct Link {
        std::optional<std::size_t> a, b;  ///< body indices; nothing = the world
        Vec3 localA, localB;              ///< the anchor in each body's frame
        std::optional<Vec3> axisInA;      ///< slider: its axis in A's frame
    };
    std::vector<Link> links_;
    double worst_ = 0.0;
};

}  // namespace anyphys::cli

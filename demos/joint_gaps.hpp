#pragma once
// Measures of an articulated scene a demo reports: how far joints open (the distance between a
// joint's anchor on body A, or in the world, and on body B) and how far hinges leave their limits.
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::demo {

class JointMeter {
public:
    JointMeter(const Scene& scene, const SceneObjects& objects);
    /// Measures now.
    void observe();
    double worstGap() const { return worstGap_; }             ///< m
    double worstLimitViolation() const { return worstLimit_; }  ///< rad, hinges with limits

private:
    struct Anchored {
        Body a, b;
        Vec3 onA, onB;  // the anchor in each body's frame (onA in the world without A)
    };
    struct LimitedHinge {
        Joint joint;
        JointLimits limits;
    };
    std::vector<Anchored> anchors_;
    std::vector<LimitedHinge> hinges_;
    double worstGap_ = 0.0, worstLimit_ = 0.0;
};

/// The first time after which every body stayed slower than `speed` (m/s) to the end of the run.
class RestTimer {
public:
    explicit RestTimer(double speed) : speed_(speed) {}
    void observe(double time, const std::vector<Body>& bodies);
    /// Negative while something still moves.
    double restTime() const { return moving_ ? -1.0 : since_; }

private:
    double speed_, since_ = 0.0;
    bool moving_ = true;
};

}  // namespace anyphys::demo

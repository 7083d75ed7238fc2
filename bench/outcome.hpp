#pragma once
// What a run left behind, judged from the boxes' final poses and velocities alone, so every
// engine is measured by the same code (after shared/peers/scene_common.h's sc_report).
#include <vector>

#include "anyphys/math.hpp"
#include "scenes.hpp"

namespace anyphys::bench {

struct BoxState {
    Vec3 position;
    Quat orientation;
    Vec3 velocity;
};

struct Outcome {
    double penetration = 0.0;        ///< m, deepest overlap, box-box or box-ground (separating axes)
    double groundPenetration = 0.0;  ///< m, deepest box corner below y = 0
    double maxSpeed = 0.0;           ///< m/s, fastest box
    double maxMove = 0.0;            ///< m, largest sideways (x, z) distance from the start
    int moved = 0;                   ///< boxes farther than kMovedDistance sideways from their start
    int nonFinite = 0;               ///< boxes with a non-finite pose or velocity (left out of the rest)
    bool settled = false;            ///< every box finite and slower than kSettledSpeed
};

/// `boxes[i]` is the final state of the box that started at `plan.starts[i]`.
Outcome assess(const ScenePlan& plan, const std::vector<BoxState>& boxes);

}  // namespace anyphys::bench

#pragma once
// The stages of the native free-body pipeline.
#include <memory>
#include <vector>

#include "pipeline.hpp"

namespace anyphys::native {

/// Backward-Euler gyroscopic update for bodies in implicit mode (a split step before integration).
std::unique_ptr<Stage> makeImplicitGyroscopicStage();
/// Advances dynamic bodies with the world's integrator (forces evaluated per stage) and kinematic
/// bodies exactly at their constant velocity.
std::unique_ptr<Stage> makeIntegrateStage();
/// Clears the user forces and torques accumulated for this step.
std::unique_ptr<Stage> makeClearForcesStage();

/// Every stage in execution order: collide, [gyroscopic_implicit, integrate] per substep,
/// solve_contacts, continuous, sleep, clear_forces.
std::vector<std::unique_ptr<Stage>> makePipeline();

}  // namespace anyphys::native

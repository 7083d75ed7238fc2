#pragma once
// The AgentPhysics thesis' other demos, each written once against anyphys (demos.cpp dispatches).
#include <string>
#include <vector>

#include "demo_support.hpp"

namespace anyphys::demo {

int runVolumes(const DemoOptions& o);       ///< compound bodies: several collision volumes per body
int runMaterials(const DemoOptions& o);     ///< ice, wood and rubber side by side
int runJoints(const DemoOptions& o);        ///< every joint type the backend has, with limits and motors
int runDynamics(const DemoOptions& o);      ///< forces, torques, impulses, gyroscopic motion
/// The same scene in one world per backend, stepped together in one process.
int runSimultaneous(const DemoOptions& o, const std::vector<std::string>& backends);

/// A static ground plane named "ground".
BodyDef groundPlane();
/// "measured vs expected" line of a summary, with the relative error.
void printCheck(const std::string& what, double measured, double expected, const std::string& unit);

}  // namespace anyphys::demo

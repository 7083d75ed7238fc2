#pragma once
// Joint springs of the ODE backend, where the spring is soft. An ODE row softened with ERP and
// CFM (ODE manual) is an implicit spring-damper over the whole ODE step: stable at any
// stiffness, but it damps a free oscillation by itself (a 0.7 Hz undamped slider spring at 60 Hz
// kept 23 % of its swing after 10 s). Where the step resolves the spring, its stiffness is a
// force instead, -k C from the ODE step's start, added to the bodies like any external force:
// ODE integrates it with semi-implicit Euler, which keeps a free spring's energy. The damping
// stays in the row (ERP 0, CFM 1 / c: an implicit damper). Soft means k h^2 K n <= 0.5, with K
// the inverse effective mass along the spring and n the sprung joints on the busier body: n
// springs on one body add up (a row sum of M^-1/2 K M^-1/2), and the bound keeps h^2 lambda_max
// well under the 4 where semi-implicit Euler diverges. K is the spring row's own, except for a
// hinge, whose pin turns B about the anchor: there K is taken with the pin's rows acting (a box
// on a 1 m arm is 150 times heavier to turn about the anchor than about its centre).
#include "anyphys/math.hpp"

namespace anyphys::ode {

class OdeBody;

/// Where a spring acts: about an axis (hinge), or along one, at a point of each body (distance:
/// the anchors; slider and wheel: B's anchor for both).
struct SpringLine {
    Vec3 axis = Vec3::UnitX();  ///< unit; B's stretch grows along (or about) it
    bool angular = false;
    Vec3 atA = Vec3::Zero(), atB = Vec3::Zero();  ///< world points, linear springs
    double stretch = 0.0;                         ///< C: m or rad from the rest position
};

/// 1/kg or 1/(kg m^2): the inverse effective mass along `line` of bodies a and b (null, static
/// or kinematic: none).
double inverseMassAlong(const SpringLine& line, const OdeBody* a, const OdeBody* b);

/// 1/(kg m^2): the inverse effective inertia about a hinge's `axis` of bodies a and b with the
/// hinge's pin at `anchor` acting (three point rows there, two keeping the axes aligned).
double hingeInverseInertia(const Vec3& axis, const Vec3& anchor, const OdeBody* a, const OdeBody* b);

/// True where a spring of stiffness k steps explicitly over ODE steps of h seconds.
bool springStepsExplicitly(double k, double h, double inverseMass, int springsOnBusierBody);

/// What an explicit spring pushed on B: the force, and the torque about B's centre.
struct SpringPush {
    Vec3 force = Vec3::Zero();
    Vec3 torque = Vec3::Zero();
};

/// Adds -k C along `line` to B and its opposite to A, each if it is an awake dynamic body, as
/// ODE forces of the next ODE step (ODE clears its accumulators after each step).
SpringPush pushSpring(const SpringLine& line, double stiffness, const OdeBody* a, const OdeBody* b);

}  // namespace anyphys::ode

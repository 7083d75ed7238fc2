#pragma once
// Turning a validated JointDef into what a backend receives (JointPeerDef), so that every engine
// gets the same frames, rest lengths and spring constants. Pure functions of the def and the
// bodies' peer frames and masses: unit-tested without a backend.
#include <optional>

#include "anyphys/joint_def.hpp"
#include "anyphys/math.hpp"
#include "anyphys/peers/joint_peer.hpp"

namespace anyphys {

/// What resolution needs of a body: its peer frame and mass properties.
struct JointBodyFrame {
    Transform pose;                  ///< the peer frame (centre of mass, principal axes) in the world
    double mass = 0.0;               ///< kg; 0 for a body the joint cannot move (static, kinematic)
    Vec3 inertia = Vec3::Zero();     ///< kg m^2, principal moments about the axes of `pose`
};

/// The def with `axis` made unit and, for a wheel, `spinAxis` made unit and exactly perpendicular
/// to it (the validated def is perpendicular within 1e-4).
JointDef normalizedJointDef(const JointDef& def);

/// The joint frame in the world at creation: origin at the anchor; X along the axis (a planar
/// ball joint: +Z, it runs as a hinge); Y along the spin axis for a wheel, otherwise the unit
/// vector perpendicular to X nearest world +Y (world +Z when X is within 25 deg of Y); Z = X x Y.
/// A distance joint's frame sits at anchorA with X along anchorB - anchorA.
Transform jointFrame(const JointDef& def, bool planar);

/// kg: the mass that resists motion along a line between the bodies, 1 / (1/mA + 1/mB); a body
/// the joint cannot move (mass 0, or no body: the world) adds nothing to the sum.
double effectiveMass(const std::optional<JointBodyFrame>& a, const JointBodyFrame& b);

/// kg m^2: the inertia that resists turning about `axis` (unit, world) through `point`, 1 / (1/IA
/// + 1/IB), each I = axis . I_world axis + m |r x axis|^2 with r from `point` to the centre of
/// mass (the parallel-axis theorem); the world and unmovable bodies add nothing to the sum.
double effectiveInertia(const std::optional<JointBodyFrame>& a, const JointBodyFrame& b, const Vec3& point,
                        const Vec3& axis);

/// Stiffness and damping as given, or from hertz f and damping ratio z with the effective mass
/// (or inertia) m: k = m (2 pi f)^2, c = 2 z m (2 pi f), so that a body of that mass oscillates
/// at f Hz with ratio z.
JointSpringSI resolveSpring(const JointSpring& spring, double effective);

/// The spring's effective mass or inertia for `def` (already normalised) between the bodies at
/// `frame` (the joint frame in the world now): angular about frame X for hinges, linear for
/// sliders, wheels and distance joints.
double springEffective(const JointDef& def, const std::optional<JointBodyFrame>& a, const JointBodyFrame& b,
                       const Transform& frame);

/// Everything but the body pointers and userData: frames in each body's peer frame (the world
/// for a missing A), distance anchors and rest length, springs in SI units. `def` is validated.
JointPeerDef resolveJoint(const JointDef& def, const std::optional<JointBodyFrame>& a, const JointBodyFrame& b,
                          bool planar);

}  // namespace anyphys

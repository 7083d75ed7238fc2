#pragma once
// A light handle to a joint: a link to its world plus a generational id, like Body. Copy freely;
// every call on a destroyed joint, or on any joint of a destroyed world, throws anyphys::Error
// (kind StaleHandle) naming the operation. A joint is destroyed
// by World::destroyJoint, or with either of its bodies (World::destroyBody destroys the body's
// joints first). A broken joint is not destroyed: its handle stays valid and reports isBroken().
#include <optional>
#include <string>
#include <typeinfo>

#include "anyphys/body.hpp"
#include "anyphys/ids.hpp"
#include "anyphys/joint_def.hpp"
#include "anyphys/joint_types.hpp"

namespace anyphys {

class World;

class Joint {
public:
    Joint() = default;
    /// The handle of joint `id` of `world` (World makes these; a null world gives a null handle).
    Joint(World* world, JointId id);

    JointId id() const { return id_; }
    /// The joint's world; nullptr for a null handle or once the world was destroyed.
    World* world() const { return link_ ? link_->world : nullptr; }
    /// False once the joint or its world was destroyed (a broken joint stays valid).
    bool isValid() const;

    const std::string& name() const;
    JointType type() const;
    /// The null handle when the joint holds bodyB to the static world.
    Body bodyA() const;
    Body bodyB() const;
    /// The def as created (axis normalised, spinAxis made exactly perpendicular to it), with the
    /// motor, limits and spring last set.
    JointDef def() const;

    /// Angle (rad) or offset (m) from the pose at creation, by type: hinge: angle of B about the
    /// axis; slider: offset along the axis; wheel: suspension offset along the axis; distance:
    /// length minus the rest length; ball and cone: swing, the angle between the axis fixed in A
    /// and in B; fixed: 0. In a planar world a ball joint reports its hinge angle about Z.
    /// 0 once broken.
    double position() const;
    /// Rate of position() (rad/s, m/s); a wheel reports its spin about the axle (rad/s). 0 once broken.
    double speed() const;
    /// N, world frame: the mean force the joint applied to bodyB over the last step. 0 once broken.
    Vec3 reactionForce() const;
    /// N m, world frame: the mean torque it applied to bodyB about B's anchor. 0 once broken.
    Vec3 reactionTorque() const;
    /// The joint broke: a reaction exceeded JointDef::breakForce or breakTorque after a step. Its
    /// constraint is gone for good; listeners were told (ContactListener::onJointBreak).
    bool isBroken() const;
    /// The game's value (JointDef::userData), and replacing it. Never read by anyphys.
    std::uint64_t userData() const;
    void setUserData(std::uint64_t value);

    /// Replace the motor, limits or spring (std::nullopt removes it), validated like the def's
    /// (limits need not contain the current position: the joint is driven back into them). From
    /// the next step; wakes the bodies. Only for the types that have one (see JointDef).
    void setMotor(const std::optional<JointMotor>& motor);
    void setLimits(const std::optional<JointLimits>& limits);
    void setSpring(const std::optional<JointSpring>& spring);
    /// Wheels created with `steering`: turns the suspension and axle about the axis fixed in A by
    /// `angle` rad from the pose at creation.
    void setSteeringAngle(double angle);

    /// Escape hatch: the engine's own joint object when the world's engine has a T, else
    /// nullptr (also once broken).
    template <class T>
    T* native() const { return static_cast<T*>(nativeObject(typeid(T*))); }
    void* nativeObject(const std::type_info& pointerType) const;

    friend bool operator==(const Joint& a, const Joint& b) { return a.link_ == b.link_ && a.id_ == b.id_; }

private:
    std::shared_ptr<detail::WorldLink> link_;
    JointId id_;
};

}  // namespace anyphys

#pragma once
// Debug drawing: World::debugDraw hands what the layer knows about the world (shapes and their
// poses, the last step's contacts, joint frames and limits, shape bounds) to an interface the game
// implements with its own renderer. Everything comes from the layer, so every backend draws the
// same scene the same way. See docs/debug-draw.md.
#include <limits>

#include "anyphys/defs.hpp"
#include "anyphys/enums.hpp"
#include "anyphys/ids.hpp"
#include "anyphys/joint_types.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

/// A colour, each component in [0, 1].
struct DebugColor {
    float r = 1.0f;
    float g = 1.0f;
    float b = 1.0f;
    friend bool operator==(const DebugColor&, const DebugColor&) = default;
};

/// The colour a shape is drawn in, by what its body is. A trigger takes `trigger` whatever its type.
struct DebugPalette {
    DebugColor staticBody{0.5f, 0.9f, 0.5f};     ///< static bodies; default light green
    DebugColor kinematicBody{0.5f, 0.5f, 0.9f};  ///< kinematic bodies; default light blue
    DebugColor awakeBody{0.9f, 0.7f, 0.7f};      ///< dynamic bodies that are awake; default pink
    DebugColor sleepingBody{0.6f, 0.6f, 0.6f};   ///< dynamic bodies asleep; default grey
    DebugColor trigger{0.9f, 0.9f, 0.3f};        ///< sensors (BodyDef::isTrigger); default yellow
};

/// What World::debugDraw draws. Each kind switched off makes no call of its kind.
struct DebugDrawOptions {
    bool shapes = true;               ///< drawShape for every primitive shape; default on
    bool contacts = false;            ///< drawContact for every point of the last step's contacts; default off
    bool joints = true;               ///< drawJoint for every simulated joint; default on
    bool jointLimits = true;          ///< drawJointLimit for the limits of those joints (needs `joints`); default on
    bool bounds = false;              ///< drawBounds: the world AABB of every primitive shape but planes; default off
    double contactNormalLength = 0.2; ///< m, >= 0 and finite: length of DebugContact::normalEnd - point; default 0.2
    DebugPalette palette;             ///< shape colours; every component in [0, 1]
};

/// One contact point of the last step (an Enter or Stay event with points).
struct DebugContact {
    BodyId bodyA;                  ///< the pair, bodyA < bodyB (the events' order)
    BodyId bodyB;
    Vec3 point = Vec3::Zero();     ///< m, world
    Vec3 normal = Vec3::Zero();    ///< unit, world, from A to B
    Vec3 normalEnd = Vec3::Zero(); ///< m, world: point + normal * contactNormalLength, where to draw the normal to
    double depth = 0.0;            ///< m, penetration (> 0 when overlapping)
    double normalImpulse = 0.0;    ///< N s over the last step; 0 unless hasImpulse
    bool hasImpulse = false;       ///< the backend reports impulses, and settings.contactImpulses is on
};

/// One limit of a joint, measured in `frame`: the joint frame fixed in A (the world when A is the
/// world), X along the joint's axis, origin at the anchor, as World::debugDraw's frameA.
struct DebugJointLimit {
    enum class Kind {
        Angle,   ///< hinge: rad, B's turn about frame X; 0 is where B was at creation (frame Y)
        Offset,  ///< slider, wheel suspension: m along frame X from the origin
        Swing,   ///< cone: rad, half-angle of the cone about frame X; lower is 0, upper the swing limit
        Twist,   ///< cone: rad, B's twist about frame X
        Length,  ///< distance: m from frame's origin (anchor A) along the line to anchor B; upper may be +inf
    };
    Kind kind = Kind::Angle;
    Transform frame;
    double lower = 0.0;
    double upper = 0.0;
};

/// Implemented by the game. World::debugDraw calls it synchronously, on the caller's thread; the
/// references passed are valid during the call only. A drawer must not create, destroy or step
/// anything of the world it is drawing (World throws if it tries); reading is fine.
class DebugDraw {
public:
    virtual ~DebugDraw() = default;

    /// A primitive shape (never a compound: each child comes on its own, at its composed pose,
    /// so ignore a child's own position and orientation fields) at `pose` in the world. Which ShapeDef fields matter depends on its type: points,
    /// vertices and half sizes are in the shape's frame (`pose`); a plane's normal and offset are
    /// in the world, as in its def. `awake` is the body's state: static bodies are never awake.
    virtual void drawShape(BodyId body, const ShapeDef& shape, const Transform& pose, DebugColor color,
                           bool awake) = 0;
    virtual void drawContact(const DebugContact& contact) = 0;
    /// A joint's frame fixed in A (frameA: in the world when A is the world) and the same frame
    /// fixed in B (frameB). They coincided at creation and stay together as far as the joint
    /// holds (a distance joint's frameB sits at anchor B). `type` is what runs: a planar world's
    /// ball joint is a hinge.
    virtual void drawJoint(JointId joint, JointType type, const Transform& frameA, const Transform& frameB) = 0;
    /// One limit of the joint just drawn; by default nothing is drawn.
    virtual void drawJointLimit(JointId joint, const DebugJointLimit& limit) { (void)joint; (void)limit; }
    /// The world AABB of one primitive shape of `body` (planes have none).
    virtual void drawBounds(BodyId body, const Vec3& min, const Vec3& max) = 0;
};

}  // namespace anyphys

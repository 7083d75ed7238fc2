// World::debugDraw: the world as the layer knows it (defs, the bodies' states, the last step's
// events, the joints' resolved frames) handed to the game's DebugDraw. Nothing here asks a backend
// for more than BodyPeer::state and isAwake, so every engine draws the same way.
#include <cmath>
#include <string>

#include "../world_impl.hpp"
#include "../geometry/shape_bounds.hpp"

namespace anyphys {
namespace {

/// Sets a flag for the lifetime of the guard, even if a drawer throws.
class DrawingGuard {
public:
    explicit DrawingGuard(bool& flag) : flag_(flag) { flag_ = true; }
    ~DrawingGuard() { flag_ = false; }
    DrawingGuard(const DrawingGuard&) = delete;
    DrawingGuard& operator=(const DrawingGuard&) = delete;

private:
    bool& flag_;
};

void validateColor(const DebugColor& c, const std::string& field) {
    const auto check = [&field](float v, const char* component) {
        if (!(v >= 0.0f && v <= 1.0f)) throw Error::invalid(field + "." + component, v, "must be in [0, 1]");
    };
    check(c.r, "r");
    check(c.g, "g");
    check(c.b, "b");
}

void validate(const DebugDrawOptions& o) {
    if (!(std::isfinite(o.contactNormalLength) && o.contactNormalLength >= 0.0))
        throw Error::invalid("DebugDrawOptions.contactNormalLength", o.contactNormalLength, "must be >= 0 and finite (m)");
    const DebugPalette& p = o.palette;
    validateColor(p.staticBody, "DebugDrawOptions.palette.staticBody");
    validateColor(p.kinematicBody, "DebugDrawOptions.palette.kinematicBody");
    validateColor(p.awakeBody, "DebugDrawOptions.palette.awakeBody");
    validateColor(p.sleepingBody, "DebugDrawOptions.palette.sleepingBody");
    validateColor(p.trigger, "DebugDrawOptions.palette.trigger");
}

/// `local` (a pose in the frame `parent`) in the world.
Transform compose(const Transform& parent, const Transform& local) {
    return {parent.position + parent.orientation * local.position, (parent.orientation * local.orientation).normalized()};
}

DebugColor colorOf(const BodyDef& def, bool awake, const DebugPalette& palette) {
    if (def.isTrigger) return palette.trigger;
    switch (def.type) {
        case BodyType::Static: return palette.staticBody;
        case BodyType::Kinematic: return palette.kinematicBody;
        case BodyType::Dynamic: break;
    }
    return awake ? palette.awakeBody : palette.sleepingBody;
}

/// Calls `visit(shape, pose)` for each primitive of `shape` at `bodyPose`: a compound's children
/// at their placement composed with the body's pose (children are never compounds).
template <class Visit>
void forEachPrimitive(const ShapeDef& shape, const Transform& bodyPose, Visit&& visit) {
    if (shape.type != ShapeType::Compound) {
        visit(shape, bodyPose);
        return;
    }
    for (const ShapeDef& child : shape.shapes) visit(child, compose(bodyPose, Transform{child.position, child.orientation}));
}

/// The limits of a joint as DebugJointLimits in `frame` (frame A in the world), by what runs.
template <class Emit>
void forEachLimit(const JointDef& def, JointType running, const Transform& frame, Emit&& emit) {
    using Kind = DebugJointLimit::Kind;
    switch (running) {
        case JointType::Hinge:
            if (def.limits) emit(DebugJointLimit{Kind::Angle, frame, def.limits->lower, def.limits->upper});
            break;
        case JointType::Slider:
        case JointType::Wheel:
            if (def.limits) emit(DebugJointLimit{Kind::Offset, frame, def.limits->lower, def.limits->upper});
            break;
        case JointType::Cone:
            emit(DebugJointLimit{Kind::Swing, frame, 0.0, def.swingLimit});
            if (def.twistLimits) emit(DebugJointLimit{Kind::Twist, frame, def.twistLimits->lower, def.twistLimits->upper});
            break;
        case JointType::Distance:
            if (def.minLength || def.maxLength)
                emit(DebugJointLimit{Kind::Length, frame, def.minLength.value_or(0.0),
                                     def.maxLength.value_or(std::numeric_limits<double>::infinity())});
            break;
        case JointType::Fixed:
        case JointType::Ball: break;
    }
}

}  // namespace

void World::debugDraw(DebugDraw& drawer, const DebugDrawOptions& options) const {
    impl_->refuseWhileStepping("World.debugDraw");
    impl_->refuseWhileDrawing("World.debugDraw");
    validate(options);
    DrawingGuard guard(impl_->drawing);
    const Impl& i = *impl_;

    // Shapes and their bounds, body by body in slot order.
    if (options.shapes || options.bounds) {
        for (std::uint32_t index = 0; index < i.slots.size(); ++index) {
            const Slot& s = i.slots[index];
            if (!s.peer) continue;
            const BodyId id{index, s.generation};
            const BodyState state = s.userState();
            const bool awake = s.def.type != BodyType::Static && s.peer->isAwake();
            const DebugColor color = colorOf(s.def, awake, options.palette);
            forEachPrimitive(s.def.shape, Transform{state.position, state.orientation},
                             [&](const ShapeDef& shape, const Transform& pose) {
                                 // A compound's sensor child in the trigger colour, its solid
                                 // children in the body's.
                                 const bool sensorChild = shape.isTrigger.value_or(s.def.isTrigger);
                                 const DebugColor shapeColor = sensorChild ? options.palette.trigger : color;
                                 if (options.shapes) drawer.drawShape(id, shape, pose, shapeColor, awake);
                                 if (!options.bounds) return;
                                 if (const auto box = shapeBounds(shape, pose)) drawer.drawBounds(id, box->min, box->max);
                             });
        }
    }

    // Contact points of the last step's collisions; events of bodies destroyed since are skipped.
    if (options.contacts) {
        for (const ContactEvent& event : impl_->writtenEvents()) {
            if (event.trigger || event.phase == ContactPhase::Exit) continue;
            if (!isValid(event.bodyA) || !isValid(event.bodyB)) continue;
            for (const ContactPoint& p : event.points) {
                DebugContact c;
                c.bodyA = event.bodyA;
                c.bodyB = event.bodyB;
                c.point = p.position;
                c.normal = event.normal;
                c.normalEnd = p.position + event.normal * options.contactNormalLength;
                c.depth = p.depth;
                c.hasImpulse = event.hasImpulses;
                c.normalImpulse = event.hasImpulses ? p.normalImpulse : 0.0;
                drawer.drawContact(c);
            }
        }
    }

    // Joints that run: frames fixed in each body, placed by the bodies' peer poses.
    if (options.joints) {
        const auto peerPose = [&i](const Body& body) {
            const BodyState st = i.slots[body.id().index].peer->state();
            return Transform{st.position, st.orientation};
        };
        for (std::uint32_t index = 0; index < i.joints.size(); ++index) {
            const JointSlot& j = i.joints[index];
            if (!j.live || !j.peer) continue;  // broken, or not simulated on this backend
            const JointId id{index, j.generation};
            const Transform frameA = j.def.bodyA.id().isNull() ? j.frameA : compose(peerPose(j.def.bodyA), j.frameA);
            const Transform frameB = compose(peerPose(j.def.bodyB), j.frameB);
            drawer.drawJoint(id, j.peerType, frameA, frameB);
            if (options.jointLimits)
                forEachLimit(j.def, j.peerType, frameA, [&](const DebugJointLimit& limit) { drawer.drawJointLimit(id, limit); });
        }
    }
}

}  // namespace anyphys

// The field stage: buoyancy, drag and wind as forces of the world's force evaluation (the
// backend's hook on backends that evaluate forces per integrator stage, so they follow the
// stage's states; the layer's own evaluation at the step's start elsewhere), explosions as
// impulses before the step. Only what every backend offers is used: body
// states, forces and torques, impulses, ray casts and overlap queries.
#include <algorithm>
#include <string>
#include <vector>

#include "anyphys/validation.hpp"
#include "anyphys/world.hpp"
#include "body_shapes.hpp"
#include "world_impl.hpp"

namespace anyphys {

namespace {

// The body's primitives in its peer frame (centre of mass, principal axes), with hull faces and
// mesh triangles (a mesh's culling grid is built here, once: meshes are static).
std::unique_ptr<FieldBody> buildFieldBody(const BodyDef& def, const MassProperties& mass, const Transform& peerFrame) {
    auto body = std::make_unique<FieldBody>();
    const Quat toPeer = peerFrame.orientation.conjugate();
    for (const PeerShape& p : flattenShape(def.shape)) {
        FieldShape s;
        s.type = p.def.type;
        s.radius = p.def.radius;
        s.halfExtents = p.def.halfExtents;
        s.halfHeight = p.def.halfHeight;
        s.normal = p.def.normal;
        s.offset = p.def.offset;
        if (p.hull) s.hull = std::make_shared<const ConvexFaces>(ConvexFaces{p.hull->vertices, p.hull->faces});
        if (s.type == ShapeType::Mesh) s.mesh = std::make_shared<const TriangleMesh>(p.def.vertices, p.def.indices);
        s.local.position = toPeer * (p.local.position - peerFrame.position);
        s.local.orientation = toPeer * p.local.orientation;
        s.sensor = p.def.isTrigger.value_or(def.isTrigger);
        body->volume += shapeVolume(s);
        body->shapes.push_back(std::move(s));
    }
    body->mass = mass.mass;
    body->inertia = mass.inertia;
    const ShapeType first = def.shape.type == ShapeType::Compound && !def.shape.shapes.empty() ? def.shape.shapes[0].type
                                                                                                : def.shape.type;
    body->dragCoefficient = def.dragCoefficient.value_or(defaultDragCoefficient(first));
    return body;
}

FieldState fieldState(const BodyState& s) { return {{s.position, s.orientation}, s.linearVelocity, s.angularVelocity}; }

std::string bodyLabel(const BodyDef& def, std::uint32_t index) {
    return def.name.empty() ? "body #" + std::to_string(index) : "body \"" + def.name + "\"";
}

// A field whose push on a body would change its speed or spin by more than the world's ceilings
// (within one step for a force, at once for an impulse) has parameters absurd for that body: an air
// density of 1e300, a wind at 1e308 m/s, an explosion of 1e308 N s. Refused before an engine
// integrates it, as a force given to Body::applyForce is: an engine handed an infinite force aborts
// inside its integrator (the API fuzzer made ODE abort on such a wind). `seconds` is the step for a
// force, 1 for an impulse.
void requireFieldPushWithinCeilings(const BodyDef& def, std::uint32_t index, const MassProperties& mass,
                                    const Vec3& linear, const Vec3& angular, double seconds, const WorldSettings& settings,
                                    const char* what) {
    const double speedChange = linear.stableNorm() / mass.mass * seconds;
    const double spinChange = angular.isZero(0) ? 0.0 : angular.stableNorm() / mass.inertia.minCoeff() * seconds;
    if (speedChange <= settings.maxSpeed && spinChange <= settings.maxAngularSpeed) return;
    const bool speed = !(speedChange <= settings.maxSpeed);
    throw Error(ErrorKind::InvalidArgument, "fields",
                std::string("World.step: the fields' ") + what + " on " + bodyLabel(def, index) + " (" +
                    (speed ? "linear " + formatVec3(linear) : "angular " + formatVec3(angular)) + ") would change its " +
                    (speed ? "speed by " + detail::ceilingText(speedChange) + " m/s" : "spin by " + detail::ceilingText(spinChange) + " rad/s") +
                    (seconds == 1.0 ? " at once" : " in one step") + ", more than WorldSettings." +
                    (speed ? "maxSpeed (" + detail::ceilingText(settings.maxSpeed) : "maxAngularSpeed (" + detail::ceilingText(settings.maxAngularSpeed)) +
                    "): a field's density, drag, wind speed or impulse is beyond what the world can integrate");
}

}  // namespace

const FieldBody& World::Slot::fieldGeometry() {
    if (!fieldBody) fieldBody = buildFieldBody(def, mass, peerFrame);
    return *fieldBody;
}

void World::addField(const FieldDef& input) {
    if (impl_->stepping) throw Error("World.addField: not allowed while the world is stepping (inside a force callback)");
    impl_->refuseWhileDrawing("World.addField");
    validate(input, "FieldDef");
    const Effect effect = fieldEffect(input.type);
    if (settings_.planar) {
        const auto inPlane = [](const std::string& field, const Vec3& v) {
            if (std::abs(v.z()) > 1e-9 * std::max(1.0, v.norm()))
                throw Error::invalid(field, formatVec3(v), "must lie in the XY plane (z = 0) in a planar world");
        };
        if (input.type == FieldType::Buoyancy) inPlane("FieldDef.surface.normal", input.surfaceNormal);
        if (input.type == FieldType::Wind) inPlane("FieldDef.velocity", input.velocity);
        if (input.type == FieldType::Explosion) inPlane("FieldDef.center", input.center);
    }
    // A wind faster than any body may move is a units mistake; its drag would overflow.
    if (input.type == FieldType::Wind)
        detail::requireSpeed("FieldDef.velocity", input.velocity, settings_.maxSpeed, "WorldSettings.maxSpeed", "m/s");
    if (settings_.effects && !settings_.effects->has(effect))
        throw Error("World.addField: the world's declared effects exclude \"" + std::string(toString(effect)) +
                    "\"; add it to WorldSettings.effects");
    FieldDef field = input;
    field.surfaceNormal.normalize();
    impl_->fields.push_back(field);
    impl_->fieldEffects.add(effect);
    installForceHook();
    refreshEffects();
}

const std::vector<FieldDef>& World::fields() const { return impl_->fields; }

void World::clearFields() {
    if (impl_->stepping) throw Error("World.clearFields: not allowed while the world is stepping (inside a force callback)");
    impl_->refuseWhileDrawing("World.clearFields");
    impl_->fields.clear();
    impl_->fieldEffects = Effects::none();
    installForceHook();
    refreshEffects();
}

void World::applyFieldForces(detail::ForceSink& sink) {
    const Effects on = activeEffects_ & kFieldForceEffects;
    const bool planar = settings_.planar;
    for (std::uint32_t index = 0; index < impl_->slots.size(); ++index) {
        Slot& slot = impl_->slots[index];
        if (!slot.peer || slot.def.type != BodyType::Dynamic || !slot.peer->isAwake()) continue;
        const FieldBody& body = slot.fieldGeometry();
        const FieldState state = fieldState(sink.state(*slot.peer));
        FieldForce total;
        for (const FieldDef& field : impl_->fields) {
            if (!on.has(fieldEffect(field.type))) continue;
            switch (field.type) {
                case FieldType::Buoyancy: total += buoyancyForce(field, body, state, settings_.gravity); break;
                case FieldType::Drag: total += dragForce(field, body, state); break;
                case FieldType::Wind: total += windForce(field, body, state); break;
                case FieldType::Explosion: break;  // impulses, before the step
            }
        }
        if (planar) {  // the plane holds the body, as for Body::applyForce
            total.force.z() = 0.0;
            total.torque.x() = total.torque.y() = 0.0;
        }
        requireFieldPushWithinCeilings(slot.def, index, slot.mass, total.force, total.torque, settings_.timeStep, settings_, "force");
        if (!total.force.isZero(0)) sink.addForce(index, *slot.peer, total.force);
        if (!total.torque.isZero(0)) sink.addTorque(index, *slot.peer, total.torque);
    }
}

void World::fireExplosions(double dt) {
    const bool planar = settings_.planar;
    // Every impulse is checked before any is applied: a refused explosion leaves the world as it was.
    struct Push {
        Slot* slot;
        Vec3 linear, angular;
    };
    std::vector<Push> pushes;
    for (const FieldDef& field : impl_->fields) {
        // Due in this step: its start time t has t <= time < t + dt.
        if (field.type != FieldType::Explosion || field.time < time_ || field.time >= time_ + dt) continue;
        const Transform at{field.center, Quat::Identity()};
        std::vector<std::uint64_t> keys = impl_->peer->overlap(flattenShape(ShapeDef::sphere(field.radius)), at, 0xFFFFFFFFu);
        std::sort(keys.begin(), keys.end());  // the same order on every backend
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
        for (std::uint64_t key : keys) {
            const BodyId id = unpackId(key);
            if (!isValid(id)) continue;
            Slot& slot = impl_->slots[id.index];
            if (slot.def.type != BodyType::Dynamic) continue;
            const FieldState state = fieldState(slot.peer->state());
            const auto hit = explosionHit(field, slot.fieldGeometry(), state);
            if (!hit) continue;
            // Static geometry between the centre and the point shields the body.
            const Vec3 ray = hit->point - field.center;
            const double reach = ray.norm();
            bool shielded = false;
            if (reach > settings_.linearSlop) {
                for (const PeerRayHit& h : detail::castFromOrigin(*impl_->peer, field.center, ray / reach, reach, false, 0xFFFFFFFFu)) {
                    if (h.distance >= reach - settings_.linearSlop) break;
                    const BodyId other = unpackId(h.body);
                    if (isValid(other) && impl_->slots[other.index].def.type == BodyType::Static) {
                        shielded = true;
                        break;
                    }
                }
            }
            if (shielded) continue;
            Vec3 linear = hit->impulse;
            Vec3 angular = (hit->point - state.pose.position).cross(hit->impulse);
            if (planar) {
                linear.z() = 0.0;
                angular.x() = angular.y() = 0.0;
            }
            requireFieldPushWithinCeilings(slot.def, id.index, slot.mass, linear, angular, 1.0, settings_, "explosion impulse");
            pushes.push_back({&slot, linear, angular});
        }
    }
    for (const Push& p : pushes) {
        p.slot->peer->applyLinearImpulse(p.linear);
        if (!p.angular.isZero(0)) p.slot->peer->applyAngularImpulse(p.angular);
    }
}

}  // namespace anyphys

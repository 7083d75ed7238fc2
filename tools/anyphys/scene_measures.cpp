// Measures shared by `anyphys compare` and its sweeps.
#include "scene_measures.hpp"

#include <algorithm>
#include <cmath>

#include "cli.hpp"

namespace anyphys::cli {
namespace {

/// True when some dynamic body may touch another body (their layers and masks allow it).
bool mayTouch(const Scene& scene) {
    const auto& b = scene.bodies;
    for (std::size_t i = 0; i < b.size(); ++i)
        for (std::size_t j = i + 1; j < b.size(); ++j)
            if ((b[i].type == BodyType::Dynamic || b[j].type == BodyType::Dynamic) &&
                layersCollide(b[i].layer, b[i].mask, b[j].layer, b[j].mask))
                return true;
    return false;
}

/// Effects the scene's content calls for, so the capability check sees them up front (a
/// backend without contacts would otherwise let a stack fall through the ground).
Effects contentEffects(const Scene& scene) {
    Effects effects;
    for (const BodyDef& def : scene.bodies) {
        if (def.type != BodyType::Dynamic) continue;
        if (!scene.settings.gravity.isZero(0) && def.gravityScale != 0.0) effects.add(Effect::Gravity);
        if (def.linearDamping > 0.0 || def.angularDamping > 0.0) effects.add(Effect::Damping);
        if (def.gyroscopic != GyroscopicMode::None) effects.add(Effect::Gyroscopic);
    }
    if (mayTouch(scene)) {
        effects.add(Effect::Contacts);
        for (const BodyDef& def : scene.bodies) {
            if (!scene.materials.contains(def.material)) continue;  // the World reports it, naming the body
            const Material& m = scene.materials.get(def.material);
            if (m.friction > 0.0) effects.add(Effect::Friction);
            if (m.restitution > 0.0) effects.add(Effect::Restitution);
        }
    }
    for (const FieldDef& field : scene.fields) effects.add(fieldEffect(field.type));
    return effects;
}

}  // namespace

double mechanicalEnergy(const World& world, const std::vector<Body>& bodies, const Scene& scene) {
    double energy = 0.0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& body = bodies[i];
        if (body.type() != BodyType::Dynamic) continue;
        const MassProperties mp = body.massProperties();
        // Spin in the principal frame, where the inertia is diagonal; height of the centre of
        // mass (a compound's is not at the body origin). linearVelocity is the centre of mass's.
        const Vec3 wPrincipal = mp.principalAxes.conjugate() * body.angularVelocityLocal();
        const Vec3 g = world.settings().gravity * scene.bodies[i].gravityScale;
        energy += 0.5 * mp.mass * body.linearVelocity().squaredNorm();
        energy += 0.5 * wPrincipal.dot(mp.inertia.cwiseProduct(wPrincipal));
        energy -= mp.mass * g.dot(body.centerOfMass());
    }
    return energy;
}

double angularMomentumNorm(const std::vector<Body>& bodies) {
    Vec3 total = Vec3::Zero();
    for (const Body& body : bodies)
        if (body.type() == BodyType::Dynamic) total += body.angularMomentum();
    return total.norm();
}

std::optional<double> relativeChange(double start, double end) {
    if (start == 0.0) return std::nullopt;
    return (end - start) / std::abs(start);
}

std::vector<BodyState> bodyStates(const std::vector<Body>& bodies) {
    std::vector<BodyState> out;
    out.reserve(bodies.size());
    for (const Body& body : bodies) out.push_back(body.state());
    return out;
}

std::vector<std::string> missingFor(const Capabilities& caps, const WorldSettings& settings, const Scene& scene) {
    std::vector<std::string> missing = missingCapabilities(caps, settings, contentEffects(scene));
    const auto note = [&missing](std::string item) {
        if (std::find(missing.begin(), missing.end(), item) == missing.end()) missing.push_back(std::move(item));
    };
    for (const BodyDef& def : scene.bodies) {
        if (!caps.shapes.contains(def.shape.type)) note("shape " + std::string(toString(def.shape.type)));
        if (!caps.bodyTypes.contains(def.type)) note("body type " + std::string(toString(def.type)));
        if (def.type == BodyType::Dynamic && !caps.gyroscopicModes.contains(def.gyroscopic))
            note("gyroscopic " + std::string(toString(def.gyroscopic)));
    }
    for (const SceneJoint& joint : scene.joints)
        for (std::string item : missingJointCapabilities(caps, joint.def, settings.planar)) note(std::move(item));
    return missing;
}

double boundingRadius(const ShapeDef& shape) {
    switch (shape.type) {
        case ShapeType::Sphere: return shape.radius;
        case ShapeType::Box: return shape.halfExtents.norm();
        case ShapeType::Capsule: return shape.radius + shape.halfHeight;
        case ShapeType::Convex: {
            double r = 0.0;
            for (const Vec3& p : shape.points) r = std::max(r, p.norm());
            return r;
        }
        case ShapeType::Compound: {
            double r = 0.0;
            for (const ShapeDef& child : shape.shapes) r = std::max(r, child.position.norm() + boundingRadius(child));
            return r;
        }
        default: return 0.0;  // planes and meshes: the static world, not a moving body's size
    }
}

CheckVerdict judgeCheck(const SceneCheck& check, const Capabilities& caps, double value) {
    CheckVerdict v;
    v.value = value;
    v.passed = check.passes(value);
    if (const auto it = caps.deviationCeilings.find(check.criterion); it != caps.deviationCeilings.end())
        v.ceiling = it->second;
    // A declaration covers a miss up to its ceiling: a deviation grown past it is a regression.
    const bool declared = !v.passed && caps.knownDeviations.contains(check.criterion);
    v.overCeiling = declared && v.ceiling && !(value <= *v.ceiling);
    v.knownDeviation = declared && !v.overCeiling;
    return v;
}

}  // namespace anyphys::cli

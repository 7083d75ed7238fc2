// Running and measuring one (scene, backend, integrator) combination.
#include "compare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cli.hpp"

namespace anyphys::cli {
namespace {

/// Kinetic plus gravitational potential energy (-m g.p, with each body's gravity scale), J.
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

/// |sum of the bodies' angular momenta about their centres|, world frame, kg m^2/s.
double angularMomentumNorm(const std::vector<Body>& bodies) {
    Vec3 total = Vec3::Zero();
    for (const Body& body : bodies)
        if (body.type() == BodyType::Dynamic) total += body.angularMomentum();
    return total.norm();
}

std::optional<double> relativeChange(double start, double end) {
    if (start == 0.0) return std::nullopt;  // no scale to compare against
    return (end - start) / std::abs(start);
}

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
    return effects;
}

std::vector<BodyState> states(const std::vector<Body>& bodies) {
    std::vector<BodyState> out;
    out.reserve(bodies.size());
    for (const Body& body : bodies) out.push_back(body.state());
    return out;
}

/// What the backend declares it lacks for this scene; empty when it claims everything.
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

}  // namespace

ComboResult runCombo(const CatalogueScene& entry, const BackendInfo& backend, Integrator integrator) {
    ComboResult result;
    result.scene = entry.name;
    result.backend = backend.name;
    result.integrator = std::string(toString(integrator));
    const auto refuse = [&result](ComboResult::Status status, std::string reason) {
        result.status = status;
        result.reason = std::move(reason);
        return result;
    };

    WorldSettings settings = entry.scene.settings;
    settings.backend = backend.name;
    settings.integrator = integrator;
    if (auto missing = missingFor(backend.capabilities, settings, entry.scene); !missing.empty())
        return refuse(ComboResult::Status::Unsupported, join(missing));

    // The backend may still refuse something its capability table cannot express.
    std::unique_ptr<World> world;
    std::vector<Body> bodies;
    try {
        world = std::make_unique<World>(settings, entry.scene.materials);
        bodies = createSceneObjects(*world, entry.scene).bodies;
    } catch (const Error& e) {
        return refuse(ComboResult::Status::Unsupported, e.what());
    }

    result.steps = std::llround(entry.duration / settings.timeStep);
    const double energy0 = mechanicalEnergy(*world, bodies, entry.scene);
    const double momentum0 = angularMomentumNorm(bodies);
    std::unique_ptr<SceneProbe> probe = entry.check ? entry.check->makeProbe() : nullptr;
    if (probe) probe->observe(world->time(), states(bodies));
    try {
        // Only the stepping is timed, not the probe's observations.
        std::chrono::steady_clock::duration stepping{};
        for (long long i = 0; i < result.steps; ++i) {
            const auto start = std::chrono::steady_clock::now();
            world->step();
            stepping += std::chrono::steady_clock::now() - start;
            if (probe) probe->observe(world->time(), states(bodies));
        }
        result.wallMs = std::chrono::duration<double, std::milli>(stepping).count();
    } catch (const Error& e) {
        return refuse(ComboResult::Status::Failed, e.what());
    }

    if (entry.reference) {
        double worst = 0.0;
        bool any = false;
        for (const Body& body : bodies) {
            if (auto exact = entry.reference(body.name(), world->time())) {
                const double error = (body.position() - exact->position).norm();
                if (!(error <= worst)) worst = error;  // written so a NaN (blow-up) is kept, not hidden
                any = true;
            }
        }
        if (any) result.positionError = worst;
    }
    if (entry.conservesEnergy)
        result.energyDrift = relativeChange(energy0, mechanicalEnergy(*world, bodies, entry.scene));
    if (entry.conservesAngularMomentum)
        result.angularMomentumDrift = relativeChange(momentum0, angularMomentumNorm(bodies));
    if (probe) {
        result.checkValue = probe->value();
        result.checkPassed = entry.check->passes(*result.checkValue);
        const Capabilities& caps = backend.capabilities;
        const std::string& criterion = entry.check->criterion;
        if (const auto it = caps.deviationCeilings.find(criterion); it != caps.deviationCeilings.end())
            result.ceiling = it->second;
        // A declaration covers a miss up to its ceiling: a deviation grown past it is a regression.
        const bool declared = !result.checkPassed && caps.knownDeviations.contains(criterion);
        result.overCeiling = declared && result.ceiling && !(*result.checkValue <= *result.ceiling);
        result.knownDeviation = declared && !result.overCeiling;
    }
    return result;
}

}  // namespace anyphys::cli

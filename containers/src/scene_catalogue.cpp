// The built-in scenes. Each is small, named, and where the exact motion is known in closed form
// it carries that solution, so tests, benchmarks and `anyphys compare` measure error against
// physics rather than against another engine.
#include "anyphys/containers/scene_catalogue.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "anyphys/error.hpp"

namespace anyphys {
namespace {

/// Rotation by a constant world-frame angular velocity w for time t, applied to q0.
Quat rotateConstant(const Quat& q0, const Vec3& w, double t) {
    const double speed = w.norm();
    if (speed == 0.0) return q0;
    return (Quat(Eigen::AngleAxisd(speed * t, w / speed)) * q0).normalized();
}

/// Exact motion of torque-free, undamped bodies under uniform gravity whose angular velocity
/// stays constant (spheres, cubes, or no spin): a parabola and a steady rotation.
std::function<std::optional<BodyState>(const std::string&, double)> ballisticReference(const Scene& scene) {
    auto defs = std::make_shared<std::map<std::string, BodyDef>>();
    for (const BodyDef& def : scene.bodies) (*defs)[def.name] = def;
    const Vec3 gravity = scene.settings.gravity;
    return [defs, gravity](const std::string& body, double t) -> std::optional<BodyState> {
        const auto it = defs->find(body);
        if (it == defs->end()) return std::nullopt;
        const BodyDef& def = it->second;
        const Vec3 g = def.type == BodyType::Dynamic ? Vec3(gravity * def.gravityScale) : Vec3::Zero();
        BodyState s;
        s.position = def.position + def.linearVelocity * t + 0.5 * g * t * t;
        s.linearVelocity = def.linearVelocity + g * t;
        s.angularVelocity = def.angularVelocity;
        s.orientation = rotateConstant(def.orientation, def.angularVelocity, t);
        return s;
    };
}

BodyDef sphereBody(const std::string& name, double radius, double mass) {
    BodyDef def;
    def.name = name;
    def.shape = ShapeDef::sphere(radius);
    def.mass = mass;
    return def;
}

/// A thin plate whose principal moments are exactly diag(1, 2, 3) kg m^2 (given explicitly; the
/// plate shape, 12 kg, 1.414 x 1 x 0.02 m, has nearly these moments).
BodyDef racketBody(const std::string& name) {
    BodyDef def;
    def.name = name;
    def.shape = ShapeDef::box(Vec3(std::sqrt(0.5), 0.5, 0.01));
    def.mass = 12.0;
    def.inertia = Vec3(1.0, 2.0, 3.0);
    def.gyroscopic = GyroscopicMode::Implicit;
    return def;
}

CatalogueScene projectile() {
    CatalogueScene c;
    c.name = "projectile";
    c.description = "ball thrown at (10,10,0) m/s under g = 10 m/s^2; lands back at height 0 at t = 2 s";
    c.duration = 2.0;
    c.scene.settings.gravity = Vec3(0, -10, 0);
    c.scene.settings.timeStep = 1.0 / 60.0;
    BodyDef ball = sphereBody("ball", 0.5, 1.0);
    ball.linearVelocity = Vec3(10, 10, 0);
    c.scene.bodies.push_back(ball);
    c.reference = ballisticReference(c.scene);
    c.conservesEnergy = true;
    // L stays exactly zero (no spin), so a relative drift is meaningless: not flagged.
    return c;
}

CatalogueScene torqueFreeSpin() {
    CatalogueScene c;
    c.name = "torque_free_spin";
    c.description = "box with inertia diag(1,2,3) spinning near its major axis, no gravity: |L| and energy conserved";
    c.duration = 10.0;
    c.scene.settings.gravity = Vec3::Zero();
    c.scene.settings.timeStep = 1.0 / 60.0;
    BodyDef box = racketBody("box");
    box.angularVelocity = Vec3(0.3, 0.2, 4.0);  // world frame = body frame at t = 0
    c.scene.bodies.push_back(box);
    // The orientation has no elementary closed form, so there is no reference; the
    // conservation laws measure the integrator instead.
    c.conservesEnergy = true;
    c.conservesAngularMomentum = true;
    return c;
}

/// The same spin with the gyroscopic term handed to the integrator, so the integrators' orders
/// show in the conservation of |L| and energy (the implicit mode is integrator-independent).
CatalogueScene torqueFreeSpinExplicit() {
    CatalogueScene c = torqueFreeSpin();
    c.name = "torque_free_spin_explicit";
    c.description = "torque_free_spin with gyroscopic \"explicit\": the integrator carries the rotation";
    c.scene.bodies.front().gyroscopic = GyroscopicMode::Explicit;
    return c;
}

CatalogueScene intermediateAxisFlip() {
    CatalogueScene c;
    c.name = "intermediate_axis_flip";
    c.description = "tennis racket: spin (0.01,5,0) rad/s about the intermediate axis of diag(1,2,3) reverses near t = 2.6 s";
    c.duration = 6.0;
    c.scene.settings.gravity = Vec3::Zero();
    c.scene.settings.timeStep = 1.0 / 60.0;
    BodyDef racket = racketBody("racket");
    racket.angularVelocity = Vec3(0.01, 5.0, 0.0);  // identity orientation: body frame = world frame
    c.scene.bodies.push_back(racket);
    c.conservesEnergy = true;
    c.conservesAngularMomentum = true;
    return c;
}

CatalogueScene dampedMotion() {
    constexpr double c0 = 0.5;  // 1/s, both dampings
    CatalogueScene c;
    c.name = "damped_motion";
    c.description = "sphere sliding at 4 m/s and spinning at 2 rad/s with damping 0.5/s, no gravity: exponential decay";
    c.duration = 4.0;
    c.scene.settings.gravity = Vec3::Zero();
    c.scene.settings.timeStep = 1.0 / 60.0;
    BodyDef ball = sphereBody("ball", 0.5, 1.0);
    ball.linearVelocity = Vec3(4, 0, 0);
    ball.angularVelocity = Vec3(0, 0, 2);  // a sphere is isotropic: no gyroscopic coupling
    ball.linearDamping = c0;
    ball.angularDamping = c0;
    c.scene.bodies.push_back(ball);
    const BodyDef def = ball;
    // dv/dt = -c v  =>  v = v0 e^{-ct}, p = p0 + v0 (1 - e^{-ct}) / c; the same for the spin.
    c.reference = [def](const std::string& body, double t) -> std::optional<BodyState> {
        if (body != def.name) return std::nullopt;
        const double decay = std::exp(-c0 * t);
        const double travelled = (1.0 - decay) / c0;  // integral of e^{-cs} ds over [0, t]
        BodyState s;
        s.position = def.position + def.linearVelocity * travelled;
        s.linearVelocity = def.linearVelocity * decay;
        s.angularVelocity = def.angularVelocity * decay;
        s.orientation = rotateConstant(def.orientation, def.angularVelocity, travelled);
        return s;
    };
    return c;
}

CatalogueScene freeFallDrop() {
    CatalogueScene c;
    c.name = "free_fall_drop";
    c.description = "ball with gravityScale 0.5 dropped from 10 m under default gravity: falls with g/2";
    c.duration = 1.0;
    BodyDef ball = sphereBody("ball", 0.5, 1.0);
    ball.position = Vec3(0, 10, 0);
    ball.gravityScale = 0.5;
    c.scene.bodies.push_back(ball);
    c.reference = ballisticReference(c.scene);
    c.conservesEnergy = true;
    return c;
}

CatalogueScene freeBodies() {
    CatalogueScene c;
    c.name = "free_bodies";
    c.description = "benchmark load: 1000 spinning cubes thrown upwards under default gravity, nothing to collide";
    c.duration = 1.0;
    c.scene = freeBodiesScene(1000);
    c.reference = ballisticReference(c.scene);  // cubes are isotropic: the spin stays constant
    c.conservesEnergy = true;
    c.conservesAngularMomentum = true;
    return c;
}

std::vector<CatalogueScene> buildCatalogue() {
    std::vector<CatalogueScene> all;
    all.push_back(projectile());
    all.push_back(torqueFreeSpin());
    all.push_back(torqueFreeSpinExplicit());
    all.push_back(intermediateAxisFlip());
    all.push_back(dampedMotion());
    all.push_back(freeFallDrop());
    all.push_back(freeBodies());
    return all;
}

}  // namespace

Scene freeBodiesScene(int count) {
    if (count < 0) throw Error::invalid("freeBodiesScene.count", count, "must be >= 0");
    Scene scene;
    constexpr int kRow = 10;  // bodies per grid row and column; spacing 1 m keeps them apart
    for (int i = 0; i < count; ++i) {
        BodyDef def;
        char name[32];
        std::snprintf(name, sizeof name, "box_%04d", i);
        def.name = name;
        def.shape = ShapeDef::box(Vec3(0.1, 0.1, 0.1));
        def.mass = 1.0;
        def.position = Vec3(i % kRow, (i / kRow) % kRow, i / (kRow * kRow));
        // Smooth deterministic spread of velocities (no RNG, so every platform builds the same scene).
        const double a = 0.7 * i;
        def.linearVelocity = Vec3(std::sin(a), 5.0 + std::cos(a), std::sin(1.3 * a));
        def.angularVelocity = Vec3(std::cos(0.5 * a), std::sin(0.9 * a), 2.0);
        scene.bodies.push_back(def);
    }
    return scene;
}

const std::vector<CatalogueScene>& sceneCatalogue() {
    static const std::vector<CatalogueScene> catalogue = buildCatalogue();
    return catalogue;
}

const CatalogueScene& catalogueScene(const std::string& name) {
    std::string known;
    for (const CatalogueScene& c : sceneCatalogue()) {
        if (c.name == name) return c;
        known += (known.empty() ? "" : ", ") + c.name;
    }
    throw Error::invalid("scene", "\"" + name + "\"", "unknown catalogue scene; known: " + known);
}

}  // namespace anyphys

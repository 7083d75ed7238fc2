// libFuzzer target: random sequences of World, Body and Joint calls decoded from the input, on
// every built backend (the first byte picks it). Values are mostly sensible, sometimes hostile
// (0, negative, NaN, inf, 1e308, just past a ceiling), so both the physics and the refusals run.
// Rule: a call returns or throws anyphys::Error; anything else (another exception, a sanitizer
// report, a crash) is a bug. Each input is capped in calls, bodies and steps to stay cheap.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_support.hpp"

namespace {

using namespace anyphys;

constexpr int kMaxCalls = 64;
constexpr std::size_t kMaxBodies = 24;
constexpr int kMaxSteps = 24;

/// Reads the input front to back, one byte per choice; past its end every byte reads 0, so a
/// short input is a short call sequence (libFuzzer's mutations map to choices one to one).
class Decoder {
public:
    Decoder(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    bool more() const { return at_ < size_; }
    std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    bool flag() { return (byte() & 1) != 0; }
    template <class E>
    E pick(int count) { return static_cast<E>(byte() % count); }

    /// A value in [lo, hi] most of the time; one in eight a hostile one.
    double number(double lo, double hi) {
        const std::uint8_t k = byte();
        if (k < 224) return lo + (hi - lo) * (k / 223.0);
        static const double hostile[] = {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                                         std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                         1e308, -1e308, 1e-300, 1e7, 1.0000001e7, 1e5, 1e4, 1e3, 4.9e-324, -0.0, 1e20};
        return hostile[k % (sizeof hostile / sizeof hostile[0])];
    }
    Vec3 vec(double lo, double hi) {
        const double x = number(lo, hi), y = number(lo, hi), z = number(lo, hi);
        return Vec3(x, y, z);
    }
    Quat quat() {
        if (flag()) return Quat::Identity();
        const double w = number(-1, 1), x = number(-1, 1), y = number(-1, 1), z = number(-1, 1);
        return Quat(w, x, y, z);  // not normalised on purpose: the layer must refuse or normalise
    }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t at_ = 0;
};

ShapeDef shapeFrom(Decoder& d, int depth) {
    ShapeDef s;
    switch (d.pick<int>(7)) {
        case 0: s = ShapeDef::sphere(d.number(0.05, 2)); break;
        case 1: s = ShapeDef::box(d.vec(0.05, 2)); break;
        case 2: s = ShapeDef::capsule(d.number(0.05, 1), d.number(0.0, 1)); break;
        case 3: s = ShapeDef::plane(d.vec(-1, 1), d.number(-2, 2)); break;
        case 4: {
            std::vector<Vec3> points(4 + d.byte() % 9);
            for (Vec3& p : points) p = d.vec(-1, 1);
            if (std::getenv("ANYPHYS_FUZZ_TRACE"))
                for (const Vec3& p : points) std::fprintf(stderr, "  convex point %g %g %g\n", p.x(), p.y(), p.z());
            s = ShapeDef::convex(std::move(points));
            break;
        }
        case 5: {
            std::vector<Vec3> vertices(3 + d.byte() % 4);
            for (Vec3& v : vertices) v = d.vec(-3, 3);
            std::vector<std::uint32_t> indices(3 * (1 + d.byte() % 3));
            for (auto& i : indices) i = d.byte() % (vertices.size() + 1);  // sometimes out of range
            s = ShapeDef::mesh(std::move(vertices), std::move(indices));
            break;
        }
        default: {
            std::vector<ShapeDef> children;
            const int n = depth > 1 ? 0 : 1 + d.byte() % 3;
            for (int i = 0; i < n; ++i) children.push_back(shapeFrom(d, depth + 1).placed(d.vec(-1, 1), d.quat()));
            s = ShapeDef::compound(std::move(children));
            if (d.flag() && !s.shapes.empty()) s.shapes[0].density = d.number(1, 5000);
        }
    }
    return s;
}

/// Checks what the layer promises of every event, delivered or read: bodies in pair order, a
/// pair never with itself, no points on exits and trigger events. A broken promise aborts.
void checkEvent(const ContactEvent& e) {
    const bool pointless = e.phase == ContactPhase::Exit || e.trigger;
    if (!(e.bodyA < e.bodyB) || (pointless && !e.points.empty())) {
        std::fprintf(stderr, "fuzz: event breaks the tracker's rules (bodies %u < %u, phase %d, trigger %d, %zu points)\n",
                     e.bodyA.index, e.bodyB.index, int(e.phase), int(e.trigger), e.points.size());
        std::abort();
    }
}

/// A listener that checks every event it receives.
class CheckingListener final : public ContactEventListener {
public:
    void onContactEvent(const ContactEvent& e) override { checkEvent(e); }
};

struct Session {
    CheckingListener listener;  // before the world: it outlives the world's use of it
    bool listening = false;
    std::unique_ptr<World> world;
    std::vector<Body> bodies;    // live and stale alike: stale handles must be refused
    std::vector<Joint> joints;
    bool planar = false;
    int steps = 0;
};

Body anyBody(Decoder& d, const Session& s) {
    if (s.bodies.empty() || d.byte() < 16) return Body();
    return s.bodies[d.byte() % s.bodies.size()];
}
Joint anyJoint(Decoder& d, const Session& s) {
    if (s.joints.empty() || d.byte() < 16) return Joint();
    return s.joints[d.byte() % s.joints.size()];
}

void newWorld(Decoder& d, Session& s) {
    const auto& all = fuzz::backends();
    const BackendInfo& backend = all[d.byte() % all.size()];
    WorldSettings w;
    w.backend = backend.name;
    s.planar = backend.capabilities.dimensions == 2 || (backend.capabilities.planar && d.flag());
    w.planar = s.planar;
    if (d.flag()) w.gravity = d.vec(-20, 20);
    if (d.flag()) w.timeStep = d.number(1e-3, 0.05);
    if (d.flag()) w.integrator = d.pick<Integrator>(5);
    if (d.flag()) w.solver = d.pick<Solver>(3);
    if (d.flag()) w.substeps = 1 + d.byte() % 4;
    if (d.flag()) w.iterations = 1 + d.byte() % 16;
    if (d.flag()) w.divergencePolicy = DivergencePolicy::Freeze;
    if (d.flag()) w.capabilityPolicy = CapabilityPolicy::Lenient;
    if (d.flag()) w.maxSpeed = d.number(1, 1e5);
    if (d.flag()) w.contactImpulses = false;
    if (std::getenv("ANYPHYS_FUZZ_TRACE"))
        std::fprintf(stderr, "  settings gravity %g %g %g timeStep %g integrator %d solver %d substeps %d iterations %d maxSpeed %g contactImpulses %d\n",
                     w.gravity.x(), w.gravity.y(), w.gravity.z(), w.timeStep, int(w.integrator), w.solver ? int(*w.solver) : -1,
                     w.substeps.value_or(-1), w.iterations.value_or(-1), w.maxSpeed, int(w.contactImpulses));
    fuzz::refusedOrDone([&] {
        auto world = std::make_unique<World>(w);
        world->setWarningHandler([](const std::string&) {});
        s.world = std::move(world);
    });
}

void createBody(Decoder& d, Session& s) {
    if (s.bodies.size() >= kMaxBodies) return;
    BodyDef b;
    b.name = d.flag() ? "b" + std::to_string(s.bodies.size()) : "";
    b.type = d.pick<BodyType>(3);
    b.shape = shapeFrom(d, 0);
    b.position = d.vec(-5, 5);
    if (s.planar) b.position.z() = 0;
    if (d.flag()) b.orientation = d.quat();
    if (d.flag()) b.linearVelocity = d.vec(-10, 10);
    if (d.flag()) b.angularVelocity = d.vec(-10, 10);
    if (d.flag()) b.mass = d.number(0.01, 100);
    if (d.flag()) b.density = d.number(1, 5000);
    if (d.flag()) b.inertia = d.vec(0.01, 10);
    if (d.flag()) b.material = d.flag() ? "no-such-material" : "default";
    if (d.flag()) b.linearDamping = d.number(0, 5);
    if (d.flag()) b.angularDamping = d.number(0, 5);
    if (d.flag()) b.gravityScale = d.number(-2, 2);
    if (d.flag()) b.gyroscopic = d.pick<GyroscopicMode>(3);
    b.isTrigger = d.byte() < 24;
    if (d.flag()) b.layer = d.byte();
    if (d.flag()) b.mask = d.byte();
    b.allowSleep = d.flag();
    if (std::getenv("ANYPHYS_FUZZ_TRACE")) {
        const Vec3 inertia = b.inertia.value_or(Vec3::Constant(-1));
        std::fprintf(stderr, "  body %s type %d shape %d radius %g half %g %g %g normal %g %g %g"
                     " offset %g at %g %g %g mass %g density %g inertia %g %g %g\n", b.name.c_str(), int(b.type), int(b.shape.type), b.shape.radius,
                     b.shape.halfExtents.x(), b.shape.halfExtents.y(), b.shape.halfExtents.z(), b.shape.normal.x(),
                     b.shape.normal.y(), b.shape.normal.z(), b.shape.offset, b.position.x(), b.position.y(),
                     b.position.z(), b.mass.value_or(-1), b.density.value_or(-1), inertia.x(), inertia.y(), inertia.z());
        // The motion too: a box's velocity decided where the swallowed-box abort struck.
        std::fprintf(stderr, "    orientation %g %g %g %g velocity %g %g %g spin %g %g %g trigger %d layer %u mask %u"
                     " gravityScale %g damping %g %g gyroscopic %d\n", b.orientation.w(), b.orientation.x(), b.orientation.y(),
                     b.orientation.z(), b.linearVelocity.x(), b.linearVelocity.y(), b.linearVelocity.z(), b.angularVelocity.x(),
                     b.angularVelocity.y(), b.angularVelocity.z(), int(b.isTrigger), unsigned(b.layer), unsigned(b.mask),
                     b.gravityScale, b.linearDamping, b.angularDamping, int(b.gyroscopic));
    }
    fuzz::refusedOrDone([&] { s.bodies.push_back(s.world->createBody(b)); });
}

void createJoint(Decoder& d, Session& s) {
    JointDef j;
    j.type = d.pick<JointType>(7);
    j.bodyA = anyBody(d, s);
    j.bodyB = anyBody(d, s);
    j.anchor = d.vec(-5, 5);
    j.axis = d.vec(-1, 1);
    j.anchorA = d.vec(-5, 5);
    j.anchorB = d.vec(-5, 5);
    if (d.flag()) j.length = d.number(0, 5);
    if (d.flag()) j.minLength = d.number(0, 2);
    if (d.flag()) j.maxLength = d.number(0, 5);
    if (d.flag()) j.swingLimit = d.number(0, 3.2);
    if (d.flag()) j.twistLimits = JointLimits{d.number(-3, 0), d.number(0, 3)};
    if (d.flag()) j.spinAxis = d.vec(-1, 1);
    j.steering = d.flag();
    if (d.flag()) j.limits = JointLimits{d.number(-2, 0), d.number(0, 2)};
    if (d.flag()) j.motor = JointMotor{d.number(-10, 10), d.number(0, 100)};
    if (d.flag()) j.spring = JointSpring{d.number(0, 100), d.number(0, 10), d.number(0, 10), d.number(0, 2)};
    if (d.flag()) j.breakForce = d.number(0, 1000);
    if (d.flag()) j.breakTorque = d.number(0, 1000);
    j.collideConnected = d.flag();
    if (std::getenv("ANYPHYS_FUZZ_TRACE"))
        std::fprintf(stderr, "  joint type %d bodies %u %u anchor %g %g %g axis %g %g %g anchorA %g %g %g anchorB %g %g %g\n",
                     int(j.type), j.bodyA.id().index, j.bodyB.id().index, j.anchor.x(), j.anchor.y(), j.anchor.z(), j.axis.x(),
                     j.axis.y(), j.axis.z(), j.anchorA.x(), j.anchorA.y(), j.anchorA.z(), j.anchorB.x(), j.anchorB.y(), j.anchorB.z());
    fuzz::refusedOrDone([&] { s.joints.push_back(s.world->createJoint(j)); });
}

void touchBody(Decoder& d, Session& s) {
    Body b = anyBody(d, s);
    const int op = d.byte() % 12;
    if (std::getenv("ANYPHYS_FUZZ_TRACE")) std::fprintf(stderr, "  touch %d on body %u\n", op, b.id().index);
    fuzz::refusedOrDone([&] {
        switch (op) {
            case 0: b.setLinearVelocity(d.vec(-10, 10)); break;
            case 1: b.setAngularVelocity(d.vec(-10, 10)); break;
            case 2: b.setTransform(d.vec(-5, 5), d.quat()); break;
            case 3: b.applyForce(d.vec(-100, 100)); break;
            case 4: b.applyForceAtPoint(d.vec(-100, 100), d.vec(-5, 5)); break;
            case 5: b.applyTorque(d.vec(-100, 100)); break;
            case 6: b.applyLinearImpulse(d.vec(-10, 10)); break;
            case 7: b.applyAngularImpulse(d.vec(-10, 10)); break;
            case 8: b.wake(); break;
            case 9: (void)b.angularMomentum(); (void)b.centerOfMass(); (void)b.massProperties(); break;
            case 10: (void)b.state(); (void)b.angularVelocityLocal(); (void)b.isAwake(); (void)b.isFrozen(); break;
            default: (void)b.name(); (void)b.material(); (void)b.type(); (void)b.isTrigger(); break;
        }
    });
}

void touchJoint(Decoder& d, Session& s) {
    static const bool trace = std::getenv("ANYPHYS_FUZZ_TRACE") != nullptr;
    Joint j = anyJoint(d, s);
    fuzz::refusedOrDone([&] {
        switch (d.byte() % 6) {
            case 0: {
                const auto motor = d.flag() ? std::optional<JointMotor>(JointMotor{d.number(-10, 10), d.number(0, 100)}) : std::nullopt;
                if (trace && motor) std::fprintf(stderr, "  motor speed %g maxForce %g\n", motor->speed, motor->maxForce);
                j.setMotor(motor);
                break;
            }
            case 1: {
                const auto limits = d.flag() ? std::optional<JointLimits>(JointLimits{d.number(-2, 0), d.number(0, 2)}) : std::nullopt;
                if (trace && limits) std::fprintf(stderr, "  limits %g %g\n", limits->lower, limits->upper);
                j.setLimits(limits);
                break;
            }
            case 2: {
                // Soft, or stiff far beyond what the step resolves (omega h up to hundreds).
                const auto stiffness = [&] { return d.flag() ? d.number(0, 100) : std::pow(10.0, d.number(2, 9)); };
                const auto damping = [&] { return d.flag() ? d.number(0, 10) : std::pow(10.0, d.number(1, 6)); };
                std::optional<JointSpring> spring;
                if (d.flag()) spring = JointSpring{stiffness(), damping(), 0, 0};
                if (trace && spring) std::fprintf(stderr, "  spring stiffness %g damping %g\n", spring->stiffness, spring->damping);
                j.setSpring(spring);
                break;
            }
            case 3: j.setSteeringAngle(d.number(-1, 1)); break;
            case 4: (void)j.position(); (void)j.speed(); (void)j.reactionForce(); (void)j.reactionTorque(); break;
            default: (void)j.def(); (void)j.bodyA(); (void)j.bodyB(); (void)j.isBroken(); (void)j.type(); break;
        }
    });
}

void query(Decoder& d, Session& s) {
    fuzz::refusedOrDone([&] {
        switch (d.byte() % 3) {
            case 0: (void)s.world->raycast(d.vec(-5, 5), d.vec(-1, 1), d.number(0, 20), d.flag() ? 0xFFFFFFFFu : d.byte()); break;
            case 1: (void)s.world->raycastAll(d.vec(-5, 5), d.vec(-1, 1), d.number(0, 20)); break;
            default: {
                const ShapeDef shape = shapeFrom(d, 1);
                (void)s.world->overlap(shape, Transform{d.vec(-5, 5), d.quat()});
            }
        }
    });
}

class NullDrawer : public DebugDraw {
public:
    void drawShape(BodyId, const ShapeDef&, const Transform&, DebugColor, bool) override {}
    void drawContact(const DebugContact&) override {}
    void drawJoint(JointId, JointType, const Transform&, const Transform&) override {}
    void drawBounds(BodyId, const Vec3&, const Vec3&) override {}
};

void misc(Decoder& d, Session& s) {
    fuzz::refusedOrDone([&] {
        const int op = d.byte() % 5;
        if (std::getenv("ANYPHYS_FUZZ_TRACE")) std::fprintf(stderr, "  misc %d\n", op);
        switch (op) {
            case 0: {
                const Vec3 push = d.vec(-50, 50);
                const Body target = anyBody(d, s);
                s.world->setForceCallback([push, target](ForceContext& c) {
                    c.addForce(target, push);  // a stale or null target must be refused, not crash
                });
                break;
            }
            case 1: s.world->setForceCallback({}); break;
            case 2: {
                FieldDef f;
                f.type = d.pick<FieldType>(4);
                f.fluidDensity = d.number(1, 2000);
                f.surfaceNormal = d.vec(-1, 1);
                f.velocity = d.vec(-20, 20);
                f.impulse = d.number(0, 100);
                f.radius = d.number(0.1, 10);
                f.time = d.number(0, 0.2);
                if (std::getenv("ANYPHYS_FUZZ_TRACE"))
                    std::fprintf(stderr, "  field type %d density %g normal %g %g %g velocity %g %g %g impulse %g radius %g time %g\n",
                                 int(f.type), f.fluidDensity, f.surfaceNormal.x(), f.surfaceNormal.y(), f.surfaceNormal.z(),
                                 f.velocity.x(), f.velocity.y(), f.velocity.z(), f.impulse, f.radius, f.time);
                s.world->addField(f);
                break;
            }
            case 3: s.world->clearFields(); break;
            default: {
                NullDrawer drawer;
                DebugDrawOptions options;
                options.contacts = d.flag();
                options.bounds = d.flag();
                s.world->debugDraw(drawer, options);
            }
        }
    });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Decoder d(data, size);
    Session s;
    newWorld(d, s);
    if (!s.world) return 0;
    // ANYPHYS_FUZZ_TRACE=1: print each call's kind, to read what a crashing input does.
    static const bool trace = std::getenv("ANYPHYS_FUZZ_TRACE") != nullptr;
    static const char* const kCalls[] = {"createBody", "createBody", "destroyBody", "createJoint", "destroyJoint", "touchBody",
                                         "touchJoint", "step", "query", "misc", "update", "new world or events"};
    if (trace) std::fprintf(stderr, "world on %s\n", s.world->backendName().c_str());
    for (int call = 0; call < kMaxCalls && d.more(); ++call) {
        const int kind = d.byte() % 12;
        if (trace) std::fprintf(stderr, "call %d: %s (%zu bodies, %zu joints)\n", call, kCalls[kind], s.world->bodyCount(),
                                s.world->jointCount());
        switch (kind) {
            case 0: case 1: createBody(d, s); break;
            case 2: {
                Body b = anyBody(d, s);
                if (trace) std::fprintf(stderr, "  destroy body %u\n", b.id().index);
                fuzz::refusedOrDone([&] { s.world->destroyBody(b); });
                break;
            }
            case 3: createJoint(d, s); break;
            case 4: { Joint j = anyJoint(d, s); fuzz::refusedOrDone([&] { s.world->destroyJoint(j); }); break; }
            case 5: touchBody(d, s); break;
            case 6: touchJoint(d, s); break;
            case 7:
                if (s.steps < kMaxSteps) {
                    ++s.steps;
                    const bool fixed = d.flag();
                    const double dt = d.number(1e-3, 0.05);
                    fuzz::refusedOrDone([&] { fixed ? s.world->step() : s.world->step(dt); });
                }
                break;
            case 8: query(d, s); break;
            case 9: misc(d, s); break;
            case 10:
                if (s.steps < kMaxSteps) {
                    const double elapsed = d.number(0, 0.1);
                    if (std::getenv("ANYPHYS_FUZZ_TRACE")) std::fprintf(stderr, "  elapsed %g s\n", elapsed);
                    s.steps += 2;
                    fuzz::refusedOrDone([&] { (void)s.world->update(elapsed); });
                }
                break;
            default: {
                // The world goes away while its handles stay: every later use must be refused.
                const std::uint8_t choice = d.byte();
                if (choice < 32) {
                    s.world.reset();
                    s.listening = false;
                    for (const Body& b : s.bodies) if (b.isValid()) std::abort();
                    for (const Joint& j : s.joints) if (j.isValid()) std::abort();
                    newWorld(d, s);
                    if (!s.world) return 0;
                } else if (choice < 64) {
                    // Events: a listener comes or goes, or the last step's events are read (the
                    // first read writes them). No further byte is read, so the inputs of older
                    // corpora decode to the calls they always made.
                    s.listening ? s.world->removeListener(&s.listener) : s.world->addListener(&s.listener);
                    s.listening = !s.listening;
                } else {
                    for (const ContactEvent& e : s.world->lastEvents()) checkEvent(e);
                }
            }
        }
    }
    return 0;
}

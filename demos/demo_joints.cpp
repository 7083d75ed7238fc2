// Joints: one rig per joint type the backend has (the others are listed as skipped, with the
// reason), each hanging from the world with its limits and, where it has one, a motor driving it
// into them. The summary gives each joint's range of motion against its limits.
#include <cstdio>
#include <limits>

#include "thesis_demos.hpp"

namespace anyphys::demo {
namespace {

struct Rig {
    std::string name;
    Joint joint;
    std::optional<JointLimits> limits;
    double lowest = std::numeric_limits<double>::infinity(), highest = -std::numeric_limits<double>::infinity();
};

BodyDef boxAt(const std::string& name, const Vec3& at) {
    BodyDef b;
    b.name = name;
    b.shape = ShapeDef::box({0.15, 0.15, 0.15});
    b.position = at;
    b.mass = 2.0;
    return b;
}

}  // namespace

int runJoints(const DemoOptions& o) {
    const WorldSettings settings = settingsFor(o.backend);
    const Capabilities caps = backendInfo(o.backend).capabilities;
    World world(settings);
    std::vector<Body> bodies;
    std::vector<Rig> rigs;
    std::vector<std::pair<std::string, std::string>> skipped;  // joint type, why
    double x = -6.0;
    for (const auto& [type, typeName] : EnumNames<JointType>::values) {
        const std::string name(typeName);
        if (!caps.jointTypes.contains(name)) {
            skipped.push_back({name, "backend " + o.backend + " has no " + name + " joints"});
            continue;
        }
        x += 2.0;
        const Vec3 top(x, 3.0, 0);
        JointDef def;
        def.name = name;
        def.type = type;
        def.anchor = top;
        const auto has = [&caps, &name](const char* field) { return caps.parameters.contains("joint." + name + "." + field); };
        Body b;
        switch (type) {
            case JointType::Fixed:
            case JointType::Ball:
            case JointType::Cone:
                // Swung out 1 rad, hanging 0.8 m below the anchor.
                b = world.createBody(boxAt(name + "_bob", top + Vec3(0.8 * std::sin(1.0), -0.8 * std::cos(1.0), 0)));
                def.axis = -Vec3::UnitY();
                if (type == JointType::Cone) def.swingLimit = 0.5;
                break;
            case JointType::Hinge:  // a bar turned by a motor into its +-1 rad limits
                b = world.createBody(boxAt(name + "_bar", top + Vec3(0, -0.6, 0)));
                if (has("limits")) def.limits = JointLimits{-1.0, 1.0};
                if (has("motor")) def.motor = JointMotor{1.5, 200.0};
                break;
            case JointType::Slider:  // a block pushed along X by its motor into +-0.5 m
                b = world.createBody(boxAt(name + "_block", top));
                def.axis = Vec3::UnitX();
                if (has("limits")) def.limits = JointLimits{-0.5, 0.5};
                if (has("motor")) def.motor = JointMotor{0.5, 100.0};
                break;
            case JointType::Distance:  // a rope between 0.5 and 1 m
                b = world.createBody(boxAt(name + "_bob", top + Vec3(0.7, 0, 0)));
                def.anchorA = top;
                def.anchorB = top + Vec3(0.7, 0, 0);
                if (has("minLength")) def.minLength = 0.5;
                if (has("maxLength")) def.maxLength = 1.0;
                break;
            case JointType::Wheel: {  // a wheel on a sprung suspension, spun by its motor
                BodyDef wheel = boxAt(name + "_wheel", top + Vec3(0, -0.6, 0));
                wheel.shape = ShapeDef::sphere(0.2);
                b = world.createBody(wheel);
                def.anchor = wheel.position;
                def.axis = Vec3::UnitY();
                def.spinAxis = Vec3::UnitZ();
                if (has("spring")) def.spring = JointSpring{2000.0, 50.0};
                if (has("limits")) def.limits = JointLimits{-0.1, 0.1};
                if (has("motor")) def.motor = JointMotor{10.0, 20.0};
                break;
            }
        }
        def.bodyB = b;
        try {
            rigs.push_back({name, world.createJoint(def), def.limits});
            bodies.push_back(b);
        } catch (const Error& e) {  // e.g. a rig a planar world cannot hold: shown, not hidden
            world.destroyBody(b);
            skipped.push_back({name, e.what()});
        }
    }
    StepHooks hooks;
    hooks.after = [&](long long) {
        for (Rig& r : rigs) {
            r.lowest = std::min(r.lowest, r.joint.position());
            r.highest = std::max(r.highest, r.joint.position());
        }
    };
    const SimulationResult result = simulate(world, bodies, o, hooks);
    std::printf("joints on %s: %zu joint types, %.3f ms per step\n", o.backend.c_str(), rigs.size(), result.msPerStep);
    for (const Rig& r : rigs) {
        std::printf("  %-8s position from %+.3f to %+.3f", r.name.c_str(), r.lowest, r.highest);
        if (r.limits) std::printf(" (limits %+.3f .. %+.3f)", r.limits->lower, r.limits->upper);
        std::printf("\n");
    }
    for (const auto& [name, why] : skipped) std::printf("  %-8s skipped: %s\n", name.c_str(), why.c_str());
    return result.finite ? 0 : 1;
}

}  // namespace anyphys::demo

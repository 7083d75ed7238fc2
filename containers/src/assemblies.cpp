// The built-in assemblies: a humanoid ragdoll and a car, each also for planar worlds. Built once,
// in code, from the dimensions and limits documented in docs/assemblies.md.
#include <map>

#include "anyphys/containers/assembly.hpp"
#include "anyphys/error.hpp"

namespace anyphys {
namespace {


BodyDef capsule(const std::string& name, const Vec3& at, double radius, double length, double mass) {
    BodyDef b;
    b.name = name;
    b.shape = ShapeDef::capsule(radius, 0.5 * length - radius);  // along body Y, `length` end to end
    b.position = at;
    b.mass = mass;
    return b;
}

BodyDef box(const std::string& name, const Vec3& at, const Vec3& half, double mass) {
    BodyDef b;
    b.name = name;
    b.shape = ShapeDef::box(half);
    b.position = at;
    b.mass = mass;
    return b;
}

SceneJoint joint(JointType type, const std::string& a, const std::string& b, const Vec3& anchor, const Vec3& axis,
                 const std::string& name) {
    SceneJoint j;
    j.def.name = name;
    j.def.type = type;
    j.def.anchor = anchor;
    j.def.axis = axis;
    j.bodyA = a;
    j.bodyB = b;
    return j;
}

SceneJoint hinge(const std::string& a, const std::string& b, const Vec3& anchor, const Vec3& axis, double lower,
                 double upper, const std::string& name) {
    SceneJoint j = joint(JointType::Hinge, a, b, anchor, axis, name);
    j.def.limits = JointLimits{lower, upper};
    return j;
}

SceneJoint cone(const std::string& a, const std::string& b, const Vec3& anchor, const Vec3& axis, double swing,
                double twist, const std::string& name) {
    SceneJoint j = joint(JointType::Cone, a, b, anchor, axis, name);
    j.def.swingLimit = swing;
    j.def.twistLimits = JointLimits{-twist, twist};
    return j;
}

// A 1.8 m, 70 kg humanoid standing on y = 0, facing +Z, arms hanging. Segment masses are the
// usual anthropometric fractions (head 8.1 %, trunk 49.7 % split chest 29.5 / pelvis 20.2, upper
// arm 2.8, forearm and hand 2.2, thigh 10, shank and foot 6.1).
// 3D: cones at neck, waist, shoulders and hips (swing and twist limits), hinges at elbows and
// knees. Planar: every joint a hinge about Z with limits, the body seen from the front.
Scene ragdoll(bool planar) {
    Scene s;
    s.settings.planar = planar;
    const double m = 70.0;
    s.bodies.push_back(box("pelvis", {0, 1.06, 0}, {0.16, 0.1, 0.1}, 0.202 * m));
    s.bodies.push_back(box("chest", {0, 1.37, 0}, {0.18, 0.2, 0.11}, 0.295 * m));
    BodyDef head;
    head.name = "head";
    head.shape = ShapeDef::sphere(0.11);
    head.position = {0, 1.70, 0};
    head.mass = 0.081 * m;
    s.bodies.push_back(head);
    for (int side : {1, -1}) {
        const std::string tag = side > 0 ? "_l" : "_r";  // left is +X (the figure faces +Z)
        const double xArm = 0.24 * side, xLeg = 0.1 * side;
        s.bodies.push_back(capsule("upper_arm" + tag, {xArm, 1.37, 0}, 0.045, 0.31, 0.028 * m));
        s.bodies.push_back(capsule("forearm" + tag, {xArm, 1.03, 0}, 0.04, 0.36, 0.022 * m));
        s.bodies.push_back(capsule("thigh" + tag, {xLeg, 0.74, 0}, 0.065, 0.44, 0.100 * m));
        s.bodies.push_back(capsule("shin" + tag, {xLeg, 0.28, 0}, 0.05, 0.46, 0.061 * m));
    }
    const Vec3 up = Vec3::UnitY(), down = -Vec3::UnitY(), z = Vec3::UnitZ();
    if (!planar) {
        s.joints.push_back(cone("chest", "head", {0, 1.58, 0}, up, 0.6, 0.8, "neck"));
        s.joints.push_back(cone("pelvis", "chest", {0, 1.165, 0}, up, 0.5, 0.5, "waist"));
    } else {
        s.joints.push_back(hinge("chest", "head", {0, 1.58, 0}, z, -0.5, 0.5, "neck"));
        s.joints.push_back(hinge("pelvis", "chest", {0, 1.165, 0}, z, -0.4, 0.4, "waist"));
    }
    for (int side : {1, -1}) {
        const std::string tag = side > 0 ? "_l" : "_r";
        const double xArm = 0.24 * side, xLeg = 0.1 * side;
        const Vec3 shoulder(xArm, 1.53, 0), elbow(xArm, 1.215, 0), hip(xLeg, 0.96, 0), knee(xLeg, 0.515, 0);
        if (!planar) {
            s.joints.push_back(cone("chest", "upper_arm" + tag, shoulder, down, 1.6, 1.0, "shoulder" + tag));
            // Flexion turns the forearm forward (+Z): about -X.
            s.joints.push_back(hinge("upper_arm" + tag, "forearm" + tag, elbow, -Vec3::UnitX(), 0.0, 2.6, "elbow" + tag));
            s.joints.push_back(cone("pelvis", "thigh" + tag, hip, down, 1.2, 0.4, "hip" + tag));
            // Flexion turns the shin backward (-Z): about +X.
            s.joints.push_back(hinge("thigh" + tag, "shin" + tag, knee, Vec3::UnitX(), 0.0, 2.5, "knee" + tag));
        } else {
            // Seen from the front: a positive turn about +Z swings a hanging limb toward +X.
            // Arms lift outward to above the head and close in slightly; elbows and knees bend
            // inward (toward the body's middle), legs spread outward.
            const double out = side;  // the sign of a turn away from the body's middle
            s.joints.push_back(hinge("chest", "upper_arm" + tag, shoulder, out * z, -0.2, 2.8, "shoulder" + tag));
            s.joints.push_back(hinge("upper_arm" + tag, "forearm" + tag, elbow, -out * z, 0.0, 2.4, "elbow" + tag));
            s.joints.push_back(hinge("pelvis", "thigh" + tag, hip, out * z, -0.1, 1.2, "hip" + tag));
            s.joints.push_back(hinge("thigh" + tag, "shin" + tag, knee, -out * z, 0.0, 1.5, "knee" + tag));
        }
    }
    return s;
}

// A 1 200 kg car (chassis 4 x 0.6 x 1.8 m, its floor 0.5 m up) on four 20 kg wheels of radius
// 0.35 m at x = +-1.4, z = +-0.8, driving toward +X. Wheel joints: suspension along +Y with k =
// 58 860 N/m and c = 4 200 N s/m (a sag of m g / k = 5 cm under a quarter of the chassis, damping
// ratio about 0.5), travel +-0.15 m; the axle along -Z so that a positive motor speed drives
// forward; the rear pair carries the drive motors (off until set: speed 0, maxForce 0), the front
// pair steers. Planar: one front and one rear wheel in the XY plane.
Scene vehicle(bool planar) {
    Scene s;
    s.settings.planar = planar;
    s.bodies.push_back(box("chassis", {0, 0.8, 0}, {2.0, 0.3, 0.9}, planar ? 600.0 : 1200.0));
    const double k = 58860.0, c = 4200.0;
    struct Wheel {
        std::string name;
        double x, z;
        bool front;
    };
    std::vector<Wheel> wheels;
    if (planar)
        wheels = {{"wheel_front", 1.4, 0.0, true}, {"wheel_rear", -1.4, 0.0, false}};
    else
        wheels = {{"wheel_fl", 1.4, 0.8, true}, {"wheel_fr", 1.4, -0.8, true}, {"wheel_rl", -1.4, 0.8, false},
                  {"wheel_rr", -1.4, -0.8, false}};
    for (const Wheel& w : wheels) {
        BodyDef wheel;
        wheel.name = w.name;
        wheel.shape = ShapeDef::sphere(0.35);
        wheel.position = {w.x, 0.35, w.z};
        wheel.mass = 20.0;
        s.bodies.push_back(wheel);
        SceneJoint j = joint(JointType::Wheel, "chassis", w.name, wheel.position, Vec3::UnitY(),
                             "suspension" + w.name.substr(5));
        j.def.spinAxis = -Vec3::UnitZ();
        j.def.spring = JointSpring{k, c};
        j.def.limits = JointLimits{-0.15, 0.15};
        if (!w.front) j.def.motor = JointMotor{0.0, 0.0};
        j.def.steering = w.front && !planar;
        s.joints.push_back(j);
    }
    return s;
}

const std::map<std::string, Scene>& assemblies() {
    static const std::map<std::string, Scene> all = {
        {"ragdoll", ragdoll(false)},
        {"ragdoll_planar", ragdoll(true)},
        {"vehicle", vehicle(false)},
        {"vehicle_planar", vehicle(true)},
    };
    return all;
}

}  // namespace

std::vector<std::string> builtinAssemblyNames() {
    std::vector<std::string> names;
    for (const auto& [name, scene] : assemblies()) names.push_back(name);
    return names;
}

bool isBuiltinAssembly(const std::string& name) { return assemblies().contains(name); }

const Scene& builtinAssembly(const std::string& name) {
    const auto it = assemblies().find(name);
    if (it == assemblies().end()) {
        std::string known;
        for (const auto& n : builtinAssemblyNames()) known += (known.empty() ? "" : ", ") + n;
        throw Error::invalid("assembly", "\"" + name + "\"", "must be a built-in assembly (" + known + ") or a scene file");
    }
    return it->second;
}

}  // namespace anyphys

// appendInstance: one scene placed into another, moved, turned and renamed.
#include <set>

#include "anyphys/containers/assembly.hpp"
#include "anyphys/error.hpp"

namespace anyphys {
namespace {

bool sameMaterial(const Material& a, const Material& b) {
    return a.friction == b.friction && a.restitution == b.restitution && a.density == b.density;
}

bool samePair(const PairOverride& a, const PairOverride& b) { return a.friction == b.friction && a.restitution == b.restitution; }

}  // namespace

void appendInstance(Scene& target, const Scene& assembly, const Transform& pose, const std::string& prefix) {
    const Quat& q = pose.orientation;
    const auto place = [&pose, &q](const Vec3& p) -> Vec3 { return pose.position + q * p; };

    // Check every clash first, so a refused instance leaves the target as it was.
    std::set<std::string> names;
    for (const BodyDef& b : target.bodies) names.insert(b.name);
    for (const BodyDef& b : assembly.bodies)
        if (!names.insert(prefix + b.name).second)
            throw Error("instance \"" + prefix + "\": body name \"" + prefix + b.name +
                        "\" is already used in the scene (give the instance another prefix)");
    std::set<std::string> jointNames;
    for (const SceneJoint& j : target.joints)
        if (!j.def.name.empty()) jointNames.insert(j.def.name);
    for (const SceneJoint& j : assembly.joints)
        if (!j.def.name.empty() && !jointNames.insert(prefix + j.def.name).second)
            throw Error("instance \"" + prefix + "\": joint name \"" + prefix + j.def.name + "\" is already used in the scene");
    for (const std::string& name : assembly.materials.names())
        if (target.materials.contains(name) && !sameMaterial(target.materials.get(name), assembly.materials.get(name)))
            throw Error("instance \"" + prefix + "\": material \"" + name +
                        "\" has other values than the scene's material of that name");
    for (const auto& [key, values] : assembly.materials.pairOverrides()) {
        const auto mine = target.materials.pairOverride(key.first, key.second);
        if (mine && !samePair(*mine, values))
            throw Error("instance \"" + prefix + "\": the material pair (\"" + key.first + "\", \"" + key.second +
                        "\") has other values than the scene's");
    }

    for (const std::string& name : assembly.materials.names())
        if (!target.materials.contains(name)) target.materials.add(name, assembly.materials.get(name));
    for (const auto& [key, values] : assembly.materials.pairOverrides())
        target.materials.setPairOverride(key.first, key.second, values);
    for (BodyDef b : assembly.bodies) {
        b.name = prefix + b.name;
        b.position = place(b.position);
        b.orientation = (q * b.orientation).normalized();
        b.linearVelocity = q * b.linearVelocity;
        b.angularVelocity = q * b.angularVelocity;
        target.bodies.push_back(std::move(b));
    }
    for (SceneJoint j : assembly.joints) {
        if (!j.def.name.empty()) j.def.name = prefix + j.def.name;
        if (!j.bodyA.empty()) j.bodyA = prefix + j.bodyA;
        j.bodyB = prefix + j.bodyB;
        j.def.anchor = place(j.def.anchor);
        j.def.anchorA = place(j.def.anchorA);
        j.def.anchorB = place(j.def.anchorB);
        j.def.axis = q * j.def.axis;
        j.def.spinAxis = q * j.def.spinAxis;
        target.joints.push_back(std::move(j));
    }
}

}  // namespace anyphys

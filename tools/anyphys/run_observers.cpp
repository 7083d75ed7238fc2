// The per-step watchers of a sweep run.
#include "run_observers.hpp"

#include <map>

namespace anyphys::cli {
namespace {

Vec3 toLocal(const std::optional<std::size_t>& body, const Vec3& point, const std::vector<BodyState>& s) {
    return body ? Vec3(s[*body].orientation.conjugate() * (point - s[*body].position)) : point;
}

Vec3 toWorld(const std::optional<std::size_t>& body, const Vec3& local, const std::vector<BodyState>& s) {
    return body ? Vec3(s[*body].position + s[*body].orientation * local) : local;
}

Vec3 directionToWorld(const std::optional<std::size_t>& body, const Vec3& local, const std::vector<BodyState>& s) {
    return body ? Vec3(s[*body].orientation * local) : local;
}

}  // namespace

PenetrationWatch::PenetrationWatch(const World& world)
    : active_(world.activeEffects().has(Effect::Contacts) && world.activeEffects().has(Effect::Events)) {}

void PenetrationWatch::observe(const World& world) {
    if (!active_) return;
    for (const ContactEvent& event : world.lastEvents()) {
        if (event.trigger || event.phase == ContactPhase::Exit) continue;
        for (const ContactPoint& point : event.points)
            if (!(point.depth <= worst_)) worst_ = point.depth;  // keeps a NaN visible
    }
}

std::optional<double> PenetrationWatch::value() const {
    if (!active_) return std::nullopt;
    return worst_;
}

JointGapWatch::JointGapWatch(const Scene& scene, const std::vector<BodyState>& states) {
    std::map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) index[scene.bodies[i].name] = i;
    const auto find = [&index](const std::string& name) -> std::optional<std::size_t> {
        if (name.empty()) return std::nullopt;
        return index.at(name);
    };
    for (const SceneJoint& joint : scene.joints) {
        const JointType type = joint.def.type;
        if (type == JointType::Distance || type == JointType::Wheel) continue;
        Link link{find(joint.bodyA), find(joint.bodyB), {}, {}, {}};
        link.localA = toLocal(link.a, joint.def.anchor, states);
        link.localB = toLocal(link.b, joint.def.anchor, states);
        if (type == JointType::Slider) {
            const Vec3 axis = joint.def.axis.normalized();
            link.axisInA = link.a ? Vec3(states[*link.a].orientation.conjugate() * axis) : axis;
        }
        links_.push_back(link);
    }
}

void JointGapWatch::observe(const std::vector<BodyState>& states) {
    for (const Link& link : links_) {
        Vec3 gap = toWorld(link.a, link.localA, states) - toWorld(link.b, link.localB, states);
        if (link.axisInA) {
            const Vec3 axis = directionToWorld(link.a, *link.axisInA, states);
            gap -= gap.dot(axis) * axis;
        }
        const double g = gap.norm();
        if (!(g <= worst_)) worst_ = g;
    }
}

std::optional<double> JointGapWatch::value() const {
    if (links_.empty()) return std::nullopt;
    return worst_;
}

}  // namespace anyphys::cli

#include "joint_gaps.hpp"

#include <algorithm>
#include <cmath>

namespace anyphys::demo {
namespace {

Vec3 local(const Body& body, const Vec3& point) { return body.orientation().conjugate() * (point - body.position()); }

}  // namespace

JointMeter::JointMeter(const Scene& scene, const SceneObjects& objects) {
    for (std::size_t i = 0; i < scene.joints.size(); ++i) {
        const SceneJoint& sj = scene.joints[i];
        const Body a = sj.bodyA.empty() ? Body() : objects.body(sj.bodyA);
        const Body b = objects.body(sj.bodyB);
        anchors_.push_back({a, b, a.isValid() ? local(a, sj.def.anchor) : sj.def.anchor, local(b, sj.def.anchor)});
        if (sj.def.type == JointType::Hinge && sj.def.limits) hinges_.push_back({objects.joints[i], *sj.def.limits});
    }
}

void JointMeter::observe() {
    for (const Anchored& j : anchors_) {
        const Vec3 pa = j.a.isValid() ? Vec3(j.a.position() + j.a.orientation() * j.onA) : j.onA;
        const double gap = (pa - (j.b.position() + j.b.orientation() * j.onB)).norm();
        if (!(gap <= worstGap_)) worstGap_ = gap;  // keeps a NaN visible
    }
    for (const LimitedHinge& h : hinges_) {
        const double angle = h.joint.position();
        worstLimit_ = std::max({worstLimit_, h.limits.lower - angle, angle - h.limits.upper});
    }
}

void RestTimer::observe(double time, const std::vector<Body>& bodies) {
    const bool still = std::all_of(bodies.begin(), bodies.end(), [this](const Body& b) {
        return b.type() != BodyType::Dynamic || b.linearVelocity().norm() < speed_;
    });
    if (!still) {
        moving_ = true;
    } else if (moving_) {
        moving_ = false;
        since_ = time;
    }
}

}  // namespace anyphys::demo

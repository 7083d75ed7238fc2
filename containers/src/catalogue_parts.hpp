#pragma once
// Building blocks of catalogue scenes, shared by the scene catalogue and the hard-case
// catalogue (internal to containers/): probes that reduce a run to one number, and common bodies.
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "anyphys/containers/scene_catalogue.hpp"

namespace anyphys::catalogue_parts {

inline BodyDef sphereBody(const std::string& name, double radius, double mass) {
    BodyDef def;
    def.name = name;
    def.shape = ShapeDef::sphere(radius);
    def.mass = mass;
    return def;
}

/// Reduces a run to f(initial states, final states, final time); most checks need no more.
class EndpointProbe : public SceneProbe {
public:
    using Measure = std::function<double(const std::vector<BodyState>&, const std::vector<BodyState>&, double)>;
    explicit EndpointProbe(Measure measure) : measure_(std::move(measure)) {}
    void observe(double time, const std::vector<BodyState>& states) override {
        if (first_.empty()) first_ = states;
        last_ = states;
        time_ = time;
    }
    double value() const override { return first_.empty() ? 0.0 : measure_(first_, last_, time_); }

private:
    Measure measure_;
    std::vector<BodyState> first_, last_;
    double time_ = 0.0;
};

inline SceneCheck endpointCheck(SceneCheck check, EndpointProbe::Measure measure) {
    check.makeProbe = [measure] { return std::make_unique<EndpointProbe>(measure); };
    return check;
}

/// The worst of f(initial states, current states, time) over every observation: a stack that
/// slid apart and came back, or one frozen by sleep before its drift showed, is still caught.
class WorstOverRunProbe : public SceneProbe {
public:
    explicit WorstOverRunProbe(EndpointProbe::Measure measure) : measure_(std::move(measure)) {}
    void observe(double time, const std::vector<BodyState>& states) override {
        if (first_.empty()) first_ = states;
        const double v = measure_(first_, states, time);
        if (!(v <= worst_)) worst_ = v;  // keeps a NaN (blow-up) visible
    }
    double value() const override { return worst_; }

private:
    EndpointProbe::Measure measure_;
    std::vector<BodyState> first_;
    double worst_ = 0.0;
};

inline SceneCheck worstOverRunCheck(SceneCheck check, EndpointProbe::Measure measure) {
    check.makeProbe = [measure] { return std::make_unique<WorstOverRunProbe>(measure); };
    return check;
}

/// First rebound of a dropped body, as a fraction of its drop: (apex - rest) / (start - rest),
/// where `rest` is its height when touching the ground. Exact for restitution e: e^2.
class ReboundProbe : public SceneProbe {
public:
    ReboundProbe(std::size_t body, double restHeight) : body_(body), rest_(restHeight) {}
    void observe(double, const std::vector<BodyState>& states) override {
        const BodyState& s = states.at(body_);
        const double y = s.position.y(), vy = s.linearVelocity.y();
        if (!start_) start_ = y;
        if (phase_ == Phase::Falling && vy > 0) phase_ = Phase::Rising;  // the first bounce
        if (phase_ == Phase::Rising) {
            if (!(y <= apex_)) apex_ = y;  // keeps a NaN (blow-up) visible
            if (vy < 0) phase_ = Phase::Done;  // past the apex: later bounces do not count
        }
    }
    double value() const override {
        if (!start_ || phase_ == Phase::Falling) return 0.0;  // no rebound (yet)
        return (apex_ - rest_) / (*start_ - rest_);
    }

private:
    enum class Phase { Falling, Rising, Done };
    std::size_t body_;
    double rest_;
    std::optional<double> start_;
    double apex_ = -std::numeric_limits<double>::infinity();
    Phase phase_ = Phase::Falling;
};

/// Indices of the dynamic bodies of a scene.
inline std::vector<std::size_t> dynamicBodies(const Scene& scene) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
        if (scene.bodies[i].type == BodyType::Dynamic) out.push_back(i);
    return out;
}

/// Largest horizontal (x, z) distance any of `bodies` moved from its start: a standing stack
/// moves ~0 sideways. Vertical settling is left out: resting contacts keep a designed overlap
/// (settings.linearSlop each), so a tall stack sinks by design without drifting.
inline EndpointProbe::Measure maxHorizontalDrift(std::vector<std::size_t> bodies) {
    return [bodies](const std::vector<BodyState>& first, const std::vector<BodyState>& last, double) {
        double worst = 0.0;
        for (std::size_t i : bodies) {
            const Vec3 moved = last[i].position - first[i].position;
            const double d = std::hypot(moved.x(), moved.z());
            if (!(d <= worst)) worst = d;  // keeps a NaN (blow-up) visible
        }
        return worst;
    };
}

inline BodyDef groundPlane() {
    BodyDef ground;
    ground.name = "ground";
    ground.type = BodyType::Static;
    ground.shape = ShapeDef::plane(Vec3(0, 1, 0), 0.0);
    return ground;
}

inline BodyDef unitBox(const std::string& name, const Vec3& position) {
    BodyDef box;
    box.name = name;
    box.shape = ShapeDef::box(Vec3(0.5, 0.5, 0.5));  // 1 m cube, 1000 kg at the default density
    box.position = position;
    return box;
}

/// The hard cases (hard_cases.cpp), each with CatalogueScene::hardCase set.
std::vector<CatalogueScene> hardCaseScenes();

}  // namespace anyphys::catalogue_parts

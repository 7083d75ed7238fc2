// The planar benchmark scenes written directly against Box2D 2.4.1, configured as backends/box2d
// configures its world, so that anyphys on "box2d" and this program differ by the layer alone:
//   raw/<scene>/box2d        drop_planar, pyramid20_planar, pyramid_planar
//   overhead/<scene>/box2d   drop_planar, pyramid_planar (see raw_benchmarks.hpp)
// A plain b2World: fixture friction mixed by Box2D (sqrt(0.6 x 0.6)), no contact listener or
// filter, mass and inertia set as the layer computes them.
#include <box2d/box2d.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../bench_main.hpp"
#include "raw_benchmarks.hpp"

namespace anyphys::bench {
namespace {

// The backend's values (backends/box2d/box2d_world.hpp, box2d_shapes.cpp, box2d_convert.hpp),
// repeated here because raw Box2D must be driven the same way: change both together.
constexpr int kVelocityIterations = 8;  // kDefaultIterations
constexpr int kPositionIterations = 3;  // kDefaultPositionIterations
// Fixtures are the true outline grown by a skin of half b2_linearSlop, built as a core polygon
// with Box2D's rounding radius: core = outline - (b2_polygonRadius - skin), radius = b2_polygonRadius.
constexpr double kSkin = 0.5 * b2_linearSlop;
constexpr double kCoreInset = b2_polygonRadius - kSkin;

/// A box fixture of half extents (hx, hy) as the backend builds it.
b2PolygonShape skinnedBox(double hx, double hy) {
    b2PolygonShape shape;
    shape.SetAsBox(static_cast<float>(hx - kCoreInset), static_cast<float>(hy - kCoreInset));
    shape.m_radius = static_cast<float>(kCoreInset + kSkin);
    return shape;
}

class Box2dSimulation final : public Simulation {
public:
    explicit Box2dSimulation(const ScenePlan& plan) : world_(b2Vec2(0.0f, static_cast<float>(kGravity))) {
        world_.SetAllowSleeping(false);  // sleeping off

        b2BodyDef groundDef;
        groundDef.position.Set(0.0f, -1.0f);
        b2Body* ground = world_.CreateBody(&groundDef);
        addFixture(ground, skinnedBox(plan.groundHalf.x(), plan.groundHalf.y()));

        const b2PolygonShape box = skinnedBox(kHalf, kHalf);
        b2MassData mass;
        mass.mass = static_cast<float>(plan.mass());
        mass.center.SetZero();
        mass.I = static_cast<float>(plan.inertia().z());  // about Z, through the centre
        for (const Vec3& start : plan.starts) {
            b2BodyDef def;
            def.type = b2_dynamicBody;
            def.position.Set(static_cast<float>(start.x()), static_cast<float>(start.y()));
            def.allowSleep = false;
            b2Body* body = world_.CreateBody(&def);
            addFixture(body, box);
            body->SetMassData(&mass);
            boxes_.push_back(body);
        }
    }

    void step() override { world_.Step(static_cast<float>(kTimeStep), kVelocityIterations, kPositionIterations); }

    void readBoxes(std::vector<BoxState>& out) const override {
        out.resize(boxes_.size());
        for (std::size_t i = 0; i < boxes_.size(); ++i) {
            const b2Body* b = boxes_[i];
            const b2Vec2 p = b->GetPosition(), v = b->GetLinearVelocity();
            out[i] = {Vec3(p.x, p.y, 0.0), Quat(Eigen::AngleAxisd(b->GetAngle(), Vec3::UnitZ())), Vec3(v.x, v.y, 0.0)};
        }
    }

    std::string describe() const override {
        return "pgs, 1 step x " + std::to_string(kVelocityIterations) + " it + " + std::to_string(kPositionIterations) +
               " position it";
    }

private:
    static void addFixture(b2Body* body, const b2PolygonShape& shape) {
        b2FixtureDef fixture;
        fixture.shape = &shape;
        fixture.density = 0.0f;  // mass from the plan (the layer's), not from Box2D's area
        fixture.friction = static_cast<float>(kFriction);
        fixture.restitution = 0.0f;
        body->CreateFixture(&fixture);
    }

    b2World world_;
    std::vector<b2Body*> boxes_;
};

void registerAll() {
    registerRaw({"box2d",
                 {"drop_planar", "pyramid20_planar", "pyramid_planar"},
                 {"drop_planar", "pyramid_planar"},
                 [](const ScenePlan& plan) { return std::make_unique<Box2dSimulation>(plan); }});
}

}  // namespace
}  // namespace anyphys::bench

int main(int argc, char** argv) { return anyphys::bench::benchMain(argc, argv, &anyphys::bench::registerAll); }

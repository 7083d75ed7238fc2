// Multiple collision volumes: three compound bodies (a dumbbell, an L of two boxes, a table of a
// top and four legs) dropped on the ground. Each rests on its volumes, and the layer puts its
// centre of mass where the children's mass-weighted centres say.
#include <cstdio>

#include "thesis_demos.hpp"

namespace anyphys::demo {
namespace {

struct Compound {
    std::string name;
    ShapeDef shape;
    Vec3 at;
};

// In a planar world every child lies in the XY plane: the table keeps two legs.
std::vector<Compound> compounds(bool planar) {
    const double legZ = planar ? 0.0 : 0.3;
    return {
        {"dumbbell",
         ShapeDef::compound({ShapeDef::sphere(0.2).placed({-0.5, 0, 0}), ShapeDef::sphere(0.2).placed({0.5, 0, 0}),
                             ShapeDef::capsule(0.05, 0.4).placed({0, 0, 0}, Quat(Eigen::AngleAxisd(1.5707963267948966, Vec3::UnitZ())))}),
         {-3, 1.5, 0}},
        {"ell", ShapeDef::compound({ShapeDef::box({0.6, 0.1, 0.2}).placed({0, 0, 0}), ShapeDef::box({0.1, 0.4, 0.2}).placed({0.5, 0.5, 0})}),
         {0, 2.0, 0}},
        {"table",
         ShapeDef::compound({ShapeDef::box({0.6, 0.05, 0.4}).placed({0, 0.5, 0}), ShapeDef::box({0.05, 0.25, 0.05}).placed({0.5, 0.2, legZ}),
                             ShapeDef::box({0.05, 0.25, 0.05}).placed({-0.5, 0.2, legZ}), ShapeDef::box({0.05, 0.25, 0.05}).placed({0.5, 0.2, -legZ}),
                             ShapeDef::box({0.05, 0.25, 0.05}).placed({-0.5, 0.2, -legZ})}),
         {3, 1.0, 0}},
    };
}

/// Mass-weighted centre of a compound's children (uniform density), in the body frame.
Vec3 childCentre(const ShapeDef& compound) {
    Vec3 sum = Vec3::Zero();
    double volume = 0.0;
    for (const ShapeDef& c : compound.shapes) {
        const double v = c.type == ShapeType::Sphere ? 4.18879020478639 * c.radius * c.radius * c.radius
                         : c.type == ShapeType::Box  ? 8.0 * c.halfExtents.prod()
                                                     : 3.14159265358979 * c.radius * c.radius * (2 * c.halfHeight + 4.0 / 3.0 * c.radius);
        sum += v * c.position;
        volume += v;
    }
    return sum / volume;
}

}  // namespace

int runVolumes(const DemoOptions& o) {
    const WorldSettings settings = settingsFor(o.backend);
    World world(settings);
    std::vector<Body> bodies{world.createBody(groundPlane())};
    for (const Compound& c : compounds(settings.planar)) {
        BodyDef def;
        def.name = c.name;
        def.shape = c.shape;
        def.position = c.at;
        bodies.push_back(world.createBody(def));
    }
    const SimulationResult r = simulate(world, bodies, o);
    std::printf("volumes on %s: %zu compound bodies dropped, %.3f ms per step\n", o.backend.c_str(), bodies.size() - 1, r.msPerStep);
    const std::vector<Compound> list = compounds(settings.planar);
    for (std::size_t i = 0; i < list.size(); ++i) {
        const Body& b = bodies[i + 1];
        const Vec3 com = b.orientation().conjugate() * (b.centerOfMass() - b.position());
        std::printf("  %-8s rests at y = %.3f m, centre of mass off the children's by %.1e m, speed %.3f m/s\n",
                    list[i].name.c_str(), b.position().y(), (com - childCentre(list[i].shape)).norm(), b.linearVelocity().norm());
    }
    return r.finite ? 0 : 1;
}

}  // namespace anyphys::demo

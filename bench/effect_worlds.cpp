#include "effect_worlds.hpp"

#include <algorithm>
#include <stdexcept>

#include "anyphys/peers/world_peer.hpp"
#include "layer_simulation.hpp"

namespace anyphys::bench {
namespace {

// The pile's extent: drop200 stands 8 boxes high in x, z within +-2.7 m; drop200_planar 10 high
// in x within +-10.5 m. Each effect is placed to act on it the way a game scene would.
double pileTop(const ScenePlan& plan) {
    double top = 0.0;
    for (const Vec3& p : plan.starts) top = std::max(top, p.y() + kHalf);
    return top;
}

// Half the pile in water half as dense as the boxes (they stay a pile), with the drag rates.
FieldDef buoyancy(const ScenePlan& plan) { return FieldDef::buoyancy(500.0, Vec3(0, 1, 0), 0.5 * pileTop(plan), 1.0, 0.5); }

// One blast due in every step (at its middle), in the pile's lower half, 3 m across: each step
// pays the overlap query, the ray casts against static geometry and the impulses, and the scan of
// every held field for the one that is due. 50 N s moves a 1000 kg box by 5 cm/s: the pile stays.
void addExplosions(World& world, const ScenePlan& plan) {
    for (int k = 0; k <= plan.steps; ++k)
        world.addField(FieldDef::explosion(Vec3(0, 2, 0), (k + 0.5) * kTimeStep, 50.0, 3.0));
}

// A block of water beside the pile that collapses against it: 10^3 particles at 0.1 m in 3D, 32^2
// at 0.05 m in the plane.
FluidDef fluid(const ScenePlan& plan) {
    FluidDef f;
    f.name = "water";
    const double x0 = plan.planar ? 11.0 : 3.5;
    f.spacing = plan.planar ? 0.05 : 0.1;
    const double side = plan.planar ? 1.6 : 1.0;
    f.boxMin = Vec3(x0, 0.0, plan.planar ? -0.05 : -0.5);
    f.boxMax = Vec3(x0 + side, side, plan.planar ? 0.05 : 0.5);
    return f;
}

// A sheet dropped on the pile from just above it: 20 x 20 cells over 4 x 4 m in 3D (441 nodes), a
// membrane 40 x 10 cells over 20 x 2 m in the plane (451 nodes).
ClothDef cloth(const ScenePlan& plan) {
    ClothDef c;
    c.name = "sheet";
    const double top = pileTop(plan) + 0.5;
    if (plan.planar) {
        c.corner = Vec3(-10.0, top + 2.0, 0.0);
        c.axisV = Vec3(0, -1, 0);
        c.size = {20.0, 2.0};
        c.resolution = {40, 10};
    } else {
        c.corner = Vec3(-2.0, top, -2.0);
        c.axisV = Vec3(0, 0, 1);
        c.size = {4.0, 4.0};
        c.resolution = {20, 20};
    }
    return c;
}

// What the pile derives, declared, without contact events: the world's per-step work is then only
// the divergence check around the peer's step.
Effects withoutEvents(const ScenePlan& plan, const std::string& backend) {
    World probe(pileSettings(plan, backend));
    createPile(probe, plan);
    Effects effects = probe.activeEffects();
    return effects.remove(Effect::Events);
}

}  // namespace

const std::vector<std::pair<std::string, SpecialEffect>>& specialEffects() {
    static const std::vector<std::pair<std::string, SpecialEffect>> all = {
        {"buoyancy", SpecialEffect::Buoyancy}, {"drag", SpecialEffect::Drag},   {"wind", SpecialEffect::Wind},
        {"explosion", SpecialEffect::Explosion}, {"fluid", SpecialEffect::Fluid}, {"cloth", SpecialEffect::Cloth}};
    return all;
}

PileSimulation::PileSimulation(const ScenePlan& plan, const std::string& backend, const PileOptions& options) {
    WorldSettings settings = pileSettings(plan, backend);
    if (!options.events) settings.effects = withoutEvents(plan, backend);
    if (options.effect == SpecialEffect::Restitution) {
        // The default material's friction and a bounce: the lowest layer lands at 1.4 m/s, above
        // the 1 m/s restitution threshold, and the layers above hit it faster.
        MaterialLibrary materials;
        materials.add("bouncy", Material{kFriction, 0.5, plan.density});
        world_ = std::make_unique<World>(settings, materials);
        boxes_ = createPile(*world_, plan, "bouncy");
    } else {
        world_ = std::make_unique<World>(settings);
        boxes_ = createPile(*world_, plan);
    }
    units_ = plan.count();
    switch (options.effect) {
        case SpecialEffect::None:
        case SpecialEffect::Restitution: break;
        case SpecialEffect::Buoyancy: world_->addField(buoyancy(plan)); break;
        case SpecialEffect::Drag: world_->addField(FieldDef::drag(1.2)); break;
        case SpecialEffect::Wind: world_->addField(FieldDef::wind(Vec3(6, 0, 0), 1.2)); break;
        case SpecialEffect::Explosion: addExplosions(*world_, plan); break;
        case SpecialEffect::Fluid: world_->addFluid(fluid(plan)); break;
        case SpecialEffect::Cloth: world_->addCloth(cloth(plan)); break;
    }
    if (options.effect == SpecialEffect::Fluid || options.effect == SpecialEffect::Cloth)
        units_ = static_cast<int>(world_->particleSystems().at(0).positions->size());
    if (options.viaPeer) {
        peer_ = world_->native<WorldPeer>();
        if (!peer_) throw std::logic_error("World::native<WorldPeer>() gave no peer");
    }
}

// The bare peer: what World::step hands the backend, without the layer's work around it (the
// effect stages, the divergence check, joint breaking, contact events).
void PileSimulation::step() {
    if (!peer_) {
        world_->step();
        return;
    }
    peer_->step(time_, kTimeStep);
    time_ += kTimeStep;
}

void PileSimulation::readBoxes(std::vector<BoxState>& out) const { readStates(boxes_, out); }

std::string PileSimulation::describe() const { return describeSolver(*world_); }

}  // namespace anyphys::bench

// The particle stage: fluids and cloths advance after the rigid step, colliding with every body at
// its new pose; the impulses the particles gave each dynamic body are applied to it through the
// backend (equal and opposite to what the particles received, so momentum is conserved). Only body
// states and impulses are used, so it runs alike on every backend.
#include <algorithm>

#include "anyphys/validation.hpp"
#include "anyphys/world.hpp"
#include "world_impl.hpp"

namespace anyphys {

namespace {

void requireInPlane(const std::string& field, const Vec3& v, const char* rule) {
    if (std::abs(v.z()) > 1e-9 * std::max(1.0, v.norm())) throw Error::invalid(field, formatVec3(v), rule);
}

}  // namespace

void World::addFluid(const FluidDef& fluid) {
    impl_->refuseWhileStepping("World.addFluid");
    impl_->refuseWhileDrawing("World.addFluid");
    validate(fluid, "FluidDef");
    if (settings_.effects && !settings_.effects->has(Effect::Fluid))
        throw Error(ErrorKind::Unsupported, "WorldSettings.effects",
                    "World.addFluid: the world's declared effects exclude \"fluid\"; add it to WorldSettings.effects");
    impl_->fluids.push_back(std::make_unique<FluidSystem>(fluid, settings_.planar));
    impl_->fluidDefs.push_back(fluid);
    impl_->particleEffects.add(Effect::Fluid);
    refreshEffects();
}

const std::vector<FluidDef>& World::fluids() const { return impl_->fluidDefs; }

void World::addCloth(const ClothDef& cloth) {
    impl_->refuseWhileStepping("World.addCloth");
    impl_->refuseWhileDrawing("World.addCloth");
    validate(cloth, "ClothDef");
    if (settings_.planar) {
        const char* rule = "must lie in the XY plane (z = 0) in a planar world: the sheet then moves in the plane";
        requireInPlane("ClothDef.corner", cloth.corner, rule);
        requireInPlane("ClothDef.axisU", cloth.axisU, rule);
        requireInPlane("ClothDef.axisV", cloth.axisV, rule);
    }
    if (settings_.effects && !settings_.effects->has(Effect::Cloth))
        throw Error(ErrorKind::Unsupported, "WorldSettings.effects",
                    "World.addCloth: the world's declared effects exclude \"cloth\"; add it to WorldSettings.effects");
    impl_->cloths.push_back(std::make_unique<ClothSystem>(cloth, settings_.planar));
    impl_->clothDefs.push_back(cloth);
    impl_->particleEffects.add(Effect::Cloth);
    refreshEffects();
}

const std::vector<ClothDef>& World::cloths() const { return impl_->clothDefs; }

void World::clearParticles() {
    impl_->refuseWhileStepping("World.clearParticles");
    impl_->refuseWhileDrawing("World.clearParticles");
    impl_->fluids.clear();
    impl_->fluidDefs.clear();
    impl_->cloths.clear();
    impl_->clothDefs.clear();
    impl_->particleEffects = Effects::none();
    for (Slot& s : impl_->slots) s.particleForce = Vec3::Zero();
    refreshEffects();
}

std::vector<ParticleSystemView> World::particleSystems() const {
    std::vector<ParticleSystemView> out;
    for (const auto& f : impl_->fluids)
        out.push_back({f->def().name, "fluid", &f->positions(), &f->velocities(), f->particleRadius()});
    for (const auto& c : impl_->cloths)
        out.push_back({c->def().name, "cloth", &c->positions(), &c->velocities(), c->def().thickness});
    return out;
}

Vec3 World::particleForce(Body body) const {
    if (body.world() != this)
        throw Error(body.world() ? ErrorKind::InvalidState : ErrorKind::StaleHandle, "",
                    body.world() ? "World.particleForce: the body belongs to another world"
                                 : "World.particleForce: stale body handle (null, or its world was destroyed)");
    return slot(body.id(), "World.particleForce").particleForce;
}

void World::stepParticles(double dt) {
    const bool fluids = activeEffects_.has(Effect::Fluid), cloths = activeEffects_.has(Effect::Cloth);
    // The colliders: every non-trigger body whose bounds reach the particles' bounds.
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    double margin = 0.0;
    const auto grow = [&](const std::vector<Vec3>& points, double radius) {
        for (const Vec3& p : points) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        margin = std::max(margin, radius);
    };
    if (fluids)
        for (const auto& f : impl_->fluids) grow(f->positions(), f->particleRadius() + 2.0 * f->def().spacing);
    if (cloths)
        for (const auto& c : impl_->cloths) grow(c->positions(), c->def().thickness + std::max(c->restU(), c->restV()));
    // Particles move during the step: reach as far as a fast particle may go in one step.
    margin += 10.0 * settings_.gravity.norm() * dt * dt + 0.5;
    lo -= Vec3::Constant(margin);
    hi += Vec3::Constant(margin);
    auto& colliders = impl_->colliders;
    auto& slots = impl_->colliderSlots;
    colliders.clear();
    slots.clear();
    for (std::uint32_t i = 0; i < impl_->slots.size(); ++i) {
        Slot& s = impl_->slots[i];
        s.particleForce = Vec3::Zero();
        if (!s.peer || s.def.isTrigger) continue;
        const BodyState state = s.peer->state();
        ParticleCollider c;
        c.body = &s.fieldGeometry();
        c.pose = {state.position, state.orientation};
        c.linearVelocity = state.linearVelocity;
        c.angularVelocity = state.angularVelocity;
        c.dynamic = s.def.type == BodyType::Dynamic;
        colliderBounds(c);
        if ((c.boundsMax.array() < lo.array()).any() || (c.boundsMin.array() > hi.array()).any()) continue;
        colliders.push_back(c);
        slots.push_back(i);
    }
    ParticleEnvironment env{settings_.gravity, &impl_->fields, settings_.planar};
    if (fluids)
        for (auto& f : impl_->fluids) f->step(dt, env, colliders);
    if (cloths)
        for (auto& c : impl_->cloths) c->step(dt, env, colliders);
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        ParticleCollider& c = colliders[k];
        Slot& s = impl_->slots[slots[k]];
        Vec3 linear = c.impulse, angular = c.angularImpulse;
        if (settings_.planar) {
            linear.z() = 0.0;
            angular.x() = angular.y() = 0.0;
        }
        s.particleForce = linear / dt;
        if (!c.dynamic || (linear.isZero(0) && angular.isZero(0))) continue;
        s.peer->applyLinearImpulse(linear);
        if (!angular.isZero(0)) s.peer->applyAngularImpulse(angular);
    }
}

}  // namespace anyphys

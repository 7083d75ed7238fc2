// Position-based fluids (Macklin and Mueller 2013): each substep predicts positions under gravity,
// then a few Jacobi iterations move particles so that each one's SPH density estimate does not
// exceed the rest density, pushing them out of rigid shapes after each; velocities follow from the
// positions. The density constraint is one-sided (C = max(rho / rho0 - 1, 0)): a particle at the
// free surface, short of neighbours, is not pulled in, so there is no tensile clumping and no
// need for the paper's artificial pressure term.
#include <algorithm>
#include <cmath>

#include "anyphys/fields/particles.hpp"

namespace anyphys {

namespace {

// Lattice counts along one axis of the box, and where the first particle sits: the lattice is
// centred in the box, particles half a spacing in from its faces.
struct Axis {
    int count;
    double first;
};
Axis latticeAxis(double lo, double hi, double s) {
    const int n = std::max(1, static_cast<int>(std::floor((hi - lo) / s + 1e-9)));
    return {n, lo + 0.5 * (hi - lo - n * s) + 0.5 * s};
}

}  // namespace

FluidSystem::FluidSystem(const FluidDef& def, bool planar) : def_(def), planar_(planar) {
    const double s = def.spacing;
    h_ = 2.0 * s;
    const Axis ax = latticeAxis(def.boxMin.x(), def.boxMax.x(), s);
    const Axis ay = latticeAxis(def.boxMin.y(), def.boxMax.y(), s);
    const Axis az = planar ? Axis{1, 0.0} : latticeAxis(def.boxMin.z(), def.boxMax.z(), s);
    for (int k = 0; k < az.count; ++k)
        for (int j = 0; j < ay.count; ++j)
            for (int i = 0; i < ax.count; ++i) x_.emplace_back(ax.first + i * s, ay.first + j * s, az.first + k * s);
    v_.assign(x_.size(), Vec3::Zero());
    // A planar fluid is a slab as deep as its box along Z: its particles carry that depth's mass.
    mass_ = def.density * s * s * (planar ? def.boxMax.z() - def.boxMin.z() : s);
    // Normalise the kernel on the rest lattice, so a particle inside it has exactly the rest
    // density (the continuous normalisation is off by a few per cent at two spacings).
    double sum = 0.0;
    const int reach = 2;
    for (int k = planar ? 0 : -reach; k <= (planar ? 0 : reach); ++k)
        for (int j = -reach; j <= reach; ++j)
            for (int i = -reach; i <= reach; ++i) {
                const double r2 = s * s * (i * i + j * j + k * k);
                if (r2 < h_ * h_) sum += std::pow(1.0 - std::sqrt(r2) / h_, 3);
            }
    kernelScale_ = def.density / (mass_ * sum);
    // The lattice beyond a wall: layers s / 2, 3 s / 2, ... past it (mirroring the fluid's own
    // first layer half a spacing in front of it), each a full lattice sideways.
    const int samples = 32;
    wallTable_.resize(samples + 1);
    for (int k = 0; k <= samples; ++k) {
        const double d = h_ * k / samples;
        double rho = 0.0;
        for (int layer = 0; d + (layer + 0.5) * s < h_; ++layer) {
            const double depth = d + (layer + 0.5) * s;
            for (int j = -reach; j <= reach; ++j)
                for (int i = planar ? 0 : -reach; i <= (planar ? 0 : reach); ++i)
                    rho += mass_ * kernel(depth * depth + s * s * (i * i + j * j));
        }
        wallTable_[k] = rho;
    }
}

double FluidSystem::wallDensity(double d, double& slope) const {
    const int samples = static_cast<int>(wallTable_.size()) - 1;
    const double x = std::clamp(d, 0.0, h_) / h_ * samples;
    const int k = std::min(samples - 1, static_cast<int>(x));
    slope = (wallTable_[k + 1] - wallTable_[k]) * samples / h_;
    if (d >= h_) slope = 0.0;
    return wallTable_[k] + (x - k) * (wallTable_[k + 1] - wallTable_[k]);
}

void FluidSystem::findWalls(const std::vector<ParticleCollider>& colliders) {
    walls_.assign(p_.size(), Wall{});
    const Vec3 margin = Vec3::Constant(h_);
    for (std::size_t c = 0; c < colliders.size(); ++c) {
        const ParticleCollider& col = colliders[c];
        for (std::size_t i = 0; i < p_.size(); ++i) {
            const Vec3& p = p_[i];
            if ((p.array() < (col.boundsMin - margin).array()).any() || (p.array() > (col.boundsMax + margin).array()).any()) continue;
            Vec3 push = colliderPush(col, x_[i], p, h_);  // (h - d) along the outward normal, when d < h
            if (planar_) push.z() = 0.0;
            const double depth = push.norm();
            if (depth <= 0.0) continue;
            const double d = h_ - depth;
            if (walls_[i].collider >= 0 && d >= walls_[i].distance) continue;
            walls_[i] = {static_cast<std::int32_t>(c), d, push / depth, p, Vec3::Zero()};
        }
    }
}

double FluidSystem::kernel(double r2) const {
    if (r2 >= h_ * h_) return 0.0;
    const double q = 1.0 - std::sqrt(r2) / h_;
    return kernelScale_ * q * q * q;
}

double FluidSystem::kernelSlope(double r) const {
    if (r >= h_) return 0.0;
    const double q = 1.0 - r / h_;
    return -3.0 * kernelScale_ * q * q / h_;
}

void FluidSystem::step(double dt, const ParticleEnvironment& env, std::vector<ParticleCollider>& colliders) {
    if (x_.empty()) return;
    // Substeps: a particle moves at most half a spacing per substep (the grid and the
    // constraints assume small moves), and at least two per step at game rates.
    double fastest = 0.0;
    for (const Vec3& v : v_) fastest = std::max(fastest, v.squaredNorm());
    fastest = std::sqrt(fastest) + env.gravity.norm() * dt;
    lastSubsteps_ = std::clamp(static_cast<int>(std::ceil(fastest * dt / (0.5 * def_.spacing))), 2, 16);
    const double h = dt / lastSubsteps_;
    for (int k = 0; k < lastSubsteps_; ++k) substep(h, env, colliders);
}

void FluidSystem::substep(double dt, const ParticleEnvironment& env, std::vector<ParticleCollider>& colliders) {
    const std::size_t n = x_.size();
    p_.resize(n);
    pushes_.assign(n, Push{});
    for (std::size_t i = 0; i < n; ++i) {
        v_[i] += dt * env.gravity;
        p_[i] = x_[i] + dt * v_[i];
    }
    collide(colliders, dt);
    findWalls(colliders);
    grid_.build(p_, h_);
    neighbourStart_.assign(n + 1, 0);
    neighbourList_.clear();
    for (std::size_t i = 0; i < n; ++i) {
        grid_.neighbours(p_, i, h_, neighbourList_);
        neighbourStart_[i + 1] = static_cast<std::uint32_t>(neighbourList_.size());
    }
    lambda_.resize(n);
    density_.resize(n);
    dp_.resize(n);
    const double massOverRho = mass_ / def_.density;
    // Regularisation of the constraint's Newton step (the paper's epsilon), relative to the rest
    // lattice's gradient norm so it does not depend on units: softens it by 0.1 %.
    const double restGradient = [&] {
        const double g = kernelSlope(def_.spacing) * massOverRho;
        return (planar_ ? 4.0 : 6.0) * g * g;
    }();
    const double epsilon = 1e-3 * restGradient;
    for (int it = 0; it < kIterations; ++it) {
        for (std::size_t i = 0; i < n; ++i) {
            double rho = mass_ * kernel(0.0);
            Vec3 gradI = Vec3::Zero();
            double sumGrad2 = 0.0;
            for (std::uint32_t k = neighbourStart_[i]; k < neighbourStart_[i + 1]; ++k) {
                const std::uint32_t j = neighbourList_[k];
                const Vec3 d = p_[i] - p_[j];
                const double r2 = d.squaredNorm();
                if (r2 >= h_ * h_) continue;
                const double r = std::sqrt(r2);
                const double q = 1.0 - r / h_;
                rho += mass_ * kernelScale_ * q * q * q;
                if (r > 0.0) {
                    const Vec3 g = massOverRho * kernelSlope(r) / r * d;
                    gradI += g;
                    sumGrad2 += g.squaredNorm();
                }
            }
            Wall& wall = walls_[i];
            if (wall.collider >= 0) {
                double slope = 0.0;
                rho += wallDensity(wall.distance + wall.normal.dot(p_[i] - wall.at), slope);
                wall.gradient = slope / def_.density * wall.normal;
                gradI += wall.gradient;
            }
            density_[i] = rho;
            const double c = std::max(0.0, rho / def_.density - 1.0);
            lambda_[i] = -c / (sumGrad2 + gradI.squaredNorm() + epsilon);
        }
        for (std::size_t i = 0; i < n; ++i) {
            Vec3 move = Vec3::Zero();
            for (std::uint32_t k = neighbourStart_[i]; k < neighbourStart_[i + 1]; ++k) {
                const std::uint32_t j = neighbourList_[k];
                const Vec3 d = p_[i] - p_[j];
                const double r = d.norm();
                if (r <= 0.0 || r >= h_) continue;
                move += (lambda_[i] + lambda_[j]) * massOverRho * kernelSlope(r) / r * d;
            }
            const Wall& wall = walls_[i];
            if (wall.collider >= 0 && lambda_[i] != 0.0) {
                // The wall's share: the particle moves off it, the body takes the reaction.
                Vec3 off = lambda_[i] * wall.gradient;
                if (planar_) off.z() = 0.0;
                move += off;
                recordPush(i, wall.collider, colliders[static_cast<std::size_t>(wall.collider)].dynamic, off, colliders, dt);
            }
            dp_[i] = move;
        }
        for (std::size_t i = 0; i < n; ++i) p_[i] += dp_[i];
        if (planar_)
            for (Vec3& p : p_) p.z() = 0.0;
        collide(colliders, dt);
    }
    for (std::size_t i = 0; i < n; ++i) v_[i] = (p_[i] - x_[i]) / dt;
    settlePushes(colliders, dt, env.gravity.norm());
    // Viscosity: explicit diffusion of velocity, nu laplacian(v) with Brookshaw's SPH Laplacian in
    // a pairwise symmetric form (each pair exchanges equal and opposite momentum), one rate for
    // every particle, capped so a large viscosity cannot overshoot (it then acts as full smoothing).
    const double nu = def_.viscosity / def_.density;
    if (nu > 0.0) {
        dp_.assign(n, Vec3::Zero());  // reused: the velocity change per unit rate
        double heaviest = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            Vec3 lap = Vec3::Zero();
            double weight = 0.0;
            for (std::uint32_t k = neighbourStart_[i]; k < neighbourStart_[i + 1]; ++k) {
                const std::uint32_t j = neighbourList_[k];
                const Vec3 d = p_[i] - p_[j];
                const double r = d.norm();
                if (r >= h_) continue;
                const double w = -4.0 * mass_ / (density_[i] + density_[j]) * kernelSlope(r) * r / (r * r + 0.01 * h_ * h_);
                lap += w * (v_[j] - v_[i]);
                weight += w;
            }
            dp_[i] = lap;
            heaviest = std::max(heaviest, weight);
        }
        const double rate = std::min(nu * dt, heaviest > 0.0 ? 0.5 / heaviest : 0.0);
        for (std::size_t i = 0; i < n; ++i) v_[i] += rate * dp_[i];
    }
    x_.swap(p_);
}

void FluidSystem::collide(std::vector<ParticleCollider>& colliders, double dt) {
    const double radius = particleRadius();
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        const ParticleCollider& c = colliders[k];
        const Vec3 margin = Vec3::Constant(radius);
        for (std::size_t i = 0; i < p_.size(); ++i) {
            const Vec3 p = p_[i];
            // The box of the particle's path this substep: a fast one may have crossed a thin shape.
            const Vec3 lo = p.cwiseMin(x_[i]), hi = p.cwiseMax(x_[i]);
            if ((hi.array() < (c.boundsMin - margin).array()).any() || (lo.array() > (c.boundsMax + margin).array()).any()) continue;
            Vec3 push = colliderPush(c, x_[i], p, radius);
            if (planar_) push.z() = 0.0;
            if (push.isZero(0)) continue;
            p_[i] += push;
            recordPush(i, static_cast<std::int32_t>(k), c.dynamic, push, colliders, dt);
        }
    }
}

void FluidSystem::recordPush(std::size_t i, std::int32_t collider, bool dynamic, const Vec3& push,
                             std::vector<ParticleCollider>& colliders, double dt) {
    Push& p = pushes_[i];
    p.total += push;
    if (dynamic) {
        if (p.dynamicCollider != collider) p.byDynamic = Vec3::Zero();  // the last dynamic shape counts
        p.dynamicCollider = collider;
        p.byDynamic += push;
    } else {  // static geometry does not move: its share is only reported, push by push
        ParticleCollider& c = colliders[static_cast<std::size_t>(collider)];
        const Vec3 j = -mass_ / dt * push;
        c.impulse += j;
        c.angularImpulse += (p_[i] - c.pose.position).cross(j);
    }
}

void FluidSystem::settlePushes(std::vector<ParticleCollider>& colliders, double dt, double gravity) {
    // What the shapes did to each particle this substep becomes impulses on them, from the
    // particle's net push (its momentum changed by m push / dt), so the shapes take exactly the
    // opposite. A dynamic shape is credited with its own push as far as the net push goes along
    // it: a particle squeezed between it and a static wall, pushed back and forth by the two in
    // every iteration, moved little and gives it little (per push it would collect one kick per
    // iteration and be flung off); the static shape, which does not move, takes the rest.
    // A push also may give a particle at most sqrt(g h) (the fluid's wave speed at the smoothing
    // length) beyond the dynamic shape's own speed: a body shoved deep into the fluid by its
    // contacts resolves that overlap in position, not by flinging the particles (and itself).
    const double cap = std::sqrt(gravity * h_);
    const double toImpulse = mass_ / dt;
    for (std::size_t i = 0; i < pushes_.size(); ++i) {
        Push& push = pushes_[i];
        if (push.dynamicCollider < 0) {
            push = Push{};
            continue;
        }
        Vec3 dynamicPart = Vec3::Zero();
        if (push.dynamicCollider >= 0) {
            ParticleCollider& c = colliders[static_cast<std::size_t>(push.dynamicCollider)];
            const double own = push.byDynamic.squaredNorm();
            if (own > 0.0) dynamicPart = std::clamp(push.total.dot(push.byDynamic) / own, 0.0, 1.0) * push.byDynamic;
            const Vec3 arm = p_[i] - c.pose.position;
            const double shapeSpeed = (c.linearVelocity + c.angularVelocity.cross(arm)).norm();
            const double speed = dynamicPart.norm() / dt;
            if (speed > shapeSpeed + cap) {
                const Vec3 excess = dynamicPart * (1.0 - (shapeSpeed + cap) / speed);
                v_[i] -= excess / dt;
                push.total -= excess;
                dynamicPart -= excess;
            }
            const Vec3 j = -toImpulse * dynamicPart;
            c.impulse += j;
            c.angularImpulse += arm.cross(j);
        }
        push = Push{};
    }
}

}  // namespace anyphys

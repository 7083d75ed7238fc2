// A position-based cloth (XPBD: Macklin, Mueller and Chentanez 2016): nodes on a lattice joined by
// distance constraints whose compliance is the inverse of a spring stiffness, so the sheet's
// stiffness is in N/m and not tied to the iteration count. Structural links along U and V carry
// the stretch stiffness, diagonals resist shear, links across two cells resist bending.
#include <algorithm>
#include <cmath>

#include "anyphys/fields/particles.hpp"

namespace anyphys {

ClothSystem::ClothSystem(const ClothDef& def, bool planar) : def_(def), planar_(planar) {
    const int nu = def.resolution[0], nv = def.resolution[1];
    const double du = restU(), dv = restV();
    const std::size_t count = static_cast<std::size_t>(nu + 1) * (nv + 1);
    x_.resize(count);
    v_.assign(count, Vec3::Zero());
    mass_.assign(count, 0.0);
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) x_[node(i, j)] = def.corner + i * du * def.axisU + j * dv * def.axisV;
    // Each cell's mass goes to its four corners.
    const double quarter = 0.25 * def.areaDensity * du * dv;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            for (int c = 0; c < 4; ++c) mass_[node(i + (c & 1), j + (c >> 1))] += quarter;
    invMass_.resize(count);
    for (std::size_t k = 0; k < count; ++k) invMass_[k] = 1.0 / mass_[k];
    for (const auto& p : def.pinned) invMass_[node(p[0], p[1])] = 0.0;
    // Spring stiffness of a link: the sheet's stiffness times the width the link stands for, over
    // its length (k = E t w / l with E t = stiffness).
    const double kU = def.stiffness * dv / du, kV = def.stiffness * du / dv;
    const double kShear = 0.5 * def.stiffness * (du * dv) / (du * du + dv * dv);
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            if (i < nu) addLink(node(i, j), node(i + 1, j), kU);
            if (j < nv) addLink(node(i, j), node(i, j + 1), kV);
            if (i < nu && j < nv) {
                addLink(node(i, j), node(i + 1, j + 1), kShear);
                addLink(node(i + 1, j), node(i, j + 1), kShear);
            }
            if (def.bending > 0.0) {
                if (i + 2 <= nu) addLink(node(i, j), node(i + 2, j), def.bending * kU / 2);
                if (j + 2 <= nv) addLink(node(i, j), node(i, j + 2), def.bending * kV / 2);
            }
        }
}

void ClothSystem::addLink(std::size_t a, std::size_t b, double stiffness) {
    links_.push_back({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), (x_[a] - x_[b]).norm(), 1.0 / stiffness});
}

double ClothSystem::elasticEnergy() const {
    double e = 0.0;
    for (const Link& l : links_) {
        const double stretch = (x_[l.a] - x_[l.b]).norm() - l.rest;
        e += 0.5 * stretch * stretch / l.compliance;
    }
    return e;
}

void ClothSystem::applyAir(double dt, const ParticleEnvironment& env) {
    // Drag and wind push each triangle along its normal: F = -0.5 rho Cd A (u . n) |u . n| n, u the
    // triangle's velocity relative to the air, Cd = 1 (a flat plate face on is 1.1 to 1.3; a
    // sheet that flutters less). A third of it on each corner.
    if (!env.fields || planar_) return;  // in a planar world the sheet's normal is out of the plane
    const int nu = def_.resolution[0], nv = def_.resolution[1];
    for (const FieldDef& f : *env.fields) {
        if (f.type != FieldType::Drag && f.type != FieldType::Wind) continue;
        const Vec3 air = f.type == FieldType::Wind ? f.velocity : Vec3::Zero();
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                const std::size_t c[4] = {node(i, j), node(i + 1, j), node(i, j + 1), node(i + 1, j + 1)};
                for (const auto& t : {std::array<std::size_t, 3>{c[0], c[1], c[2]}, std::array<std::size_t, 3>{c[1], c[3], c[2]}}) {
                    const Vec3 twice = (x_[t[1]] - x_[t[0]]).cross(x_[t[2]] - x_[t[0]]);
                    const double area2 = twice.norm();
                    if (area2 <= 0.0) continue;
                    const Vec3 n = twice / area2;
                    const Vec3 u = (v_[t[0]] + v_[t[1]] + v_[t[2]]) / 3.0 - air;
                    const double un = u.dot(n);
                    const Vec3 force = -0.5 * f.airDensity * (0.5 * area2) * un * std::abs(un) * n;
                    for (std::size_t k : t) v_[k] += dt * invMass_[k] * force / 3.0;
                }
            }
    }
}

void ClothSystem::step(double dt, const ParticleEnvironment& env, std::vector<ParticleCollider>& colliders) {
    const double h = dt / kSubsteps;
    const std::size_t n = x_.size();
    std::vector<double> lambda(links_.size());
    p_.resize(n);
    const double decay = std::max(0.0, 1.0 - def_.damping * h);
    for (int s = 0; s < kSubsteps; ++s) {
        applyAir(h, env);
        for (std::size_t k = 0; k < n; ++k) {
            if (invMass_[k] > 0.0) v_[k] = decay * (v_[k] + h * env.gravity);
            p_[k] = x_[k] + h * v_[k];
        }
        std::fill(lambda.begin(), lambda.end(), 0.0);
        for (int it = 0; it < kIterations; ++it) {
            for (std::size_t l = 0; l < links_.size(); ++l) {
                const Link& link = links_[l];
                const double wa = invMass_[link.a], wb = invMass_[link.b];
                if (wa + wb <= 0.0) continue;
                const Vec3 d = p_[link.a] - p_[link.b];
                const double len = d.norm();
                if (len <= 0.0) continue;
                const double alpha = link.compliance / (h * h);
                const double dl = (-(len - link.rest) - alpha * lambda[l]) / (wa + wb + alpha);
                lambda[l] += dl;
                const Vec3 move = dl * d / len;
                p_[link.a] += wa * move;
                p_[link.b] -= wb * move;
            }
            // Nodes out of rigid shapes, the shapes taking the reaction.
            for (ParticleCollider& c : colliders) {
                const Vec3 margin = Vec3::Constant(def_.thickness);
                for (std::size_t k = 0; k < n; ++k) {
                    if (invMass_[k] <= 0.0) continue;
                    const Vec3 p = p_[k];
                    // The box of the node's path this substep: a fast one may have crossed a thin shape.
                    const Vec3 lo = p.cwiseMin(x_[k]), hi = p.cwiseMax(x_[k]);
                    if ((hi.array() < (c.boundsMin - margin).array()).any() || (lo.array() > (c.boundsMax + margin).array()).any()) continue;
                    Vec3 push = colliderPush(c, x_[k], p, def_.thickness);
                    if (planar_) push.z() = 0.0;
                    if (push.isZero(0)) continue;
                    p_[k] += push;
                    const Vec3 j = -mass_[k] / h * push;
                    c.impulse += j;
                    c.angularImpulse += (p - c.pose.position).cross(j);
                }
            }
        }
        for (std::size_t k = 0; k < n; ++k) {
            if (planar_) p_[k].z() = 0.0;
            v_[k] = (p_[k] - x_[k]) / h;
        }
        x_.swap(p_);
    }
}

}  // namespace anyphys

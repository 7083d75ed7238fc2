#pragma once
// Particle systems above the backends: a position-based fluid (Macklin and Mueller, "Position
// Based Fluids", SIGGRAPH 2013) and a position-based cloth, each colliding both ways with rigid
// bodies. The solvers see rigid bodies only as `ParticleCollider`s (shapes, pose, velocity,
// whether they move) and report the impulse each took from the particles; the world applies it
// through the backend. Pure code: no backend, no World.
#include <cmath>
#include <array>
#include <cstdint>
#include <vector>

#include "anyphys/fields/field_def.hpp"
#include "anyphys/fields/field_forces.hpp"
#include "anyphys/fields/particle_defs.hpp"

namespace anyphys {

/// A rigid body as the particle solvers see it, at its pose after the rigid step.
struct ParticleCollider {
    const FieldBody* body = nullptr;  ///< shapes in the frame of `pose`
    Transform pose;                   ///< the peer frame (centre of mass, principal axes)
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    bool dynamic = false;             ///< takes the reaction (static and kinematic bodies do not)
    Vec3 boundsMin = Vec3::Zero();    ///< world box around every shape (filled by colliderBounds)
    Vec3 boundsMax = Vec3::Zero();
    // Out: what the particles did to it over the step (dynamic or not, for measurements).
    Vec3 impulse = Vec3::Zero();      ///< N s, world frame, at the centre of mass
    Vec3 angularImpulse = Vec3::Zero();  ///< N m s about the centre of mass
};

/// Fills the collider's world bounds from its shapes and pose.
void colliderBounds(ParticleCollider& collider);

/// The deepest contact of a sphere of `radius` at `point` with the collider's shapes: the push
/// (along the outward normal, length the penetration) that separates them, or zero. `from` is
/// where the particle started the substep: a triangle mesh has no inside, so the side of each
/// triangle it started on is the side it is kept on (a path through a triangle is moved back).
Vec3 colliderPush(const ParticleCollider& collider, const Vec3& from, const Vec3& point, double radius);

/// A uniform grid over space with cells of `cell` metres, stored by hashing the cell coordinates
/// into a table (so particles may spread anywhere): counting sort by bucket, neighbours by the
/// 27 (planar: 9) cells around a point. Rebuilt once per step; reuses its buffers.
class ParticleGrid {
public:
    void build(const std::vector<Vec3>& points, double cell);
    /// Calls f(j) for every point within the cells overlapping the box [lo, hi] (a superset of
    /// those in it; bucket collisions may add others, so callers check distances).
    template <class F>
    void forEachInBox(const Vec3& lo, const Vec3& hi, F&& f) const;
    /// Indices of the points within `radius` (<= the cell size) of point i, itself excluded.
    void neighbours(const std::vector<Vec3>& points, std::size_t i, double radius, std::vector<std::uint32_t>& out) const;

private:
    std::size_t bucketOf(long long x, long long y, long long z) const;
    double cell_ = 1.0;
    std::size_t mask_ = 0;
    std::vector<std::uint32_t> start_;  // bucket -> first index in order_ (size buckets + 1)
    std::vector<std::uint32_t> order_;  // point indices sorted by bucket
    mutable std::vector<std::uint32_t> seen_;  // the query that last visited a bucket (hashed cells may repeat)
    mutable std::uint32_t query_ = 0;
    Vec3 lo_ = Vec3::Zero(), hi_ = Vec3::Zero();  // bounds of the points
    std::vector<std::uint32_t> scratch_;
};

/// Gravity, the world's force fields on particles (drag and wind act on cloth), and whether the
/// world is planar (particles stay at z = 0, and a fluid's lattice is two-dimensional).
struct ParticleEnvironment {
    Vec3 gravity = Vec3(0, -9.81, 0);
    const std::vector<FieldDef>* fields = nullptr;
    bool planar = false;
};

/// A position-based fluid. Particles have radius spacing / 2 and mass density spacing^3 (planar:
/// density spacing^2 times the box's depth along Z, the slab it stands for).
class FluidSystem {
public:
    explicit FluidSystem(const FluidDef& def, bool planar);
    /// Advances the fluid by dt with the rigid bodies at their poses after the rigid step, adding
    /// into each collider the impulse it took (equal and opposite to the particles' change).
    void step(double dt, const ParticleEnvironment& env, std::vector<ParticleCollider>& colliders);

    const FluidDef& def() const { return def_; }
    const std::vector<Vec3>& positions() const { return x_; }
    const std::vector<Vec3>& velocities() const { return v_; }
    double particleMass() const { return mass_; }
    double particleRadius() const { return 0.5 * def_.spacing; }
    double smoothingLength() const { return h_; }
    /// Iterations of the density constraint per substep and the substeps of the last step.
    int iterations() const { return kIterations; }
    int lastSubsteps() const { return lastSubsteps_; }

    static constexpr int kIterations = 4;

private:
    void substep(double dt, const ParticleEnvironment& env, std::vector<ParticleCollider>& colliders);
    double kernel(double r2) const;       // W(r), normalised on the rest lattice
    double kernelSlope(double r) const;   // dW/dr
    void collide(std::vector<ParticleCollider>& colliders, double dt);
    void findWalls(const std::vector<ParticleCollider>& colliders);
    void recordPush(std::size_t i, std::int32_t collider, bool dynamic, const Vec3& push,
                    std::vector<ParticleCollider>& colliders, double dt);
    void settlePushes(std::vector<ParticleCollider>& colliders, double dt, double gravity);
    double wallDensity(double d, double& slope) const;  // the rest lattice beyond a wall d away

    // A rigid surface within the smoothing length of a particle stands in for the fluid missing
    // beyond it: the density a rest lattice continuing past the wall would add (wallTable_, by
    // distance), so particles at a wall feel full pressure (otherwise a wall takes too little).
    struct Wall {
        std::int32_t collider = -1;  // nearest collider within h, or -1
        double distance = 0.0;       // from its surface, at `at`
        Vec3 normal = Vec3::Zero();  // out of it
        Vec3 at = Vec3::Zero();
        Vec3 gradient = Vec3::Zero();  // of the particle's constraint by the wall term
    };

    FluidDef def_;
    bool planar_ = false;
    double h_ = 0.1;         // smoothing length (2 spacings)
    double mass_ = 1.0;      // kg per particle
    double kernelScale_ = 1.0;
    int lastSubsteps_ = 1;
    std::vector<Vec3> x_, v_, p_, dp_;
    std::vector<double> lambda_, density_;
    std::vector<std::uint32_t> neighbourStart_, neighbourList_;
    std::vector<std::uint32_t> scratch_;
    std::vector<Wall> walls_;
    struct Push {  // what the shapes pushed a particle by this substep
        Vec3 total = Vec3::Zero();
        Vec3 byDynamic = Vec3::Zero();      // by the last dynamic shape that pushed it
        std::int32_t dynamicCollider = -1;
    };
    std::vector<Push> pushes_;
    std::vector<double> wallTable_;  // wall density at distances 0, h / n, ..., h
    ParticleGrid grid_;
};

/// A position-based cloth (XPBD distance constraints: stretch and shear along the lattice, bending
/// across two cells), its nodes colliding with rigid shapes both ways; drag and wind fields push
/// its triangles along their normals.
class ClothSystem {
public:
    explicit ClothSystem(const ClothDef& def, bool planar);
    void step(double dt, const ParticleEnvironment& env, std::vector<ParticleCollider>& colliders);

    const ClothDef& def() const { return def_; }
    const std::vector<Vec3>& positions() const { return x_; }
    const std::vector<Vec3>& velocities() const { return v_; }
    /// Mass of node k (kg; pinned nodes report their share though they do not move).
    double nodeMass(std::size_t k) const { return mass_[k]; }
    std::size_t node(int i, int j) const { return static_cast<std::size_t>(j) * (def_.resolution[0] + 1) + i; }
    /// Rest length of the structural edges along U and V.
    double restU() const { return def_.size[0] / def_.resolution[0]; }
    double restV() const { return def_.size[1] / def_.resolution[1]; }
    /// Elastic energy stored in the constraints (J), for energy checks.
    double elasticEnergy() const;

    static constexpr int kSubsteps = 8;
    static constexpr int kIterations = 4;

private:
    struct Link {
        std::uint32_t a, b;
        double rest, compliance;  // compliance = 1 / spring stiffness (m/N)
    };
    void addLink(std::size_t a, std::size_t b, double stiffness);
    void applyAir(double dt, const ParticleEnvironment& env);

    ClothDef def_;
    bool planar_ = false;
    std::vector<Vec3> x_, v_, p_;
    std::vector<double> mass_, invMass_;
    std::vector<Link> links_;
};

template <class F>
void ParticleGrid::forEachInBox(const Vec3& lo, const Vec3& hi, F&& f) const {
    if (order_.empty()) return;
    const Vec3 a = lo.cwiseMax(lo_), b = hi.cwiseMin(hi_);
    if (a.x() > b.x() || a.y() > b.y() || a.z() > b.z()) return;
    const long long x0 = static_cast<long long>(std::floor(a.x() / cell_)), x1 = static_cast<long long>(std::floor(b.x() / cell_));
    const long long y0 = static_cast<long long>(std::floor(a.y() / cell_)), y1 = static_cast<long long>(std::floor(b.y() / cell_));
    const long long z0 = static_cast<long long>(std::floor(a.z() / cell_)), z1 = static_cast<long long>(std::floor(b.z() / cell_));
    const double cells = double(x1 - x0 + 1) * double(y1 - y0 + 1) * double(z1 - z0 + 1);
    ++query_;
    if (cells > double(order_.size())) {  // more cells than points: every point, once
        for (std::uint32_t k : order_) f(k);
        return;
    }
    for (long long z = z0; z <= z1; ++z)
        for (long long y = y0; y <= y1; ++y)
            for (long long x = x0; x <= x1; ++x) {
                const std::size_t bucket = bucketOf(x, y, z);
                if (seen_[bucket] == query_) continue;  // a hashed cell already visited
                seen_[bucket] = query_;
                for (std::uint32_t k = start_[bucket]; k < start_[bucket + 1]; ++k) f(order_[k]);
            }
}

}  // namespace anyphys

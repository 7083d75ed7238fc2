#pragma once
// The contact solver. Two methods, selected by WorldSettings::solver:
//  - soft step (default, after Box2D v3): per substep integrate velocities, warm start, solve
//    soft contacts with bias, integrate positions, relax without bias; restitution once after
//    the substeps. Soft contacts act as stiff damped springs on overlap, so deep overlaps are
//    resolved smoothly rather than with explosive impulses.
//  - projected Gauss-Seidel (sequential impulses): per substep integrate velocities, warm
//    start, `iterations` passes with Baumgarte position correction and restitution folded into
//    the velocity target, integrate positions.
// Both: Coulomb friction on two tangents clamped to the friction circle; speculative points
// (separation > 0) only stop the approach at the surface.
#include <vector>

#include "contacts.hpp"
#include "pipeline.hpp"

namespace anyphys::native {

class NativeWorld;

class ContactSolver {
public:
    /// Collects the constraints of this step (non-trigger contacts with points and an awake
    /// dynamic body) and marks their dynamic bodies `constrained`.
    void prepare(NativeWorld& world);
    bool empty() const { return constraints_.empty(); }
    /// No constraints this step (nothing awake).
    void clear() { constraints_.clear(); }
    /// Advances the constrained bodies over the whole step.
    void solve(NativeWorld& world, const StepInfo& step);

private:
    struct Constraint {
        Contact* contact;
        ContactManifold* manifold;
        std::uint32_t bodyA, bodyB;
    };
    void prepareConstraint(NativeWorld& world, Constraint& c, double dt);
    std::vector<Constraint> constraints_;
    std::vector<std::uint32_t> bodies_;  // constrained dynamic and kinematic bodies
};

}  // namespace anyphys::native

#pragma once
// Mass and inertia regularisation for articulated assemblies. An iterative joint solver (every
// backend's) converges slowly when a joint links bodies of very different mass, or when a light
// parent carries children that resist turning more than it does: a ragdoll's hand pulls its
// forearm apart, a chain with a heavy end stretches. Games fix the model rather than the
// solver (Jolt's ragdoll "stabilize" step does this): bound the mass ratio across each joint
// and give each parent at least its children's inertia. Applied to the scene description, so it
// is the same on every backend.
#include <string>

#include "anyphys/containers/scene.hpp"

namespace anyphys {

struct MassRegularization {
    /// Largest allowed ratio of the heavier to the lighter body across any joint between two
    /// dynamic bodies, >= 1; 0 (default) leaves masses alone. Lighter bodies are raised, then
    /// each jointed group is scaled back to its total mass, so the assembly weighs what it did.
    double maxMassRatio = 0.0;
    /// Raise each principal moment of a joint's body A (the parent) to at least the largest
    /// principal moment of its body B (the child), repeated up the tree. Default false.
    bool raiseParentInertia = false;

    bool enabled() const { return maxMassRatio > 0.0 || raiseParentInertia; }
};

/// Checks the options; throws anyphys::Error naming `path` + the field otherwise.
void validate(const MassRegularization& options, const std::string& path);

/// Applies `options` to the bodies joined by `scene`'s joints: their masses (and explicit
/// inertias, scaled with them) and, for raiseParentInertia, explicit inertias set where raised.
/// Bodies are resolved as the world would: mass, else density (the body's, its material's, or
/// 1000 kg/m^3) times volume. Throws anyphys::Error naming the body if a jointed body's mass or
/// inertia cannot be known here (a convex hull or compound body without an explicit mass and
/// inertia); the scene is unchanged then.
void regularizeMasses(Scene& scene, const MassRegularization& options);

}  // namespace anyphys

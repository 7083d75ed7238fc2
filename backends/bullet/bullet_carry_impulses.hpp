#pragma once
// Warm starting across a manifold that an algorithm refilled from scratch.
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

namespace anyphys::bullet {

/// Gives each point of `manifold` the accumulated impulses of the old point at the same place on
/// either body (within the breaking threshold), so resting and sliding contact warm-start as
/// before the refill (bullet_box_box.cpp).
void carryImpulses(btPersistentManifold& manifold, const btManifoldPoint* old, int oldCount);

}  // namespace anyphys::bullet

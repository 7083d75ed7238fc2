#pragma once
// The AABB of one primitive shape at a pose, computed by the layer from the ShapeDef: debug
// drawing shows the same bounds on every backend (engines pad their broad-phase boxes each in
// their own way), and body creation measures a body's reach about its axes with it. Pure
// function: unit-tested without a backend.
#include <optional>

#include "anyphys/defs.hpp"
#include "anyphys/math.hpp"

namespace anyphys {

struct Aabb {
    Vec3 min = Vec3::Zero();
    Vec3 max = Vec3::Zero();
};

/// The tightest axis-aligned box holding `shape` (a primitive: not a compound) placed at `pose`;
/// none for a plane (unbounded) or a shape with no points.
std::optional<Aabb> shapeBounds(const ShapeDef& shape, const Transform& pose);

}  // namespace anyphys

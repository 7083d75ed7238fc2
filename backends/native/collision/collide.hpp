#pragma once
// Narrow phase: contact manifolds between two shapes.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "collision/shape.hpp"

namespace anyphys::native {

/// What collide() remembers about one pair between calls, to skip work when the pair moved
/// little: the axis that last separated the shapes by more than the speculative distance (a pair
/// still apart along it costs one axis test), or the reference face of the last contact (hulls:
/// tried first, it lets the face search skip faces that cannot beat it). The caller keeps one per
/// shape pair (zero-initialised: empty), passes it on every call for that pair in the same
/// argument order, and may reset it at any time. Results never depend on it: a separating axis
/// proves what the full test would find (no points), and a remembered face only orders the
/// search. Used by box-box, box-hull and hull-hull pairs; the other pairs leave it alone.
struct CollideCache {
    enum Axis : std::uint8_t { None, FaceOfA, FaceOfB, EdgePair };
    Axis axis = None;         // in collide()'s internal order of the two shapes (see collide.cpp)
    bool separating = false;  // the axis separated them; else it is the last contact's reference face
    std::int32_t indexA = 0;  // face of a, or a's edge of the edge pair (a box: its axis)
    std::int32_t indexB = 0;  // face of b, or b's edge of the edge pair (a box: its axis)
};
static_assert(std::is_trivially_copyable_v<CollideCache>);

/// Appends the manifolds of shapes a and b at world poses xfA and xfB (shape frames, i.e.
/// shapeWorldPose(...)): one for a pair of convex shapes, one per touched triangle against a
/// mesh. Only points with separation < speculativeDistance are produced; a manifold without
/// points is not appended. Normals point from a to b whatever order the routine used inside.
/// Planes and meshes are static: a pair of two static shapes never reaches this function.
/// Allocates nothing once `out` and the calling thread's scratch buffers (grown by the largest
/// hull or mesh query met) have their capacity; several threads may call it at once.
void collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB, double speculativeDistance,
             std::vector<Manifold>& out, CollideCache* cache = nullptr);

}  // namespace anyphys::native

#pragma once
// Feature ids of contact points. An id is a hash of the features that produced the point (which
// face is the reference, which incident face, which incident vertex or which incident edge
// clipped by which side plane, ...). The same features give the same id on the next step, so
// the solver can match the point and warm start it; different features give different ids.
#include <cstdint>

namespace anyphys::native::feature {

/// What produced a point; the first word of every id so different routines never collide.
enum class Kind : std::uint32_t {
    Round = 1,        // sphere / capsule pairs
    FaceOfA = 2,      // reference face on shape a, incident polygon of b clipped to it
    FaceOfB = 3,      // reference face on shape b
    EdgeEdge = 4,     // closest points of an edge of a and an edge of b
    Closest = 5,      // closest points of a round shape and a polytope (distance routine)
    Plane = 6,        // a vertex or segment end against a plane
    BoxRegion = 7,    // sphere against box: which of the 27 Voronoi regions
};

/// Murmur3's 32-bit finaliser: every input bit affects every output bit.
constexpr std::uint32_t mix(std::uint32_t h) {
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

constexpr std::uint32_t combine(std::uint32_t seed, std::uint32_t value) {
    return mix(seed ^ (value + 0x9e3779b9u + (seed << 6) + (seed >> 2)));
}

/// The id of a point made by `kind` from the given feature numbers.
template <class... T>
constexpr std::uint32_t id(Kind kind, T... parts) {
    std::uint32_t h = mix(static_cast<std::uint32_t>(kind));
    ((h = combine(h, static_cast<std::uint32_t>(parts))), ...);
    return h;
}

/// Tags for clipping: a vertex of the incident polygon, the incident edge leaving a vertex, and
/// a side plane of the reference face. A clipped point is (edge tag, plane tag).
constexpr std::uint32_t vertexTag(std::uint32_t v) { return combine(0x11u, v); }
constexpr std::uint32_t edgeTag(std::uint32_t v) { return combine(0x22u, v); }
constexpr std::uint32_t planeTag(std::uint32_t k) { return combine(0x33u, k); }

}  // namespace anyphys::native::feature

#pragma once
// Generational handles. A handle stays valid until its object is destroyed; after that every
// use raises anyphys::Error, even if the slot has been reused.
#include <cstdint>
#include <functional>
#include <limits>

namespace anyphys {

struct BodyId {
    std::uint32_t index = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t generation = 0;

    constexpr bool isNull() const { return index == std::numeric_limits<std::uint32_t>::max(); }
    friend constexpr bool operator==(BodyId a, BodyId b) { return a.index == b.index && a.generation == b.generation; }
    friend constexpr bool operator<(BodyId a, BodyId b) {
        return a.index != b.index ? a.index < b.index : a.generation < b.generation;
    }
};

/// A joint's handle id: the same generational scheme as BodyId.
struct JointId {
    std::uint32_t index = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t generation = 0;

    constexpr bool isNull() const { return index == std::numeric_limits<std::uint32_t>::max(); }
    friend constexpr bool operator==(JointId a, JointId b) { return a.index == b.index && a.generation == b.generation; }
    friend constexpr bool operator<(JointId a, JointId b) {
        return a.index != b.index ? a.index < b.index : a.generation < b.generation;
    }
};

}  // namespace anyphys

template <>
struct std::hash<anyphys::BodyId> {
    std::size_t operator()(anyphys::BodyId id) const noexcept {
        return std::hash<std::uint64_t>()((std::uint64_t(id.generation) << 32) | id.index);
    }
};

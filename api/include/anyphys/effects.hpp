#pragma once
// Effects: the physical phenomena a world simulates. A world runs only the stages its effects
// call for; a stage whose effect is off is never entered.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace anyphys {

enum class Effect : std::uint32_t {
    Gravity = 1u << 0,              ///< uniform gravity field (WorldSettings::gravity)
    Damping = 1u << 1,              ///< linear and angular velocity damping
    Gyroscopic = 1u << 2,           ///< the omega x (I omega) term of Euler's equations
    UserForces = 1u << 3,           ///< forces, torques and the per-step force callback
    Contacts = 1u << 4,             ///< collision detection and contact response
    Friction = 1u << 5,             ///< Coulomb friction at contacts
    Restitution = 1u << 6,          ///< bouncing at contacts
    Joints = 1u << 7,               ///< joint constraints
    Sleeping = 1u << 8,             ///< resting islands stop being simulated
    ContinuousCollision = 1u << 9,  ///< time of impact for fast bodies
    Events = 1u << 10,              ///< collision / trigger events for listeners
    // Force fields (fields/): the layer applies them through forces and impulses on every backend.
    Buoyancy = 1u << 11,            ///< fluid below a plane: Archimedes' force and drag in the fluid
    Drag = 1u << 12,                ///< quadratic air drag
    Wind = 1u << 13,                ///< quadratic drag relative to moving air
    Explosion = 1u << 14,           ///< impulses from a point at a given time
    // Particle effects (fields/): simulated by the layer, coupled to bodies through impulses.
    Fluid = 1u << 15,               ///< position-based fluid particles
    Cloth = 1u << 16,               ///< position-based cloth sheets
};

/// A set of effects. Bitwise, cheap to copy.
class Effects {
public:
    constexpr Effects() = default;
    constexpr Effects(Effect e) : bits_(static_cast<std::uint32_t>(e)) {}  // NOLINT: implicit by design

    static constexpr Effects none() { return Effects(); }
    static Effects all();

    constexpr bool has(Effect e) const { return (bits_ & static_cast<std::uint32_t>(e)) != 0; }
    constexpr Effects& add(Effect e) { bits_ |= static_cast<std::uint32_t>(e); return *this; }
    constexpr Effects& remove(Effect e) { bits_ &= ~static_cast<std::uint32_t>(e); return *this; }
    constexpr bool empty() const { return bits_ == 0; }
    constexpr bool contains(Effects other) const { return (bits_ & other.bits_) == other.bits_; }
    constexpr std::uint32_t bits() const { return bits_; }

    friend constexpr Effects operator|(Effects a, Effects b) { Effects r; r.bits_ = a.bits_ | b.bits_; return r; }
    friend constexpr Effects operator&(Effects a, Effects b) { Effects r; r.bits_ = a.bits_ & b.bits_; return r; }
    friend constexpr Effects operator~(Effects a) { Effects r; r.bits_ = ~a.bits_ & allBits(); return r; }
    friend constexpr bool operator==(Effects a, Effects b) { return a.bits_ == b.bits_; }

    /// Names in declaration order, e.g. {"gravity", "damping"}.
    std::vector<std::string> names() const;

private:
    static constexpr std::uint32_t allBits() { return (1u << 17) - 1; }  // one bit per Effect
    std::uint32_t bits_ = 0;
};

constexpr Effects operator|(Effect a, Effect b) { return Effects(a) | Effects(b); }

/// Every effect with its scene-file name ("gravity", "damping", "gyroscopic", "userForces",
/// "contacts", "friction", "restitution", "joints", "sleeping", "continuousCollision", "events",
/// "buoyancy", "drag", "wind", "explosion", "fluid", "cloth").
struct EffectName {
    Effect effect;
    std::string_view name;
};
inline constexpr EffectName kEffectNames[] = {
    {Effect::Gravity, "gravity"},
    {Effect::Damping, "damping"},
    {Effect::Gyroscopic, "gyroscopic"},
    {Effect::UserForces, "userForces"},
    {Effect::Contacts, "contacts"},
    {Effect::Friction, "friction"},
    {Effect::Restitution, "restitution"},
    {Effect::Joints, "joints"},
    {Effect::Sleeping, "sleeping"},
    {Effect::ContinuousCollision, "continuousCollision"},
    {Effect::Events, "events"},
    {Effect::Buoyancy, "buoyancy"},
    {Effect::Drag, "drag"},
    {Effect::Wind, "wind"},
    {Effect::Explosion, "explosion"},
    {Effect::Fluid, "fluid"},
    {Effect::Cloth, "cloth"},
};

std::string_view toString(Effect e);
/// Returns the effect with that scene-file name, or nothing.
std::optional<Effect> effectFromString(std::string_view name);

inline Effects Effects::all() {
    Effects r;
    for (const auto& n : kEffectNames) r.add(n.effect);
    return r;
}

inline std::vector<std::string> Effects::names() const {
    std::vector<std::string> out;
    for (const auto& n : kEffectNames)
        if (has(n.effect)) out.emplace_back(n.name);
    return out;
}

inline std::string_view toString(Effect e) {
    for (const auto& n : kEffectNames)
        if (n.effect == e) return n.name;
    return "unknown";
}

inline std::optional<Effect> effectFromString(std::string_view name) {
    for (const auto& n : kEffectNames)
        if (n.name == name) return n.effect;
    return std::nullopt;
}

}  // namespace anyphys

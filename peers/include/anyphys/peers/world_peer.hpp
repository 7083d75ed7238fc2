#pragma once
// The backend side of one world.
#include <functional>
#include <memory>

#include "anyphys/defs.hpp"
#include "anyphys/effects.hpp"
#include "anyphys/peers/body_peer.hpp"

namespace anyphys {

/// Everything the layer has resolved for a new body: the def plus its final mass properties.
struct BodyPeerDef {
    BodyDef def;                 ///< validated; orientation normalised
    MassProperties mass;         ///< solved by the layer (zero for static and kinematic bodies)
};

/// Access to body states while the backend evaluates forces inside a step. For backends with
/// ForceEvaluation::PerStage these are the integrator's intermediate states.
class ForceStage {
public:
    virtual ~ForceStage() = default;
    virtual double time() const = 0;  ///< s, the time of this evaluation
    virtual BodyState state(const BodyPeer& body) const = 0;
    virtual void addForce(BodyPeer& body, const Vec3& force) = 0;
    virtual void addTorque(BodyPeer& body, const Vec3& torque) = 0;
};

using ForceHook = std::function<void(ForceStage&)>;

class WorldPeer {
public:
    virtual ~WorldPeer() = default;

    virtual std::unique_ptr<BodyPeer> createBody(const BodyPeerDef& def) = 0;
    /// The peer is destroyed by the caller right after this returns.
    virtual void destroyBody(BodyPeer& body) = 0;

    /// The effects to simulate from now on (already intersected with the capabilities).
    virtual void setEffects(Effects effects) = 0;
    /// Called inside each step when forces are evaluated; empty to clear.
    virtual void setForceHook(ForceHook hook) = 0;

    /// Advances by dt seconds (the layer guarantees dt > 0 and finite). `time` is the start time.
    virtual void step(double time, double dt) = 0;
};

}  // namespace anyphys

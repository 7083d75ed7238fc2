#pragma once
// The native backend's world: body storage, collision (broad phase, contacts), the contact
// solver, islands for sleeping, and the pipeline of stages that advances them.
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "anyphys/peers/world_peer.hpp"
#include "anyphys/world_settings.hpp"
#include "collision/broad_phase.hpp"
#include "contact_solver.hpp"
#include "contacts.hpp"
#include "integrators.hpp"
#include "native_body.hpp"
#include "pipeline.hpp"

namespace anyphys::native {

class NativeWorld final : public WorldPeer {
public:
    /// Solver defaults (the backend's capabilities declare the same): Box2D v3's 4 substeps, and
    /// 2 iterations each, measured to keep a 10-box stack within 3 mm where 1 substep with 10
    /// iterations drifts 1 cm at about the same cost.
    static constexpr Solver kDefaultSolver = Solver::SoftStep;
    static constexpr int kDefaultSubsteps = 4;
    static constexpr int kDefaultIterations = 3;

    /// Unset solver settings take the defaults above.
    explicit NativeWorld(const WorldSettings& settings);
    ~NativeWorld() override;

    std::unique_ptr<BodyPeer> createBody(const BodyPeerDef& def) override;
    void destroyBody(BodyPeer& body) override;
    void setEffects(Effects effects) override;
    void setForceHook(ForceHook hook) override;
    void step(double time, double dt) override;
    void setMaterialTable(const MaterialTable& table) override;
    void collectContacts(std::vector<PeerContact>& out) override;
    std::vector<PeerRayHit> raycast(const Vec3& origin, const Vec3& direction, double maxDistance, bool closestOnly,
                                    std::uint32_t mask) override;
    std::vector<std::uint64_t> overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                       std::uint32_t mask) override;

    // ---- for stages and peers -------------------------------------------------------
    const WorldSettings& settings() const { return settings_; }
    /// Some dynamic or kinematic body was awake when this step began. When none is, nothing can
    /// move or touch anew, so the contact stages skip their walks: a sleeping pile costs ~nothing.
    bool anyActive() const { return anyActive_; }
    Effects effects() const { return effects_; }
    /// Body slots; a slot with alive == false is free.
    std::vector<NativeBody>& bodies() { return bodies_; }
    const std::vector<NativeBody>& bodies() const { return bodies_; }
    const ForceHook& forceHook() const { return forceHook_; }
    IntegratorScratch& integratorScratch() { return scratch_; }
    BroadPhase& broadPhase() { return broadPhase_; }
    ContactManager& contactManager() { return contacts_; }
    ContactSolver& contactSolver() { return solver_; }
    const MaterialTable& materials() const { return materials_; }

    /// Evaluates the user's force hook once with the bodies' current states (solver substeps).
    void evaluateForceHook(double time);
    Vec3 hookForce(std::uint32_t body) const { return body < hookForces_.size() ? hookForces_[body] : Vec3::Zero(); }
    Vec3 hookTorque(std::uint32_t body) const { return body < hookTorques_.size() ? hookTorques_[body] : Vec3::Zero(); }

    void wakeBody(std::uint32_t body);
    void sleepBody(std::uint32_t body);
    /// Puts a set of resting bodies to sleep together; waking one wakes them all.
    void sleepIsland(const std::vector<std::uint32_t>& members);
    /// Moves the body's proxies after a teleport and wakes it.
    void bodyTeleported(std::uint32_t body);
    /// Refreshes a body's broad-phase proxies from its pose, enlarged along `displacement`.
    void updateProxies(std::uint32_t body, const Vec3& displacement);

    /// Names of the stages the next step will run, in order (for tests and diagnostics).
    std::vector<std::string> activeStageNames();

private:
    void rebuildPipelineIfNeeded();

    WorldSettings settings_;
    Effects effects_;
    ForceHook forceHook_;
    std::vector<NativeBody> bodies_;
    std::vector<std::uint32_t> freeSlots_;
    std::vector<std::unique_ptr<Stage>> stages_;
    std::vector<Stage*> active_;
    bool pipelineDirty_ = true;
    bool anyActive_ = true;
    IntegratorScratch scratch_;
    BroadPhase broadPhase_;
    ContactManager contacts_;
    ContactSolver solver_;
    MaterialTable materials_;
    std::vector<Vec3> hookForces_, hookTorques_;
    std::unordered_map<int, std::vector<std::uint32_t>> sleepingIslands_;
    int nextIslandId_ = 0;
};

}  // namespace anyphys::native

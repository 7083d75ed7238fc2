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
#include "contacts.hpp"
#include "integrators.hpp"
#include "joints.hpp"
#include "native_body.hpp"
#include "per_worker_lists.hpp"
#include "pipeline.hpp"
#include "solver/step_solver.hpp"

namespace anyphys::native {

class NativeWorld final : public WorldPeer {
public:
    /// Solver defaults, published as the backend's capabilities (native_backend.cpp); the layer
    /// fills unset settings with them before it creates the world. Substeps buy more
    /// stability than iterations: measured without sleeping at 60 Hz, 8 substeps x 1 iteration
    /// (16 passes) keeps a 20-box stack within 6 mm and Box3D's 100-row pyramid standing, where
    /// 4 x 1 (Box3D's 8 passes) lets 294 of the pyramid's boxes slide more than 25 cm
    /// (docs/architecture.md has the figures).
    static constexpr Solver kDefaultSolver = Solver::SoftStep;
    static constexpr int kDefaultSubsteps = 8;
    static constexpr int kDefaultIterations = 1;

    /// `settings` resolved by the layer (solver, substeps and iterations set: withBackendDefaults);
    /// throws std::logic_error otherwise.
    explicit NativeWorld(const WorldSettings& settings);
    ~NativeWorld() override;

    std::unique_ptr<BodyPeer> createBody(const BodyPeerDef& def) override;
    void destroyBody(BodyPeer& body) override;
    std::unique_ptr<JointPeer> createJoint(const JointPeerDef& def) override;
    void destroyJoint(JointPeer& joint) override;
    void setEffects(Effects effects) override;
    void setForceHook(ForceHook hook) override;
    void setTaskSystem(TaskSystem* tasks) override { tasks_ = tasks; }
    void step(double time, double dt) override;
    void setMaterialTable(const MaterialTable& table) override;
    void reportContacts(ContactReport& out) override;
    bool hasAwakeBodies() const override { return awakeBodies_ > 0; }
    void findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const override;
    std::vector<PeerRayHit> raycast(const Vec3& origin, const Vec3& direction, double maxDistance, bool closestOnly,
                                    std::uint32_t mask) override;
    std::vector<std::uint64_t> overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                       std::uint32_t mask) override;

    // ---- for stages and peers -------------------------------------------------------
    const WorldSettings& settings() const { return settings_; }
    /// Relax passes per substep (backend option relaxIterations): each a pass over the joints
    /// and contacts without position bias, after the positions move. Default: soft_step runs as
    /// many as it runs solve passes (settings.iterations), pgs none (Baumgarte keeps its push).
    int relaxIterations() const { return relaxIterations_; }
    /// Some dynamic or kinematic body was awake when this step began. When none is, nothing can
    /// move or touch anew, so the contact stages skip their walks: a sleeping pile costs ~nothing.
    bool anyActive() const { return anyActive_; }
    Effects effects() const { return effects_; }
    /// Joint slots; a slot with alive == false is free.
    std::vector<NativeJoint>& joints() { return joints_; }
    /// Wakes the bodies of a joint (a changed motor, limit or spring).
    void wakeJoint(std::uint32_t joint);
    /// Body slots; a slot with alive == false is free.
    NativeBodies& bodies() { return bodies_; }
    const NativeBodies& bodies() const { return bodies_; }
    const ForceHook& forceHook() const { return forceHook_; }
    BroadPhase& broadPhase() { return broadPhase_; }
    const BroadPhase& broadPhase() const { return broadPhase_; }
    ContactManager& contactManager() { return contacts_; }
    const ContactManager& contactManager() const { return contacts_; }
    StepSolver& solver() { return solver_; }
    /// Where parallel work runs; null: on the calling thread.
    TaskSystem* taskSystem() const { return tasks_; }
    const MaterialTable& materials() const { return materials_; }

    /// Evaluates the user's force hook once with the bodies' current states (solver substeps).
    void evaluateForceHook(double time);
    Vec3 hookForce(std::uint32_t body) const { return body < hookForces_.size() ? hookForces_[body] : Vec3::Zero(); }
    Vec3 hookTorque(std::uint32_t body) const { return body < hookTorques_.size() ? hookTorques_[body] : Vec3::Zero(); }

    void wakeBody(std::uint32_t body);
    void sleepBody(std::uint32_t body);
    /// Puts a set of resting bodies to sleep together; waking one wakes them all.
    void sleepIsland(const std::vector<std::uint32_t>& members);
    /// Islands asleep now (tests: an island goes when it wakes or its last body is destroyed).
    std::size_t sleepingIslandCount() const { return sleepingIslands_.size(); }
    /// Sets a body's awake flag, keeping the count of awake moving bodies.
    void setAwakeFlag(NativeBody& body, bool awake);
    /// Moves the body's proxies after a teleport and wakes it.
    void bodyTeleported(std::uint32_t body);
    /// Refreshes a body's broad-phase proxies from its pose, enlarged along `displacement`.
    void updateProxies(std::uint32_t body, const Vec3& displacement);
    /// The same for every awake moving body, enlarged along its motion over `dt`: bounds are
    /// computed on the workers, then the proxies that left their fat boxes move, in proxy order.
    void updateAllProxies(double dt);

    /// Names of the stages the next step will run, in order (for tests and diagnostics).
    std::vector<std::string> activeStageNames();

private:
    void rebuildPipelineIfNeeded();

    WorldSettings settings_;
    int relaxIterations_ = 0;
    Effects effects_;
    double lastStepDt_ = 0.0;   // s: the last step's (NativeBody::fall)
    bool fallNotedLastStep_ = false;  // the last step noted its bodies' NativeBody::fall
    ForceHook forceHook_;
    NativeBodies bodies_;
    std::vector<std::uint32_t> freeSlots_;
    std::vector<NativeJoint> joints_;
    std::vector<std::uint32_t> freeJoints_;
    std::vector<std::unique_ptr<Stage>> stages_;
    std::vector<Stage*> active_;
    bool pipelineDirty_ = true;
    bool anyActive_ = true;
    int awakeBodies_ = 0;       // dynamic and kinematic bodies awake
    int multiShapeBodies_ = 0;  // bodies with several shapes (their contacts need merging per body pair)
    BroadPhase broadPhase_;
    ContactManager contacts_;
    StepSolver solver_;
    TaskSystem* tasks_ = nullptr;
    struct ReportChunk {  // reportContacts: a chunk's first pair and point (its counts while counting)
        std::size_t pairs = 0, points = 0;
    };
    std::vector<ReportChunk> reportChunks_;
    MaterialTable materials_;
    std::vector<Vec3> hookForces_, hookTorques_;
    struct ProxyMove {
        int proxy;
        Aabb fat;
        bool operator<(const ProxyMove& o) const { return proxy < o.proxy; }
    };
    PerWorkerLists<ProxyMove> proxyMoves_;
    std::unordered_map<int, std::vector<std::uint32_t>> sleepingIslands_;
    int nextIslandId_ = 0;
};

}  // namespace anyphys::native

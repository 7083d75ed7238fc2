#pragma once
// The native backend's world: dense body storage plus a pipeline of stages.
#include <memory>
#include <string>
#include <vector>

#include "anyphys/peers/world_peer.hpp"
#include "anyphys/world_settings.hpp"
#include "integrators.hpp"
#include "native_body.hpp"
#include "pipeline.hpp"

namespace anyphys::native {

class NativeWorld final : public WorldPeer {
public:
    explicit NativeWorld(const WorldSettings& settings);
    ~NativeWorld() override;

    std::unique_ptr<BodyPeer> createBody(const BodyPeerDef& def) override;
    void destroyBody(BodyPeer& body) override;
    void setEffects(Effects effects) override;
    void setForceHook(ForceHook hook) override;
    void step(double time, double dt) override;

    // ---- for stages -----------------------------------------------------------------
    const WorldSettings& settings() const { return settings_; }
    Effects effects() const { return effects_; }
    std::vector<NativeBody>& bodies() { return bodies_; }
    const std::vector<NativeBody>& bodies() const { return bodies_; }
    const ForceHook& forceHook() const { return forceHook_; }
    IntegratorScratch& integratorScratch() { return scratch_; }

    /// Names of the stages the next step will run, in order (for tests and diagnostics).
    std::vector<std::string> activeStageNames();

private:
    void rebuildPipelineIfNeeded();

    WorldSettings settings_;
    Effects effects_;
    ForceHook forceHook_;
    std::vector<NativeBody> bodies_;
    std::vector<std::unique_ptr<Stage>> stages_;
    std::vector<Stage*> active_;
    bool pipelineDirty_ = true;
    IntegratorScratch scratch_;
};

}  // namespace anyphys::native

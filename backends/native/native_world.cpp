#include "native_world.hpp"

#include "stages.hpp"

namespace anyphys::native {

NativeWorld::NativeWorld(const WorldSettings& settings) : settings_(settings), stages_(makeFreeBodyPipeline()) {}

NativeWorld::~NativeWorld() = default;

std::unique_ptr<BodyPeer> NativeWorld::createBody(const BodyPeerDef& peerDef) {
    const BodyDef& def = peerDef.def;
    NativeBody body;
    body.type = def.type;
    body.state = {def.position, def.orientation.normalized(), def.linearVelocity, def.angularVelocity};
    if (def.type == BodyType::Dynamic) {
        body.invMass = 1.0 / peerDef.mass.mass;
        body.inertia = peerDef.mass.inertia;
        body.invInertia = peerDef.mass.inertia.cwiseInverse();
    }
    body.linearDamping = def.linearDamping;
    body.angularDamping = def.angularDamping;
    body.gravityScale = def.gravityScale;
    body.gyroscopic = def.gyroscopic;
    auto peer = std::make_unique<NativeBodyPeer>(*this, static_cast<std::uint32_t>(bodies_.size()));
    body.peer = peer.get();
    bodies_.push_back(body);
    pipelineDirty_ = true;
    return peer;
}

void NativeWorld::destroyBody(BodyPeer& peer) {
    // Swap-and-pop keeps storage dense; the moved body's peer learns its new index.
    auto& native = static_cast<NativeBodyPeer&>(peer);
    const std::uint32_t index = native.index();
    if (index + 1 != bodies_.size()) {
        bodies_[index] = bodies_.back();
        bodies_[index].peer->setIndex(index);
    }
    bodies_.pop_back();
    pipelineDirty_ = true;
}

void NativeWorld::setEffects(Effects effects) {
    effects_ = effects;
    pipelineDirty_ = true;
}

void NativeWorld::setForceHook(ForceHook hook) {
    forceHook_ = std::move(hook);
    pipelineDirty_ = true;
}

void NativeWorld::rebuildPipelineIfNeeded() {
    if (!pipelineDirty_) return;
    active_.clear();
    for (const auto& stage : stages_)
        if (stage->needed(*this)) active_.push_back(stage.get());
    pipelineDirty_ = false;
}

std::vector<std::string> NativeWorld::activeStageNames() {
    rebuildPipelineIfNeeded();
    std::vector<std::string> names;
    for (const Stage* stage : active_) names.emplace_back(stage->name());
    return names;
}

void NativeWorld::step(double time, double dt) {
    rebuildPipelineIfNeeded();
    const int substeps = settings_.substeps;
    const double h = dt / substeps;
    for (int i = 0; i < substeps; ++i) {
        const StepInfo info{time + i * h, h};
        for (Stage* stage : active_)
            if (stage->perSubstep()) stage->run(*this, info);
    }
    const StepInfo whole{time, dt};
    for (Stage* stage : active_)
        if (!stage->perSubstep()) stage->run(*this, whole);
}

}  // namespace anyphys::native

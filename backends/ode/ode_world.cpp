#include "ode_world.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "anyphys/error.hpp"
#include "anyphys/peers/resolved_settings.hpp"
#include "ode_init.hpp"
#include "ode_math.hpp"
#include "ode_tuning.hpp"

namespace anyphys::ode {
namespace {

}  // namespace

OdeWorld::OdeWorld(const WorldSettings& settings) : settings_(settings) {
    erp_ = backendOption(settings, "erp", settings.baumgarte);
    cfm_ = backendOption(settings, "cfm", kDefaultCfm);  // both in range: the layer checked (caps.options)
    ensureOdeInitialised();
    world_ = dWorldCreate();
    dWorldSetData(world_, this);  // lets tests reach the peer from the escape hatch
    space_ = dHashSpaceCreate(nullptr);
    dHashSpaceSetLevels(space_, kHashMinLevel, kHashMaxLevel);
    contactGroup_ = dJointGroupCreate(0);
    ray_ = dCreateRay(nullptr, 1.0);
    dGeomSetCategoryBits(ray_, ~0ul);
    dGeomSetCollideBits(ray_, ~0ul);

    dWorldSetERP(world_, erp_);
    dWorldSetCFM(world_, cfm_);
    direct_ = resolvedSolver(settings_) == Solver::Direct;
    dWorldSetQuickStepNumIterations(world_, resolvedIterations(settings_));
    dWorldSetQuickStepW(world_, kQuickStepW);
    // ODE 0.16's dWorldStep with a surface layer pumps energy into resting stacks (three stacked
    // boxes thrown 20 m up when the correcting velocity is not capped): the direct solver runs
    // without one.
    dWorldSetContactSurfaceLayer(world_, direct_ ? 0.0 : kSurfaceLayerPerSlop * settings.linearSlop);
    dWorldSetContactMaxCorrectingVel(world_, settings.contactPushMaxVelocity);
    // Sleeping: ODE's auto-disable with the layer's thresholds, instantaneous (one velocity
    // sample), after timeToSleep seconds at rest. Set as the world's defaults, so each body
    // starts its idle countdown from timeToSleep; the flag is per body (effects, def.allowSleep).
    dWorldSetAutoDisableFlag(world_, 0);
    dWorldSetAutoDisableLinearThreshold(world_, settings.sleepLinearVelocity);
    dWorldSetAutoDisableAngularThreshold(world_, settings.sleepAngularVelocity);
    dWorldSetAutoDisableAverageSamplesCount(world_, 1);
    dWorldSetAutoDisableSteps(world_, 0);
    dWorldSetAutoDisableTime(world_, settings.timeToSleep);
    dWorldSetGravity(world_, 0, 0, 0);  // until setEffects turns gravity on
}

OdeWorld::~OdeWorld() {
    // Bodies are destroyed by the layer before the world; whatever is left goes with the world.
    dGeomDestroy(ray_);
    dJointGroupDestroy(contactGroup_);
    dSpaceDestroy(space_);
    dWorldDestroy(world_);
}

std::unique_ptr<BodyPeer> OdeWorld::createBody(const BodyPeerDef& def) {
    auto body = std::make_unique<OdeBody>(*this, def);
    body->slot = bodies_.size();
    bodies_.push_back(body.get());
    if (body->isDynamic() && body->gravityScale() != 0.0 && body->gravityScale() != 1.0) scaledGravity_.push_back(body.get());
    if (body->shapeCount() > 1) ++multiShapeBodies_;
    geomCount_ += body->shapeCount();
    if (body->needsGyroscopic(effects_)) gyroscopic_.push_back(body.get());
    body->applyEffects(effects_, odeStep());
    return body;
}

void OdeWorld::destroyBody(BodyPeer& peer) {
    auto& body = static_cast<OdeBody&>(peer);
    wakeTouching(body);  // bodies resting on it (even asleep) must not hang in the air
    std::erase_if(pairs_, [&](const PairRecord& p) { return p.a == &body || p.b == &body; });
    geomCount_ -= body.shapeCount();
    std::erase(forced_, &body);
    std::erase(scaledGravity_, &body);
    std::erase(gyroscopic_, &body);
    if (body.shapeCount() > 1) --multiShapeBodies_;
    bodies_.back()->slot = body.slot;
    bodies_[body.slot] = bodies_.back();
    bodies_.pop_back();
}

std::unique_ptr<JointPeer> OdeWorld::createJoint(const JointPeerDef& def) {
    auto joint = std::make_unique<OdeJoint>(*this, def);
    joint->slot = userJoints_.size();
    userJoints_.push_back(joint.get());
    if (!def.collideConnected && def.bodyA)
        ++excludedPairs_[std::minmax(static_cast<const OdeBody*>(def.bodyA), static_cast<const OdeBody*>(def.bodyB))];
    return joint;
}

void OdeWorld::destroyJoint(JointPeer& peer) {
    auto& joint = static_cast<OdeJoint&>(peer);
    if (!joint.collideConnected() && joint.bodyA()) {
        const std::pair<const OdeBody*, const OdeBody*> key = std::minmax<const OdeBody*>(joint.bodyA(), joint.bodyB());
        if (--excludedPairs_[key] == 0) excludedPairs_.erase(key);
    }
    // Bodies it held (even asleep) move freely from now on.
    if (joint.bodyB()->id()) dBodyEnable(joint.bodyB()->id());
    if (joint.bodyA() && joint.bodyA()->id()) dBodyEnable(joint.bodyA()->id());
    userJoints_.back()->slot = joint.slot;
    userJoints_[joint.slot] = userJoints_.back();
    userJoints_.pop_back();
}

bool OdeWorld::jointExcludes(const OdeBody* a, const OdeBody* b) const {
    return !excludedPairs_.empty() && excludedPairs_.contains(std::minmax(a, b));
}

void OdeWorld::setEffects(Effects effects) {
    effects_ = effects;
    for (OdeJoint* j : userJoints_) j->setEnabled(effects.has(Effect::Joints));
    const Vec3 g = effects.has(Effect::Gravity) ? settings_.gravity : Vec3::Zero();
    dWorldSetGravity(world_, g.x(), g.y(), g.z());
    const double h = odeStep();
    gyroscopic_.clear();
    for (OdeBody* b : bodies_) {
        b->applyEffects(effects_, h);
        if (b->needsGyroscopic(effects_)) gyroscopic_.push_back(b);
    }
}

double OdeWorld::odeStep() const {
    // Before the first step: the step the settings announce.
    return lastH_ > 0.0 ? lastH_ : settings_.timeStep / resolvedSubsteps(settings_);
}

void OdeWorld::setMaterialTable(const MaterialTable& table) { materials_ = table; }

void OdeWorld::queueForces(OdeBody& body) {
    if (body.forceQueued) return;
    body.forceQueued = true;
    forced_.push_back(&body);
}

void OdeWorld::applyDampingStep(double h) {
    // Damping scales depend on the ODE step length: recomputed when dt / substeps changes.
    lastH_ = h;
    if (!effects_.has(Effect::Damping)) return;
    for (OdeBody* b : bodies_) b->applyEffects(effects_, h);
}

void OdeWorld::step(double /*time: forces come evaluated from the layer*/, double dt) {
    const int substeps = resolvedSubsteps(settings_);
    const double h = dt / substeps;
    lastDt_ = dt;
    if (h != lastH_) applyDampingStep(h);
    const bool contacts = effects_.has(Effect::Contacts);
    const bool continuous = contacts && effects_.has(Effect::ContinuousCollision);
    const Vec3 g = settings_.gravity;
    ensureOdeThreadData();
    // Quickstep shuffles constraint rows with ODE's one global generator: each world keeps its own
    // stream, so a world's results never depend on what other worlds (or users of ODE) did. Worlds
    // on other threads wait for the generator (docs/threads.md: ODE worlds step one at a time).
    const std::lock_guard randomLock(odeRandomMutex());
    const unsigned long outsideSeed = dRandGetSeed();
    dRandSetSeed(randomSeed_);
    if (!contacts) {
        pairs_.clear();
        points_.clear();
        normals_.clear();
    }
    const bool joints = effects_.has(Effect::Joints) && !userJoints_.empty();
    {
        // The one value ODE's world CFM still sets (contacts and every other joint row have their
        // own): a slider's and a wheel's main rows, made stiff enough for the heaviest pair they
        // hold (pairCfm), and never below the conditioning floor of the lightest (conditionedCfm).
        // A light slider in the same world is stiffer with it, never softer; with the last heavy
        // one gone, the world's CFM is back to its own.
        double heaviest = 0.0, heaviestRow = 0.0;
        for (const OdeJoint* j : userJoints_)
            if (j->mainRowsTakeTheWorldsCfm()) {
                heaviest = std::max(heaviest, j->pairMass());
                heaviestRow = std::max(heaviestRow, j->rowWeightBound());
            }
        const double worldCfm = conditionedCfm(pairCfm(cfm_, heaviest), h, heaviestRow);
        if (worldCfm != dWorldGetCFM(world_)) dWorldSetCFM(world_, worldCfm);
    }
    if (joints) countSpringsPerBody();
    for (int s = 0; s < substeps; ++s) {
        if (contacts) collide();
        if (joints)
            for (OdeJoint* j : userJoints_) j->beforeOdeStep(h);
        for (const OdeBody* b : forced_) b->feedForces();
        if (effects_.has(Effect::Gravity))
            for (const OdeBody* b : scaledGravity_) {
                // ODE applies g to every body: add the rest of gravityScale x g as a force.
                const Vec3 f = b->mass() * (b->gravityScale() - 1.0) * g;
                dBodyAddForce(b->id(), f.x(), f.y(), f.z());
            }
        for (const OdeBody* b : gyroscopic_)
            if (b->isActive()) b->applyGyroscopic(h);
        if (continuous) {
            before_.resize(bodies_.size());
            for (std::size_t i = 0; i < bodies_.size(); ++i)
                if (bodies_[i]->id()) before_[i] = toVec3(dBodyGetPosition(bodies_[i]->id()));
        }
        if (direct_) {
            if (directStepper_.step(world_, bodies_, h)) ++directFallbacks_;
            ++directSteps_;
        } else {
            dWorldQuickStep(world_, h);
            ++quickSteps_;
        }
        if (contacts) dJointGroupEmpty(contactGroup_);
        if (joints)
            for (OdeJoint* j : userJoints_) j->afterOdeStep();
        if (settings_.planar)
            for (const OdeBody* b : bodies_) b->projectToPlane();
        if (continuous) continuousCollision(before_);
    }
    for (OdeBody* b : forced_) b->clearForces();
    forced_.clear();
    for (OdeJoint* j : userJoints_) j->finishStep(dt, joints ? substeps : 1);
    randomSeed_ = dRandGetSeed();
    dRandSetSeed(outsideSeed);
}

void OdeWorld::countSpringsPerBody() {
    springsPerBody_.clear();
    for (const OdeJoint* joint : userJoints_)
        if (joint->sprung())
            for (const OdeBody* body : {joint->bodyA(), joint->bodyB()})
                if (body && body->isDynamic()) springsPerBody_.add(body);  // not the world, not static
    if (springsPerBody_.empty()) return;
    springsPerBody_.sort();
    for (OdeJoint* joint : userJoints_)
        if (joint->sprung()) joint->springsOnBusierBody = springsPerBody_.onBusierBody(joint->bodyA(), joint->bodyB());
}

void* OdeWorld::nativeObject(const std::type_info& pointerType) {
    if (pointerType == typeid(dxWorld*)) return world_;
    if (pointerType == typeid(dxSpace*)) return space_;
    return nullptr;
}

}  // namespace anyphys::ode

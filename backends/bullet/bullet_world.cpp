#include "bullet_world.hpp"

#include <algorithm>
#include <functional>

#include "anyphys/peers/resolved_settings.hpp"
#include "bullet_convert.hpp"
#include "bullet_solver.hpp"

namespace anyphys::bullet {

bool LayerFilter::needBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const {
    const auto* o0 = static_cast<const btCollisionObject*>(proxy0->m_clientObject);
    const auto* o1 = static_cast<const btCollisionObject*>(proxy1->m_clientObject);
    const auto* a = static_cast<const BulletBodyPeer*>(o0->getUserPointer());
    const auto* b = static_cast<const BulletBodyPeer*>(o1->getUserPointer());
    if (a == nullptr || b == nullptr) return true;  // not ours (e.g. a user's object through the escape hatch)
    if (!contacts) return false;
    if (!o0->checkCollideWith(o1)) return false;  // joined by a joint with collideConnected false
    // Bodies' unions of their children's layers and masks: a pair may touch only if these do; a
    // body with mixed children has its points sorted per child after the narrow phase.
    if (!layersCollide(a->layer(), a->mask(), b->layer(), b->mask())) return false;
    if (a->anyTrigger() || b->anyTrigger()) return a->moves() || b->moves();  // sensors see anything that moves
    return a->dynamic() || b->dynamic();                               // something must respond
}

namespace {

bool planeMultipoint(const WorldSettings& settings) { return backendOption(settings, "planeMultipoint", 1.0) != 0.0; }

std::unique_ptr<btDefaultCollisionConfiguration> makeCollisionConfiguration(const WorldSettings& settings) {
    // Bullet's default pools hold 4096 manifolds and 4096 collision algorithms, allocated and
    // touched up front: 65 ms per world under ASan (the API fuzzer spent most of its time there).
    // 256 of each cover a pile of hundreds of touching pairs; past that Bullet allocates each new
    // pair's manifold from the heap (CD_DISABLE_CONTACTPOOL_DYNAMIC_ALLOCATION is not set), which
    // costs only when pairs begin. bench/direct/bullet_scenes.cpp gives raw Bullet the same pools.
    btDefaultCollisionConstructionInfo info;
    info.m_defaultMaxPersistentManifoldPoolSize = 256;
    info.m_defaultMaxCollisionAlgorithmPoolSize = 256;
    auto configuration = std::make_unique<btDefaultCollisionConfiguration>(info);
    // Backend option planeMultipoint (default 1): a convex shape on a plane gets its whole face
    // of points (Bullet's perturbation) instead of one new point per step, which leaves a box on
    // the ground standing on a corner and rocking. Five perturbations, 72 deg apart, so that no
    // two lie along a face's edges (there the tilted face's deepest corner is a tie and one is
    // missed: with Bullet's 3, a box sliding along x kept 3 corners, tipped and stopped 1 % short),
    // whenever the manifold lacks a whole face (4). Set before the dispatcher copies the
    // algorithm factories.
    if (planeMultipoint(settings)) configuration->setPlaneConvexMultipointIterations(5, 4);
    return configuration;
}

}  // namespace

BulletWorld::BulletWorld(const WorldSettings& settings)
    : settings_(settings),
      configuration_(makeCollisionConfiguration(settings)),
      boxBox_(static_cast<btScalar>(settings.linearSlop)),
      // Pairs closer than linearSlop touch, at every size (bullet_touching.hpp).
      dispatcher_(std::make_unique<TouchingDispatcher>(configuration_.get(), static_cast<btScalar>(2 * settings.linearSlop))),
      broadphase_(std::make_unique<btDbvtBroadphase>()) {
    const Solver solver = resolvedSolver(settings);
    const auto maxPush = static_cast<btScalar>(settings.contactPushMaxVelocity);
    if (solver == Solver::Direct) {
        // Bullet's MLCP: contacts and friction as one mixed LCP solved by Dantzig's pivoting method
        // (btMLCPSolver falls back to sequential impulses when the pivoting fails).
        mlcpInterface_ = std::make_unique<btDantzigSolver>();
        solver_ = std::make_unique<AnyphysMlcpSolver>(mlcpInterface_.get(), maxPush);
    } else {
        solver_ = std::make_unique<AnyphysSequentialImpulseSolver>(maxPush);
    }
    world_ = std::make_unique<AnyphysDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                    configuration_.get());
    broadphase_->getOverlappingPairCache()->setOverlapFilterCallback(&filter_);
    world_->setGravity(btVector3(0, 0, 0));  // per body (gravity scale), see BulletBodyPeer::applyEffects
    world_->setSensorCompounds(&sensorCompounds_);
    world_->setMaterials(&materials_);
    world_->setTimeToSleep(settings.timeToSleep);
    world_->setRestitutionThreshold(settings.restitutionThreshold);
    // A sliding box keeps its whole face of contact on a box (bullet_box_box.hpp).
    dispatcher_->registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, &boxBox_);
    dispatcher_->registerCollisionCreateFunc(SPHERE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE, &sphereSphere_);
    // A sliding hull keeps its whole face of contact on a box or a hull (bullet_hull_pairs.hpp).
    dispatcher_->registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE, &hullPairs_);
    dispatcher_->registerCollisionCreateFunc(CONVEX_HULL_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, &hullPairs_);
    dispatcher_->registerCollisionCreateFunc(CONVEX_HULL_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE, &hullPairs_);
    // A capsule lying on a box or a hull keeps its whole line of contact (bullet_capsule_polyhedron.hpp).
    dispatcher_->registerCollisionCreateFunc(CAPSULE_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, &capsulePolyhedron_);
    dispatcher_->registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE, &polyhedronCapsule_);
    dispatcher_->registerCollisionCreateFunc(CAPSULE_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE, &capsulePolyhedron_);
    dispatcher_->registerCollisionCreateFunc(CONVEX_HULL_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE, &polyhedronCapsule_);
    // A box, a hull, a capsule or a sphere lying on a mesh triangle keeps its whole face, line or
    // point of contact (bullet_face_on_triangle.hpp); btConvexTriangleCallback asks for (convex,
    // triangle) only.
    const auto onTriangle = [this](FaceOnTriangleAlgorithm::CreateFunc& mine, int convex) {
        mine.bullets = configuration_->getCollisionAlgorithmCreateFunc(convex, TRIANGLE_SHAPE_PROXYTYPE);
        dispatcher_->registerCollisionCreateFunc(convex, TRIANGLE_SHAPE_PROXYTYPE, &mine);
    };
    onTriangle(boxOnTriangle_, BOX_SHAPE_PROXYTYPE);
    onTriangle(hullOnTriangle_, CONVEX_HULL_SHAPE_PROXYTYPE);
    onTriangle(capsuleOnTriangle_, CAPSULE_SHAPE_PROXYTYPE);
    onTriangle(sphereOnTriangle_, SPHERE_SHAPE_PROXYTYPE);
    planeMultipoint_ = planeMultipoint(settings);  // its refresh pass runs while a plane is here (createBody)
    if (planeMultipoint_) {  // a capsule's whole line of contact too (bullet_capsule_plane.hpp)
        dispatcher_->registerCollisionCreateFunc(CAPSULE_SHAPE_PROXYTYPE, STATIC_PLANE_PROXYTYPE, &capsulePlane_);
        dispatcher_->registerCollisionCreateFunc(STATIC_PLANE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE, &planeCapsule_);
    }
    // Only moving bodies need fresh bounds each step; static ones are refreshed when teleported.
    world_->setForceUpdateAllAabbs(false);

    btContactSolverInfo& info = world_->getSolverInfo();
    info.m_numIterations = resolvedIterations(settings);
    // Overlap is pushed out at the layer's Baumgarte fraction per step: through the velocity up to
    // 4 cm deep, by split impulse (moving positions only) beyond (Bullet's defaults). Split impulse
    // from 5 mm on lets a box sliding down a 35 deg slope sink 4 cm into it, and at every depth a
    // 10-box stack topples. Bouncing impacts get no push at all (AnyphysDynamicsWorld::applyMaterials).
    info.m_erp = static_cast<btScalar>(settings.baumgarte);
    info.m_erp2 = static_cast<btScalar>(backendOption(settings, "erp2", settings.baumgarte));
    info.m_splitImpulse = backendOption(settings, "splitImpulse", 1.0) != 0.0;
    info.m_splitImpulsePenetrationThreshold = static_cast<btScalar>(-backendOption(settings, "splitImpulseDepth", 0.04));
    // Two friction directions per point (Bullet's SOLVER_USE_2_FRICTION_DIRECTIONS): with one,
    // along the sliding velocity only, a box resting 2 deg under the friction angle creeps away
    // (0.85 m in 2 s) because at rest that direction is arbitrary. Two make friction a square
    // rather than a circle, which holds slightly more than mu (see the known deviations).
    if (backendOption(settings, "frictionDirections", 2) >= 2) info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
    if (backendOption(settings, "frictionCaching", 0) != 0) info.m_solverMode |= SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
    if (backendOption(settings, "fixedFrictionDirections", 0) != 0)
        info.m_solverMode |= SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION;
    info.m_linearSlop = static_cast<btScalar>(backendOption(settings, "linearSlop", 0.0));
    info.m_warmstartingFactor = static_cast<btScalar>(backendOption(settings, "warmstarting", info.m_warmstartingFactor));
    info.m_restitutionVelocityThreshold = static_cast<btScalar>(settings.restitutionThreshold);
    info.m_globalCfm = static_cast<btScalar>(backendOption(settings, "cfm", info.m_globalCfm));
    // Bullet starts every joint row from zero impulse each step (no warm starting, unlike
    // contacts). Each joint's rigid rows are decoupled (DecoupledConstraint), but rows of
    // different joints, and a motor or limit against its joint's rigid rows, still converge by
    // iteration: at the world's 30 a motor holding a 1 m arm of 2 kg droops by 0.3 rad in 2 s and
    // a 40-link chain gaps 5.8 cm. Joints get their own count (Bullet's per-constraint override;
    // contacts keep the world's): 10 x iterations, 2e-4 rad and 3.5 mm.
    jointIterations_ = static_cast<int>(backendOption(settings, "jointIterations", 10.0 * info.m_numIterations));
    decoupledJoints_ = backendOption(settings, "decoupledJoints", 1.0) != 0.0;
}

BulletWorld::~BulletWorld() {
    // Joints and bodies whose peers outlive the world (the layer destroys them first; tests may
    // not) leave it now, so their peers never touch a dead world; joints first, their constraints
    // refer to the bodies.
    while (!joints_.empty()) detachJoint(*joints_.back());
    while (!bodies_.empty()) detach(*bodies_.back());
}

std::unique_ptr<JointPeer> BulletWorld::createJoint(const JointPeerDef& def) {
    auto peer = std::make_unique<BulletJointPeer>(*this, def);
    // collideConnected false: Bullet records the pair on both bodies (checkCollideWith), the
    // layer filter then refuses the pair, and a pair already in the cache goes now, with its
    // manifold, so no stale contact between them is reported or solved. A joint to the world has
    // no pair to keep apart.
    const bool apart = !def.collideConnected && def.bodyA != nullptr;
    world_->addConstraint(&peer->constraint(), apart);
    if (apart) {
        btRigidBody& a = static_cast<BulletBodyPeer*>(def.bodyA)->rigidBody();
        btRigidBody& b = static_cast<BulletBodyPeer*>(def.bodyB)->rigidBody();
        if (a.getBroadphaseHandle() != nullptr && b.getBroadphaseHandle() != nullptr)
            broadphase_->getOverlappingPairCache()->removeOverlappingPair(a.getBroadphaseHandle(),
                                                                          b.getBroadphaseHandle(), dispatcher_.get());
    }
    // A joint wakes what it joins (Bullet then keeps them in one island).
    if (def.bodyA != nullptr) def.bodyA->setAwake(true);
    def.bodyB->setAwake(true);
    peer->constraint().setEnabled(effects_.has(Effect::Joints));
    peer->constraint().setOverrideNumSolverIterations(jointIterations_);
    joints_.push_back(peer.get());
    return peer;
}

void BulletWorld::destroyJoint(JointPeer& joint) { detachJoint(static_cast<BulletJointPeer&>(joint)); }

void BulletWorld::detachJoint(BulletJointPeer& joint) {
    const auto it = std::find(joints_.begin(), joints_.end(), &joint);
    if (it == joints_.end()) return;
    joints_.erase(it);
    btTypedConstraint& c = joint.constraint();
    world_->removeConstraint(&c);
    joint.detached();
    // The bodies fall on their own now: wake them.
    btRigidBody& a = c.getRigidBodyA();
    btRigidBody& b = c.getRigidBodyB();
    for (btRigidBody* body : {&a, &b})
        if (!body->isStaticOrKinematicObject()) body->activate(true);
    // A pair kept apart may collide again: the broad phase only reports pairs that begin to
    // overlap, so one overlapping already goes back into the cache here (through the filter).
    btBroadphaseProxy* pa = a.getBroadphaseHandle();
    btBroadphaseProxy* pb = b.getBroadphaseHandle();
    if (pa != nullptr && pb != nullptr && a.checkCollideWith(&b) &&
        TestAabbAgainstAabb2(pa->m_aabbMin, pa->m_aabbMax, pb->m_aabbMin, pb->m_aabbMax) &&
        broadphase_->getOverlappingPairCache()->findPair(pa, pb) == nullptr)
        broadphase_->getOverlappingPairCache()->addOverlappingPair(pa, pb);
}

std::unique_ptr<BodyPeer> BulletWorld::createBody(const BodyPeerDef& def) {
    auto peer = std::make_unique<BulletBodyPeer>(*this, def);
    btRigidBody& body = peer->rigidBody();
    // Filtering is the layer's rule (LayerFilter); Bullet's own groups let everything through.
    world_->addRigidBody(&body, btBroadphaseProxy::AllFilter, btBroadphaseProxy::AllFilter);
    peer->inWorld_ = true;
    bodies_.push_back(peer.get());
    attached_.insert(&body);
    if (peer->type() == BodyType::Kinematic) kinematic_.push_back(peer.get());
    if (peer->hasMesh() && meshBodies_++ == 0) setReaching(true);
    else if (meshBodies_ > 0) peer->setReaching(true);
    if (peer->trigger() && sensorBodies_++ == 0) world_->setClearSensorManifolds(true);
    if (peer->mixedSurfaces() && mixedBodies_++ == 0) world_->setSortChildPoints(true);
    if (peer->hasSolidPart()) sensorCompounds_.push_back(peer.get());
    if (peer->isPlane() && planeBodies_++ == 0) world_->setRefreshPlaneManifoldsFirst(planeMultipoint_);
    if (peer->compound()) ++compoundBodies_;
    peer->applyEffects();
    if (!def.def.isAwake && peer->moves()) peer->setAwake(false);
    return peer;
}

void BulletWorld::destroyBody(BodyPeer& peer) { detach(static_cast<BulletBodyPeer&>(peer)); }

void BulletWorld::setReaching(bool on) {
    // Only while a mesh is here: the larger boxes cost broad-phase pairs (see ReachingShape).
    for (BulletBodyPeer* body : bodies_) {
        body->setReaching(on);
        world_->updateSingleAabb(&body->rigidBody());
    }
}

void BulletWorld::detach(BulletBodyPeer& peer) {
    if (!peer.inWorld_) return;
    btRigidBody& body = peer.rigidBody();
    // Bodies resting on this one must not hang in the air.
    const auto wake = [this](const btCollisionObject* other) {
        if (attached_.contains(other)) const_cast<btCollisionObject*>(other)->activate();
    };
    const int manifolds = dispatcher_->getNumManifolds();
    for (int m = 0; m < manifolds; ++m) {
        btPersistentManifold* manifold = dispatcher_->getManifoldByIndexInternal(m);
        if (manifold->getBody0() == &body) wake(manifold->getBody1());
        if (manifold->getBody1() == &body) wake(manifold->getBody0());
    }
    world_->removeRigidBody(&body);
    world_->forgetChildOverlaps(&body);
    attached_.erase(&body);
    peer.inWorld_ = false;
    const auto drop = [&peer](std::vector<BulletBodyPeer*>& list) {
        list.erase(std::remove(list.begin(), list.end(), &peer), list.end());
    };
    drop(bodies_);
    if (peer.type() == BodyType::Kinematic) drop(kinematic_);
    if (peer.hasMesh() && --meshBodies_ == 0) setReaching(false);
    if (peer.trigger() && --sensorBodies_ == 0) world_->setClearSensorManifolds(false);
    if (peer.mixedSurfaces() && --mixedBodies_ == 0) world_->setSortChildPoints(false);
    if (peer.hasSolidPart()) drop(sensorCompounds_);
    if (peer.isPlane() && --planeBodies_ == 0) world_->setRefreshPlaneManifoldsFirst(false);
    if (peer.compound()) --compoundBodies_;
    drop(forced_);
}

void BulletWorld::teleported(BulletBodyPeer& peer) {
    if (!peer.inWorld_) return;
    world_->updateSingleAabb(&peer.rigidBody());
    if (peer.moves()) return;
    // A moved static body: what touched it must look again.
    const int manifolds = dispatcher_->getNumManifolds();
    for (int m = 0; m < manifolds; ++m) {
        btPersistentManifold* manifold = dispatcher_->getManifoldByIndexInternal(m);
        const btCollisionObject* other = manifold->getBody0() == &peer.rigidBody()   ? manifold->getBody1()
                                         : manifold->getBody1() == &peer.rigidBody() ? manifold->getBody0()
                                                                                     : nullptr;
        if (other != nullptr && attached_.contains(other)) const_cast<btCollisionObject*>(other)->activate();
    }
}

void BulletWorld::setEffects(Effects effects) {
    const bool contactsChanged = effects.has(Effect::Contacts) != effects_.has(Effect::Contacts);
    effects_ = effects;
    world_->setEffects(effects);
    filter_.contacts = effects.has(Effect::Contacts);
    for (BulletJointPeer* joint : joints_) joint->constraint().setEnabled(effects.has(Effect::Joints));
    // Continuous collision: Bullet's swept-sphere CCD and its predictive contacts.
    world_->getDispatchInfo().m_useContinuous = effects.has(Effect::ContinuousCollision);
    for (BulletBodyPeer* body : bodies_) {
        body->applyEffects();
        // Pairs are filtered when they are created: re-filter every proxy when contacts toggle.
        if (contactsChanged && body->rigidBody().getBroadphaseHandle())
            world_->refreshBroadphaseProxy(&body->rigidBody());
    }
}

void BulletWorld::setMaterialTable(const MaterialTable& table) {
    materials_ = table;
    world_->setMaterials(&materials_);  // the points hold the old table's values
}

// A spring keeps its explicit force only while the springs of its busier body together stay
// inside explicit stepping's stable range (bullet_joint_spring.hpp): each joint gets that count.
void BulletWorld::countSpringsPerBody() {
    springsPerBody_.clear();
    for (BulletJointPeer* joint : joints_)
        if (joint->sprung())
            for (const btRigidBody* body : {&joint->constraint().getRigidBodyA(), &joint->constraint().getRigidBodyB()})
                if (body->getInvMass() != 0) springsPerBody_.add(body);  // not static or kinematic
    if (springsPerBody_.empty()) return;
    springsPerBody_.sort();
    for (BulletJointPeer* joint : joints_)
        if (joint->sprung())
            joint->setSpringsOnBusierBody(
                springsPerBody_.onBusierBody(&joint->constraint().getRigidBodyA(), &joint->constraint().getRigidBodyB()));
}

void BulletWorld::step(double /*time: forces come evaluated from the layer*/, double dt) {
    // One internal Bullet step per substep, of exactly dt / substeps: the layer already takes
    // fixed steps, so Bullet's own accumulator must neither add nor drop a step.
    const int substeps = resolvedSubsteps(settings_);
    const double h = dt / substeps;
    const auto bh = static_cast<btScalar>(h);
    countSpringsPerBody();
    for (BulletJointPeer* joint : joints_) joint->beginStep();
    earlierImpulses_.clear();
    for (int s = 0; s < substeps; ++s) {
        for (BulletBodyPeer* body : forced_) body->pushForces();
        for (BulletJointPeer* joint : joints_) joint->beginSubstep();
        world_->stepSimulation(bh, 1, bh);
        if (s + 1 < substeps && effects_.has(Effect::Events)) accumulateSubstepImpulses();
        for (BulletJointPeer* joint : joints_) joint->endSubstep(h);
        for (BulletBodyPeer* body : kinematic_) body->advanceKinematic(h);
    }
    mergeEarlierImpulses();
    for (BulletJointPeer* joint : joints_) joint->endStep(dt);
    for (BulletBodyPeer* body : forced_) body->clearForces();
    forced_.clear();
    boundsStale_ = true;
}

void BulletWorld::refreshBounds() {
    if (!boundsStale_) return;
    world_->updateAabbs();
    boundsStale_ = false;
}

bool BulletWorld::hasAwakeBodies() const {
    return !effects_.has(Effect::Contacts) || world_->awakeBodyCount() > 0;
}

void BulletWorld::findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const {
    for (const BulletBodyPeer* body : bodies_)
        if (body->moves() && !body->admittedBy(limits)) out.push_back(body->userData());
}

BulletWorld::ObjectPair BulletWorld::pairOf(const btPersistentManifold& manifold) {
    const btCollisionObject* a = manifold.getBody0();
    const btCollisionObject* b = manifold.getBody1();
    return std::less<>()(a, b) ? ObjectPair(a, b) : ObjectPair(b, a);
}

void BulletWorld::accumulateSubstepImpulses() {
    const int manifolds = dispatcher_->getNumManifolds();
    for (int m = 0; m < manifolds; ++m) {
        const btPersistentManifold* manifold = dispatcher_->getManifoldByIndexInternal(m);
        double impulse = 0.0;
        for (int i = 0; i < manifold->getNumContacts(); ++i) impulse += manifold->getContactPoint(i).getAppliedImpulse();
        if (!(impulse > 0.0)) continue;  // none (a NaN too, as before)
        const auto solved = static_cast<std::uint32_t>(earlierImpulses_.size());
        earlierImpulses_.push_back({pairOf(*manifold), impulse, 0.0, 0, solved});
    }
}

void BulletWorld::mergeEarlierImpulses() {
    if (earlierImpulses_.empty()) return;
    // A pair's entries in the order they were solved, so its sum adds its substeps and manifolds
    // in that order (std::stable_sort would allocate a buffer every step).
    std::sort(earlierImpulses_.begin(), earlierImpulses_.end(), [](const EarlierImpulse& x, const EarlierImpulse& y) {
        return x.pair != y.pair ? x.pair < y.pair : x.solved < y.solved;
    });
    std::size_t kept = 0;
    for (std::size_t k = 0; k < earlierImpulses_.size(); ++k) {
        if (kept > 0 && earlierImpulses_[kept - 1].pair == earlierImpulses_[k].pair)
            earlierImpulses_[kept - 1].impulse += earlierImpulses_[k].impulse;
        else
            earlierImpulses_[kept++] = earlierImpulses_[k];
    }
    earlierImpulses_.resize(kept);
}

BulletWorld::EarlierImpulse* BulletWorld::earlierImpulse(const btPersistentManifold& manifold) {
    const ObjectPair pair = pairOf(manifold);
    const auto it = std::lower_bound(earlierImpulses_.begin(), earlierImpulses_.end(), pair,
                                     [](const EarlierImpulse& e, const ObjectPair& p) { return e.pair < p; });
    return it != earlierImpulses_.end() && it->pair == pair ? &*it : nullptr;
}

// A first pass over every manifold, short and independent per manifold, lets the processor load
// many of them at once; most of a pile's manifolds have no points (bounding boxes overlap, shapes
// do not). The report's walk then finds the rest in cache.
const std::vector<const btPersistentManifold*>& BulletWorld::manifoldsWithPoints() {
    withPoints_.clear();
    btPersistentManifold* const* manifolds = dispatcher_->getInternalManifoldPointer();
    const int count = dispatcher_->getNumManifolds();
    for (int m = 0; m < count; ++m)
        if (manifolds[m]->getNumContacts() > 0) withPoints_.push_back(manifolds[m]);
    return withPoints_;
}

void BulletWorld::reportContacts(ContactReport& out) {
    // Compound bodies (one manifold per child pair) and continuous collision's predictive
    // contacts make several manifolds per body pair: merged at the end, only then.
    bool repeats = world_->predictiveManifoldCount() > 0;
    const auto asleep = [](const BulletBodyPeer& body) { return body.moves() && !body.isAwake(); };
    const std::vector<const btPersistentManifold*>& manifolds = manifoldsWithPoints();
    // With substeps, each pair's impulse of the earlier substeps is shared among its points in
    // proportion to their last impulses (evenly when those are zero): the pair's total is the
    // step's, its split among points the last substep's.
    if (!earlierImpulses_.empty()) {
        for (EarlierImpulse& e : earlierImpulses_) {
            e.lastImpulse = 0.0;
            e.lastPoints = 0;
        }
        for (const btPersistentManifold* manifold : manifolds)
            if (EarlierImpulse* e = earlierImpulse(*manifold))
                for (int i = 0; i < manifold->getNumContacts(); ++i) {
                    e->lastImpulse += manifold->getContactPoint(i).getAppliedImpulse();
                    ++e->lastPoints;
                }
    }
    const auto earlierShare = [&](const btPersistentManifold& manifold, const btManifoldPoint& p) {
        if (earlierImpulses_.empty()) return 0.0;
        const EarlierImpulse* e = earlierImpulse(manifold);
        if (e == nullptr) return 0.0;
        return e->lastImpulse > 0.0 ? e->impulse * p.getAppliedImpulse() / e->lastImpulse : e->impulse / e->lastPoints;
    };
    for (const btPersistentManifold* manifold : manifolds) {
        const int count = manifold->getNumContacts();
        const auto* a = static_cast<const BulletBodyPeer*>(manifold->getBody0()->getUserPointer());
        const auto* b = static_cast<const BulletBodyPeer*>(manifold->getBody1()->getUserPointer());
        if (a == nullptr || b == nullptr) continue;
        if (!a->activeMover() && !b->activeMover()) continue;  // asleep: the layer keeps the pair
        repeats = repeats || a->compound() || b->compound();
        const bool sleeping = asleep(*a) || asleep(*b);
        if (a->trigger() || b->trigger()) {
            bool overlapping = false;  // a sensor overlaps when some point touches or penetrates
            for (int i = 0; i < count && !overlapping; ++i) overlapping = manifold->getContactPoint(i).getDistance() <= 0;
            if (overlapping) out.addPair(a->userData(), b->userData(), true, Vec3::Zero(), sleeping);
            continue;
        }
        // Bullet's normal points from body 1 to body 0; the layer wants it from A to B.
        out.addPair(a->userData(), b->userData(), false, -fromBt(manifold->getContactPoint(0).m_normalWorldOnB), sleeping);
        for (int i = 0; i < count; ++i) {
            const btManifoldPoint& p = manifold->getContactPoint(i);
            const Vec3 point = 0.5 * (fromBt(p.getPositionWorldOnA()) + fromBt(p.getPositionWorldOnB()));
            const double impulse = static_cast<double>(p.getAppliedImpulse()) + earlierShare(*manifold, p);
            out.addPoint({point, -static_cast<double>(p.getDistance()), impulse});
        }
    }
    // Sensor children's overlaps, taken out of the manifolds before the solver (sortChildPoints).
    for (const AnyphysDynamicsWorld::ChildOverlap& o : world_->childOverlaps()) {
        const auto* a = static_cast<const BulletBodyPeer*>(o.a->getUserPointer());
        const auto* b = static_cast<const BulletBodyPeer*>(o.b->getUserPointer());
        if (!a->activeMover() && !b->activeMover()) continue;  // asleep: the layer keeps the pair
        out.addPair(a->userData(), b->userData(), true, Vec3::Zero(), asleep(*a) || asleep(*b));
        repeats = true;  // several child pairs may overlap: one trigger per body pair
    }
    out.sleepKnown = true;
    if (repeats) {
        out.mergeRepeatedPairs();
    } else if (effects_.has(Effect::ContinuousCollision) || compoundBodies_ > 0) {
        // A later step may merge (a fast body's predictive manifold, a compound's first touch):
        // its buffers grow now, with the report, not in that step.
        out.keepRoomToMerge();
    }
}

void* BulletWorld::nativeObject(const std::type_info& pointerType) {
    if (pointerType == typeid(btDiscreteDynamicsWorld*)) return static_cast<btDiscreteDynamicsWorld*>(world_.get());
    if (pointerType == typeid(btDynamicsWorld*)) return static_cast<btDynamicsWorld*>(world_.get());
    if (pointerType == typeid(btCollisionWorld*)) return static_cast<btCollisionWorld*>(world_.get());
    return nullptr;
}

}  // namespace anyphys::bullet

#pragma once
// btDiscreteDynamicsWorld with the per-world hooks anyphys needs, through virtual overrides so
// that two worlds in one process never share state (Bullet's own ways, such as gDeactivationTime,
// are process globals):
//  - solveConstraints: before Bullet solves, contact points get the layer's resolved friction and
//    restitution for their pair of materials, per compound child (Bullet would multiply the two
//    bodies' values). A point takes them when the narrow phase adds or replaces it, through
//    Bullet's gContactAddedCallback (a process global, but stateless: it reaches the point's world
//    through the bodies), so only continuous collision's predictive points are left to this pass;
//    every point is written again after the table or the effects change, and every step while
//    some material bounces (restitution depends on the closing speed);
//  - updateActivationState: sleeping with this world's timeToSleep, or never.
//  - predictUnconstraintMotion: damping by the exact factor exp(-c h) per Bullet step, and the
//    layer's gyroscopic term (implicit or explicit), in one pass over the bodies;
//  - performDiscreteCollisionDetection: stale convex-plane points dropped before the narrow
//    phase, so a sliding box keeps its face of points; after it, the points of compound children
//    that the layer's filter keeps apart are dropped and those of sensor children taken out as
//    trigger overlaps (Bullet's filter and contact response are per body, not per child);
//  - createPredictiveContacts, integrateTransforms (continuous collision's sweeps): a compound of
//    solid and sensor children shows only its solid part while they run; a predictive point sits
//    on the body's surface facing the hit, not at its centre, so friction turns the body; a body
//    held by a joint is not clamped to its first hit (integrateTransforms), only held by its
//    predictive contacts;
//  - saveKinematicState: a no-op; Bullet would recompute a kinematic body's velocity from its
//    last two poses, but anyphys moves kinematic bodies itself at their exact velocity.
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "anyphys/effects.hpp"
#include "anyphys/peers/world_peer.hpp"

namespace anyphys::bullet {

class BulletBodyPeer;

class AnyphysDynamicsWorld final : public btDiscreteDynamicsWorld {
public:
    AnyphysDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, btConstraintSolver* solver,
                         btCollisionConfiguration* configuration);

    /// The table the points' materials come from; called again after it changed.
    void setMaterials(const MaterialTable* table);
    void setEffects(Effects effects);
    void setTimeToSleep(double seconds) { timeToSleep_ = static_cast<btScalar>(seconds); }
    void setRestitutionThreshold(double speed) { restitutionThreshold_ = static_cast<btScalar>(speed); }
    /// Drop stale points of convex-plane manifolds before the narrow phase (with planeMultipoint,
    /// while the world holds a plane: the pass looks at every manifold).
    void setRefreshPlaneManifoldsFirst(bool on) { refreshPlaneManifoldsFirst_ = on; }
    /// Empty sensor manifolds before each narrow phase (see the .cpp); on while the world holds
    /// a sensor, since the pass over every manifold costs 2 % of a 1 000-box step without one.
    void setClearSensorManifolds(bool on) { clearSensorManifolds_ = on; }
    /// Sort contact points per compound child (see sortChildPoints); on while the world holds a
    /// body whose children differ in material, filter or sensor flag.
    void setSortChildPoints(bool on) { sortChildPoints_ = on; }

    /// A sensor child overlapping another body in the last Bullet step: the two collision objects
    /// (body 0 and body 1 of the manifold), once per manifold.
    struct ChildOverlap {
        const btCollisionObject* a;
        const btCollisionObject* b;
    };
    const std::vector<ChildOverlap>& childOverlaps() const { return childOverlaps_; }
    /// The compounds of solid and sensor children (kept by the world): the sweeps see only their
    /// solid children.
    void setSensorCompounds(const std::vector<BulletBodyPeer*>* bodies) { sensorCompounds_ = bodies; }
    /// A body leaving the world leaves no overlap behind that names it.
    void forgetChildOverlaps(const btCollisionObject* object) {
        std::erase_if(childOverlaps_, [object](const ChildOverlap& o) { return o.a == object || o.b == object; });
    }

    /// Gives the contact points that lack them the table's friction and restitution, and every
    /// point its restitution for this step while some material bounces (see the .cpp).
    void applyMaterials();
    /// The table's values for the two shapes the point joins (a and b: the manifold's body 0 and
    /// body 1).
    void writeMaterial(btManifoldPoint& p, const BulletBodyPeer& a, const BulletBodyPeer& b) const;
    /// Continuous collision's predictive contacts of the last step (they live in the dispatcher
    /// next to the ordinary manifolds, so one pair may have both).
    int predictiveManifoldCount() const { return m_predictiveManifolds.size(); }
    /// Dynamic and kinematic bodies awake at the end of the last step.
    int awakeBodyCount() const { return awakeBodies_; }

protected:
    void solveConstraints(btContactSolverInfo& solverInfo) override;
    void updateActivationState(btScalar timeStep) override;
    void saveKinematicState(btScalar timeStep) override { (void)timeStep; }
    void predictUnconstraintMotion(btScalar timeStep) override;
    void performDiscreteCollisionDetection() override;
    void createPredictiveContacts(btScalar timeStep) override;
    void integrateTransforms(btScalar timeStep) override;

private:
    void sortChildPoints();
    /// Writes the table into every point of the manifolds; with bouncing, judges each point's
    /// impact too.
    void writeMaterials(btPersistentManifold* const* manifolds, int count, bool bouncing);
    /// A point closing faster than the restitution threshold rebounds without Baumgarte push-out.
    void judgeImpact(btManifoldPoint& p, const btRigidBody* bodyA, const btRigidBody* bodyB) const;

    const MaterialTable* materials_ = nullptr;
    Effects effects_;
    btScalar timeToSleep_ = 0.5f;
    btScalar restitutionThreshold_ = 1.0f;
    btScalar timeStep_ = 1.0f / 60.0f;  // of the step being solved
    int awakeBodies_ = 0;
    bool refreshPlaneManifoldsFirst_ = false;
    bool clearSensorManifolds_ = false;
    bool sortChildPoints_ = false;
    // Set when the table or the effects change: the points Bullet keeps hold the old values.
    bool pointsStale_ = true;
    // Restitution is on and some pair of materials has some: each point's rebound is judged
    // every step from its closing speed.
    bool bouncing_ = false;
    bool fallNotedLastStep_ = false;  // the last step noted its bodies' fall (BulletBodyPeer::noteStepStart)
    const std::vector<BulletBodyPeer*>* sensorCompounds_ = nullptr;

    /// Runs one of Bullet's sweep phases with sensor children out of the way.
    template <class Phase>
    void sweep(Phase&& phase);
    std::vector<ChildOverlap> childOverlaps_;
    /// Bodies held by joints whose motion clamp integrateTransforms suspends, with its threshold.
    std::vector<std::pair<btRigidBody*, btScalar>> unclamped_;
    /// Moving kinematic bodies that integrateTransforms hides from the motion clamp, with their group.
    std::vector<std::pair<btBroadphaseProxy*, int>> hiddenKinematic_;
};

}  // namespace anyphys::bullet

#pragma once
// btDiscreteDynamicsWorld with the two per-world hooks anyphys needs, both through virtual
// overrides so that two worlds in one process never share state (Bullet's own ways, such as
// gContactAddedCallback and gDeactivationTime, are process globals):
//  - solveConstraints: before Bullet solves, every contact point gets the layer's resolved
//    friction and restitution for its pair of materials, per compound child (Bullet would
//    multiply the two bodies' values);
//  - updateActivationState: sleeping with this world's timeToSleep, or never.
//  - predictUnconstraintMotion: damping by the exact factor exp(-c h) per Bullet step;
//  - performDiscreteCollisionDetection: stale convex-plane points dropped before the narrow
//    phase, so a sliding box keeps its face of points; after it, the points of compound children
//    that the layer's filter keeps apart are dropped and those of sensor children taken out as
//    trigger overlaps (Bullet's filter and contact response are per body, not per child);
//  - createPredictiveContacts, integrateTransforms (continuous collision's sweeps): a compound of
//    solid and sensor children shows only its solid part while they run;
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
                         btCollisionConfiguration* configuration)
        : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration) {}

    void setMaterials(const MaterialTable* table) { materials_ = table; }
    void setEffects(Effects effects) { effects_ = effects; }
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

    /// Writes the table's friction and restitution into every contact point (also called by
    /// tests to check the table reaches the points).
    void applyMaterials();
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

    const MaterialTable* materials_ = nullptr;
    Effects effects_;
    btScalar timeToSleep_ = 0.5f;
    btScalar restitutionThreshold_ = 1.0f;
    btScalar timeStep_ = 1.0f / 60.0f;  // of the step being solved
    int awakeBodies_ = 0;
    bool refreshPlaneManifoldsFirst_ = false;
    bool clearSensorManifolds_ = false;
    bool sortChildPoints_ = false;
    const std::vector<BulletBodyPeer*>* sensorCompounds_ = nullptr;

    /// Runs one of Bullet's sweep phases with sensor children out of the way.
    template <class Phase>
    void sweep(Phase&& phase);
    std::vector<ChildOverlap> childOverlaps_;
};

}  // namespace anyphys::bullet

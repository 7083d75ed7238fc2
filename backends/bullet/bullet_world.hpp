#pragma once
// The Bullet backend's world: a btDiscreteDynamicsWorld and the objects it needs, owned here and
// destroyed in the right order (the world first, then solver, broad phase, dispatcher and
// configuration), plus what anyphys adds per world: the material table, the layer filter, the
// effects and the forces held for a step (addForce and the layer's step forces).
#include <cstdint>
#include <memory>
#include <utility>
#include <unordered_set>
#include <vector>

#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>
#include <btBulletDynamicsCommon.h>

#include "anyphys/peers/springs_per_body.hpp"
#include "anyphys/peers/world_peer.hpp"
#include "anyphys/world_settings.hpp"
#include "bullet_body.hpp"
#include "bullet_box_box.hpp"
#include "bullet_capsule_plane.hpp"
#include "bullet_capsule_polyhedron.hpp"
#include "bullet_dynamics_world.hpp"
#include "bullet_face_on_triangle.hpp"
#include "bullet_hull_pairs.hpp"
#include "bullet_joints.hpp"
#include "bullet_touching.hpp"

namespace anyphys::bullet {

/// The layer's filter, per world: two bodies pair only if their layers and masks agree and one
/// of them can respond (a sensor needs something that moves). Contacts off: nothing pairs.
class LayerFilter final : public btOverlapFilterCallback {
public:
    bool needBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override;
    bool contacts = false;
};

class BulletWorld final : public WorldPeer {
public:
    explicit BulletWorld(const WorldSettings& settings);
    ~BulletWorld() override;

    std::unique_ptr<BodyPeer> createBody(const BodyPeerDef& def) override;
    void destroyBody(BodyPeer& body) override;
    std::unique_ptr<JointPeer> createJoint(const JointPeerDef& def) override;
    void destroyJoint(JointPeer& joint) override;
    void setEffects(Effects effects) override;
    void step(double time, double dt) override;
    void setMaterialTable(const MaterialTable& table) override;
    void reportContacts(ContactReport& out) override;
    bool reportNearPair(BodyPeer& a, BodyPeer& b, double reach, ContactReport& out) override;  // bullet_near_pairs.cpp
    bool hasAwakeBodies() const override;
    void findUnsound(const MotionLimits& limits, std::vector<std::uint64_t>& out) const override;
    std::vector<PeerRayHit> raycast(const Vec3& origin, const Vec3& direction, double maxDistance, bool closestOnly,
                                    std::uint32_t mask) override;
    std::vector<std::uint64_t> overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                       std::uint32_t mask) override;
    void* nativeObject(const std::type_info& pointerType) override;

    // ---- for body peers ------------------------------------------------------------------
    const WorldSettings& settings() const { return settings_; }
    Effects effects() const { return effects_; }
    AnyphysDynamicsWorld& dynamicsWorld() { return *world_; }
    /// The body has force or torque to apply this step.
    void addForced(BulletBodyPeer* body) { forced_.push_back(body); }
    /// Removes the body from the Bullet world (on destroyBody, or when its peer dies first).
    void detach(BulletBodyPeer& body);
    /// Turns every body's reaching bounding boxes on or off (on while the world holds a mesh).
    void setReaching(bool on);
    /// The static body a joint to the world is attached to (frame = world frame; not in the
    /// Bullet world, one per world rather than Bullet's process-wide getFixedBody()).
    btRigidBody& ground() { return *ground_; }
    /// Joint rows decoupled per joint (backend option decoupledJoints, default 1).
    bool decoupledJoints() const { return decoupledJoints_; }
    /// The solver honours each row's CFM: sequential impulses do, the MLCP solver uses one for all.
    bool solvesRowsSoftly() const { return mlcpInterface_ == nullptr; }
    /// Removes the joint's constraint from the Bullet world (on destroyJoint, or when its peer dies first).
    void detachJoint(BulletJointPeer& joint);
    /// After a teleport: refresh the body's bounds and wake what touches it.
    void teleported(BulletBodyPeer& body);

private:
    /// Tells each sprung joint how many sprung joints its busier body has (before each step;
    /// anyphys/peers/springs_per_body.hpp).
    void countSpringsPerBody();
    /// A pair of collision objects, lower address first (one Bullet pair, however many manifolds).
    using ObjectPair = std::pair<const btCollisionObject*, const btCollisionObject*>;
    static ObjectPair pairOf(const btPersistentManifold& manifold);
    /// Adds each pair's normal impulse of the substep just solved to earlierImpulses_.
    void accumulateSubstepImpulses();
    /// After the last substep: earlierImpulses_ sorted by pair, one entry per pair.
    void mergeEarlierImpulses();
    /// The pair's entry in earlierImpulses_ (once merged), or nullptr.
    struct EarlierImpulse;
    EarlierImpulse* earlierImpulse(const btPersistentManifold& manifold);
    /// Brings the broad phase's bounds up to the poses a step left (queries see where bodies are).
    void refreshBounds();
    /// A convex shape of a body, in the world (reportNearPair, bullet_near_pairs.cpp).
    struct ConvexPart {
        const btConvexShape* shape;
        btTransform pose;
        int child;  // in the body's compound, else 0
    };
    /// The body's convex parts: its shape, or its compound's children. False when some part is
    /// not convex (a plane or a mesh).
    static bool convexParts(const btCollisionObject& object, std::vector<ConvexPart>& parts);
    std::vector<ConvexPart> nearPartsA_, nearPartsB_;  // reportNearPair's, kept for their capacity
    /// The manifolds holding contact points, in the dispatcher's order.
    const std::vector<const btPersistentManifold*>& manifoldsWithPoints();

    WorldSettings settings_;
    Effects effects_;
    // Normal impulse per pair over the step's substeps before the last (events only). Bullet's
    // points hold the last solve's impulse; reportContacts adds these to report the whole step's,
    // shared among a pair's points as the last solve shared its impulse (`last`). A vector kept
    // from step to step, so a steady step allocates nothing (a map made a node per pair per step).
    struct EarlierImpulse {
        ObjectPair pair;
        double impulse = 0.0;      // N s, the earlier substeps' sum
        double lastImpulse = 0.0;  // the last substep's, over the pair's points (reportContacts)
        int lastPoints = 0;
        std::uint32_t solved = 0;  // before merging: which solve added it (sums keep solve order)
    };
    std::vector<EarlierImpulse> earlierImpulses_;
    MaterialTable materials_;
    std::vector<BulletBodyPeer*> bodies_;     // every attached body
    int meshBodies_ = 0;                      // attached bodies with a triangle mesh
    int sensorBodies_ = 0;                    // attached trigger bodies
    int mixedBodies_ = 0;                     // attached bodies whose children differ in surface
    std::vector<BulletBodyPeer*> sensorCompounds_;  // attached compounds of solid and sensor children
    int planeBodies_ = 0;                     // attached bodies whose shape is a plane
    int compoundBodies_ = 0;                  // attached bodies of several child shapes
    bool planeMultipoint_ = true;             // backend option planeMultipoint
    // Bullet refreshes bounds before it integrates, so a step leaves them at the old poses. The
    // first query after a step refreshes them; later ones (an explosion casts a ray per body) do not.
    bool boundsStale_ = false;
    // The attached bodies' collision objects. Bullet can keep a manifold naming a body already
    // removed (seen when a torn chain's world is destroyed); waking a neighbour goes through here.
    std::unordered_set<const btCollisionObject*> attached_;
    std::vector<BulletBodyPeer*> kinematic_;  // attached kinematic bodies
    std::vector<BulletBodyPeer*> forced_;     // bodies with force or torque this step
    std::vector<BulletJointPeer*> joints_;    // every attached joint, in creation order
    SpringsPerBody<btRigidBody> springsPerBody_;    // countSpringsPerBody's
    std::vector<const btPersistentManifold*> withPoints_;  // scratch of manifoldsWithPoints
    int jointIterations_ = 300;                // solver iterations of joint rows (backend option)
    bool decoupledJoints_ = true;              // DecoupledConstraint on (backend option)

    // Destroyed in reverse order of declaration: world_ first.
    std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
    CapsulePlaneAlgorithm::CreateFunc capsulePlane_{false}, planeCapsule_{true};  // the dispatcher uses them
    BoxBoxAlgorithm::CreateFunc boxBox_;                                           // the same
    SphereSphereAlgorithm::CreateFunc sphereSphere_;                               // the same
    HullPairAlgorithm::CreateFunc hullPairs_;                                      // the same
    CapsulePolyhedronAlgorithm::CreateFunc capsulePolyhedron_{false}, polyhedronCapsule_{true};  // the same
    FaceOnTriangleAlgorithm::CreateFunc boxOnTriangle_, hullOnTriangle_, capsuleOnTriangle_, sphereOnTriangle_;  // the same
    std::unique_ptr<TouchingDispatcher> dispatcher_;
    std::unique_ptr<btBroadphaseInterface> broadphase_;
    std::unique_ptr<btDantzigSolver> mlcpInterface_;
    std::unique_ptr<btConstraintSolver> solver_;
    LayerFilter filter_;
    std::unique_ptr<btRigidBody> ground_ = std::make_unique<btRigidBody>(0, nullptr, nullptr);
    std::unique_ptr<AnyphysDynamicsWorld> world_;
};

}  // namespace anyphys::bullet

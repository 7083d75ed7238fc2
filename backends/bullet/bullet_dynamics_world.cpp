#include "bullet_dynamics_world.hpp"

#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>

#include <cmath>

#include "anyphys/peers/gyroscopic.hpp"
#include "anyphys/peers/rebound_from_depth.hpp"
#include "bullet_body.hpp"
#include "bullet_convert.hpp"
#include "bullet_world.hpp"

namespace anyphys::bullet {

void AnyphysDynamicsWorld::predictUnconstraintMotion(btScalar timeStep) {
    // One pass over the bodies applies both of the layer's terms, where Bullet would apply its
    // own: to the velocity at the start of the step, before forces and contacts.
    //  - Damping: Bullet damps by v *= (1 - d)^h with d clamped to [0, 1]. The d giving
    //    exp(-c h), 1 - exp(-c), rounds to exactly 1 above c = 37 1/s and freezes the body; so
    //    Bullet's damping stays 0 and the exact decay of dv/dt = -c v is applied here.
    //  - Gyroscopic: implicit, the torque-free backward-Euler turn of w; explicit,
    //    w += h I^-1 (-w x I w), the body frame's acceleration (as a torque, Bullet's world-frame
    //    inverse inertia would leak rounding of the large moments' terms into the small one: the
    //    needle of RotationTest diverged within 6 steps).
    const bool damping = effects_.has(Effect::Damping);
    const bool gyroscopic = effects_.has(Effect::Gyroscopic);
    for (int i = 0; bouncing_ && i < m_nonStaticRigidBodies.size(); ++i) {
        btRigidBody* body = m_nonStaticRigidBodies[i];
        if (body->isStaticOrKinematicObject() || !body->isActive()) continue;
        static_cast<BulletBodyPeer*>(body->getUserPointer())
            ->noteStepStart(fallNotedLastStep_, body->getLinearVelocity(), body->getGravity(), timeStep);
    }
    fallNotedLastStep_ = bouncing_;
    for (int i = 0; (damping || gyroscopic) && i < m_nonStaticRigidBodies.size(); ++i) {
        btRigidBody* body = m_nonStaticRigidBodies[i];
        if (body->isStaticOrKinematicObject() || !body->isActive()) continue;
        const auto* peer = static_cast<const BulletBodyPeer*>(body->getUserPointer());
        if (damping) {
            const double h = timeStep;
            body->setLinearVelocity(body->getLinearVelocity() * static_cast<btScalar>(std::exp(-peer->linearDamping() * h)));
            body->setAngularVelocity(body->getAngularVelocity() *
                                     static_cast<btScalar>(std::exp(-peer->angularDamping() * h)));
        }
        const GyroscopicMode mode = gyroscopic ? peer->appliedGyroscopic() : GyroscopicMode::None;
        if (mode == GyroscopicMode::None) continue;
        btQuaternion bq;
        body->getWorldTransform().getBasis().getRotation(bq);
        const Quat q = fromBt(bq).normalized();
        const Vec3 w = fromBt(body->getAngularVelocity());
        const Vec3& inertia = peer->massProperties().inertia;
        if (mode == GyroscopicMode::Implicit)
            body->setAngularVelocity(toBt(gyroscopic::solveImplicit(w, q, inertia, timeStep)));
        else
            body->setAngularVelocity(toBt(w + timeStep * gyroscopic::acceleration(w, q, inertia)));
    }
    btDiscreteDynamicsWorld::predictUnconstraintMotion(timeStep);
}

void AnyphysDynamicsWorld::performDiscreteCollisionDetection() {
    // Bullet's convex-plane test asks for a whole face of points (its perturbation) only when the
    // manifold holds fewer than 3, but drops the points that have slid past the breaking
    // threshold only afterwards. A sliding box's face points, made in one step, expire together
    // (after 8.7 mm for a 0.5 m box), so that step ends with the one new point: the box stands
    // on a corner, tips, rocks, and loses speed in the impacts (a box 2 deg past the friction
    // angle slid at 0.21 m/s^2, exact 0.38). Dropping them first lets the test refill the face.
    if (refreshPlaneManifoldsFirst_)
        for (int m = 0; m < getDispatcher()->getNumManifolds(); ++m) {
            btPersistentManifold* manifold = getDispatcher()->getManifoldByIndexInternal(m);
            const bool plane = manifold->getBody0()->getCollisionShape()->getShapeType() == STATIC_PLANE_PROXYTYPE ||
                               manifold->getBody1()->getCollisionShape()->getShapeType() == STATIC_PLANE_PROXYTYPE;
            if (plane && manifold->getNumContacts() > 0)
                manifold->refreshContactPoints(manifold->getBody0()->getWorldTransform(),
                                               manifold->getBody1()->getWorldTransform());
        }
    // A sensor's manifold starts each step empty, so whether it overlaps is judged from this
    // step's points only. Kept points are refreshed by moving with the bodies and dropped only
    // once they separate or slide past the breaking threshold; a ball passing straight through a
    // sensor moves along its entry point's normal, so that point only grew deeper (2.5 m deep
    // after crossing the sensor) and the sensor reported the overlap until the bounding boxes
    // parted. A sensor has no impulses to warm start, so nothing is lost.
    if (clearSensorManifolds_)
        for (int m = 0; m < getDispatcher()->getNumManifolds(); ++m) {
            btPersistentManifold* manifold = getDispatcher()->getManifoldByIndexInternal(m);
            if (!manifold->getBody0()->hasContactResponse() || !manifold->getBody1()->hasContactResponse())
                manifold->clearManifold();
        }
    btDiscreteDynamicsWorld::performDiscreteCollisionDetection();
    childOverlaps_.clear();
    if (sortChildPoints_) sortChildPoints();
}

// Bullet filters and responds per collision object; a compound's children may differ. After the
// narrow phase each point of a body with mixed children is judged by the two shapes it joins
// (the child indices m_index0 / m_index1 that Bullet's compound algorithm writes):
//  - the layer's filter keeps them apart, or neither body responds (no dynamic body and no
//    sensor): the point is dropped, as if never found;
//  - a sensor child: an overlapping point makes a trigger overlap of the two bodies, and every
//    such point is dropped so the solver never pushes on it (the manifold also starts the next
//    step empty, as a sensor body's does).
// The solver runs after this (solveConstraints), so it only sees the points that collide.
void AnyphysDynamicsWorld::sortChildPoints() {
    btDispatcher* dispatcher = getDispatcher();
    for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
        btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
        const auto* a = static_cast<const BulletBodyPeer*>(manifold->getBody0()->getUserPointer());
        const auto* b = static_cast<const BulletBodyPeer*>(manifold->getBody1()->getUserPointer());
        if (a == nullptr || b == nullptr || (!a->mixedSurfaces() && !b->mixedSurfaces())) continue;
        bool overlapping = false;
        for (int i = manifold->getNumContacts() - 1; i >= 0; --i) {
            btManifoldPoint& p = manifold->getContactPoint(i);
            // Continuous collision's predictive points name no child: found by position, and
            // written back with that child's material.
            const bool unnamed = (p.m_index0 < 0 && a->mixedSurfaces()) || (p.m_index1 < 0 && b->mixedSurfaces());
            if (p.m_index0 < 0 && a->mixedSurfaces()) p.m_index0 = a->childNear(p.getPositionWorldOnA());
            if (p.m_index1 < 0 && b->mixedSurfaces()) p.m_index1 = b->childNear(p.getPositionWorldOnB());
            if (unnamed) writeMaterial(p, *a, *b);
            const ChildSurface &sa = a->surface(p.m_index0), &sb = b->surface(p.m_index1);
            const bool sensor = sa.trigger || sb.trigger;
            const bool responds = sensor ? a->moves() || b->moves() : a->dynamic() || b->dynamic();
            const bool meets = responds && layersCollide(sa.layer, sa.mask, sb.layer, sb.mask);
            if (meets && !sensor) continue;                                  // two solid shapes: the solver's
            if (meets) overlapping = overlapping || p.getDistance() <= 0;  // a sensor child's overlap
            manifold->removeContactPoint(i);
        }
        if (overlapping) childOverlaps_.push_back({manifold->getBody0(), manifold->getBody1()});
    }
}

// Bullet's sweeps test whole collision shapes and would stop a body at a sensor child, so a
// compound of solid and sensor children shows only its solid part while they run (the shape is
// given back before anything else reads it: the narrow phase follows the predictive contacts,
// the next step follows the motion clamp).
template <class Phase>
void AnyphysDynamicsWorld::sweep(Phase&& phase) {
    const bool swap = sensorCompounds_ != nullptr && !sensorCompounds_->empty();
    if (swap)
        for (BulletBodyPeer* body : *sensorCompounds_) body->sweepSolidPartOnly(true);
    phase();
    if (swap)
        for (BulletBodyPeer* body : *sensorCompounds_) body->sweepSolidPartOnly(false);
}

// Bullet puts a predictive point on the swept body's centre, where friction has no lever: a ball
// landing obliquely fast enough to be swept lost its whole slide and never spun (20 m/s down and
// 6 across: 0 m/s after, where it rolls on at 5/7 of 6). The point moves to where the body's
// surface faces the hit, on the line through its centre along the normal: the normal row is
// unchanged (its lever lies along the normal), and friction acts at the surface and turns the body.
void AnyphysDynamicsWorld::createPredictiveContacts(btScalar timeStep) {
    sweep([&] { btDiscreteDynamicsWorld::createPredictiveContacts(timeStep); });
    for (int m = 0; m < m_predictiveManifolds.size(); ++m) {
        btPersistentManifold* manifold = m_predictiveManifolds[m];
        const btCollisionObject* body = manifold->getBody0();  // the swept body (Bullet's order)
        if (!body->getCollisionShape()->isConvex()) continue;
        const auto* shape = static_cast<const btConvexShape*>(body->getCollisionShape());
        const btTransform& pose = body->getWorldTransform();
        for (int i = 0; i < manifold->getNumContacts(); ++i) {
            btManifoldPoint& p = manifold->getContactPoint(i);
            const btVector3 towardHit = -p.m_normalWorldOnB;  // the normal points from the hit to the body
            const btVector3 support = pose * shape->localGetSupportingVertex(pose.getBasis().transpose() * towardHit);
            const btScalar reach = (support - pose.getOrigin()).dot(towardHit);
            p.m_positionWorldOnA = pose.getOrigin() + towardHit * reach;
            p.m_localPointA = pose.invXform(p.m_positionWorldOnA);
        }
    }
}

// Bullet's motion clamp stops a fast body at its first hit along the step and moves it there
// without its joints: in a falling pile of ragdolls, limbs stopped against each other opened
// their joints (the 10-ragdoll pile's worst gap over four nudged layouts 0.13 to 0.18 m; 0.04 to
// 0.07 without the clamp). A body held by an enabled joint keeps the predictive contacts of the
// same sweep, which the solver meets together with its joints, and skips the clamp.
// The clamp also sweeps against a kinematic body where it stands at the step's start, not where
// the step takes it: a box falling onto a platform going down at 2 m/s was stopped each step where
// the platform had been and hovered 2.3 cm above it for good, reported falling at 4 m/s. The
// predictive contacts, which the solver meets with the platform's velocity, stop a body at a
// moving kinematic one; the clamp leaves moving kinematic bodies out (their broad-phase group is
// emptied while it runs).
void AnyphysDynamicsWorld::integrateTransforms(btScalar timeStep) {
    hiddenKinematic_.clear();
    for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) {
        btRigidBody* body = m_nonStaticRigidBodies[i];
        if (!body->isKinematicObject()) continue;
        btBroadphaseProxy* proxy = body->getBroadphaseHandle();
        const bool moving = !body->getLinearVelocity().fuzzyZero() || !body->getAngularVelocity().fuzzyZero();
        if (!moving || !proxy) continue;
        hiddenKinematic_.emplace_back(proxy, proxy->m_collisionFilterGroup);
        proxy->m_collisionFilterGroup = 0;
    }
    unclamped_.clear();
    for (int i = 0; i < getNumConstraints(); ++i) {
        btTypedConstraint* c = getConstraint(i);
        if (!c->isEnabled()) continue;
        for (btRigidBody* body : {&c->getRigidBodyA(), &c->getRigidBodyB()})
            if (body->getCcdMotionThreshold() > 0) {  // once per body: the threshold is 0 from here
                unclamped_.emplace_back(body, body->getCcdMotionThreshold());
                body->setCcdMotionThreshold(0);
            }
    }
    sweep([&] { btDiscreteDynamicsWorld::integrateTransforms(timeStep); });
    for (const auto& [body, threshold] : unclamped_) body->setCcdMotionThreshold(threshold);
    for (const auto& [proxy, group] : hiddenKinematic_) proxy->m_collisionFilterGroup = group;
}

namespace {

// Bullet's internal-edge utility (btAdjustInternalEdgeContacts, with the edge angles ShapeSet
// stored for the mesh): near an edge shared with a flat or concave neighbour the normal becomes
// the triangle's own; near a convex one it is kept between the two faces' normals. The mesh is
// always body 1 (Bullet's convex-concave algorithm builds its manifold convex shape first), and
// the point's normal is on the triangle, as the utility expects. Two additions:
//  - The utility changes only points whose normal leans to the triangle's front (flags 0: the
//    layer's triangles face where they are counter-clockwise, and the back of a mesh keeps
//    Bullet's contacts). A body sunk a few mm meets the next triangle's edge side-on, with a
//    normal a hair behind the plane (a hull sliding at 5 m/s: (1, -0.002, 0)): while the body's
//    centre is in front, such a normal is mirrored to the front for the utility, and kept as it
//    was where the utility then changes nothing (no shared edge near).
//  - The utility keeps the depth measured along the old normal (a side-on hit's 0.6 mm where the
//    body is level with the face); the depth is measured again along the new normal, from the
//    old point on the triangle (on a flat or concave edge: the distance to the triangle's plane).
void correctMeshEdge(btManifoldPoint& p, const btCollisionObjectWrapper* obj0, const btCollisionObjectWrapper* obj1,
                     int partId1, int index1) {
    if (obj1->getCollisionShape()->getShapeType() != TRIANGLE_SHAPE_PROXYTYPE ||
        obj1->getCollisionObject()->getCollisionShape()->getShapeType() != TRIANGLE_MESH_SHAPE_PROXYTYPE)
        return;
    const btManifoldPoint found = p;
    btVector3 face;
    static_cast<const btTriangleShape*>(obj1->getCollisionShape())->calcNormal(face);
    face = obj1->getWorldTransform().getBasis() * face;
    const btVector3 triangleCorner =
        obj1->getWorldTransform() * static_cast<const btTriangleShape*>(obj1->getCollisionShape())->m_vertices1[0];
    const btScalar behind = p.m_normalWorldOnB.dot(face);
    const bool mirrored = behind < 0 && (obj0->getWorldTransform().getOrigin() - triangleCorner).dot(face) > 0;
    if (mirrored) p.m_normalWorldOnB -= 2 * behind * face;
    const btVector3 before = p.m_normalWorldOnB;
    btAdjustInternalEdgeContacts(p, obj1, obj0, partId1, index1);
    if (p.m_normalWorldOnB == before) {  // not near a shared edge, or already within its range
        p = found;
        return;
    }
    p.m_distance1 = (found.m_positionWorldOnA - found.m_positionWorldOnB).dot(p.m_normalWorldOnB);
    p.m_positionWorldOnB = p.m_positionWorldOnA - p.m_normalWorldOnB * p.m_distance1;
    p.m_localPointB = obj1->getWorldTransform().invXform(p.m_positionWorldOnB);
}

// Bullet calls this for every point the narrow phase adds or replaces, right after it wrote its
// own product of the two bodies' frictions into it, when one of the bodies has
// CF_CUSTOM_MATERIAL_CALLBACK (every anyphys body does). The point names its compound children
// (m_index0 / m_index1) and follows the manifold's body order, as obj0 and obj1 do.
// A point on a mesh triangle also gets its normal corrected near the edges the triangle shares
// with its neighbours (correctMeshEdge): Bullet collides the triangles one by one, and a body
// sliding across a flat mesh met the edges ahead as walls.
bool materialOnContactAdded(btManifoldPoint& p, const btCollisionObjectWrapper* obj0, int, int,
                            const btCollisionObjectWrapper* obj1, int partId1, int index1) {
    correctMeshEdge(p, obj0, obj1, partId1, index1);
    const auto* a = static_cast<const BulletBodyPeer*>(obj0->getCollisionObject()->getUserPointer());
    const auto* b = static_cast<const BulletBodyPeer*>(obj1->getCollisionObject()->getUserPointer());
    if (a != nullptr && b != nullptr) a->world().dynamicsWorld().writeMaterial(p, *a, *b);
    return false;  // ignored by Bullet
}

// Installed once for the process, unless someone else's callback is there: then every world
// writes all its points every step instead (applyMaterials).
void installMaterialCallback() {
    static const bool installed = [] {
        if (gContactAddedCallback == nullptr) gContactAddedCallback = &materialOnContactAdded;
        return true;
    }();
    (void)installed;
}

bool materialCallbackInstalled() { return gContactAddedCallback == &materialOnContactAdded; }

}  // namespace

AnyphysDynamicsWorld::AnyphysDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase,
                                           btConstraintSolver* solver, btCollisionConfiguration* configuration)
    : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration) {
    installMaterialCallback();
}

void AnyphysDynamicsWorld::setMaterials(const MaterialTable* table) {
    materials_ = table;
    setEffects(effects_);
}

void AnyphysDynamicsWorld::setEffects(Effects effects) {
    effects_ = effects;
    pointsStale_ = true;
    bouncing_ = false;
    if (materials_ != nullptr && effects.has(Effect::Restitution))
        for (const ContactMaterial& m : materials_->values) bouncing_ = bouncing_ || m.restitution > 0;
}

void AnyphysDynamicsWorld::writeMaterial(btManifoldPoint& p, const BulletBodyPeer& a, const BulletBodyPeer& b) const {
    // Per point: a compound child may carry its own material (the child indices say which).
    const ContactMaterial& mix = materials_->get(a.material(p.m_index0), b.material(p.m_index1));
    p.m_combinedFriction = effects_.has(Effect::Friction) ? static_cast<btScalar>(mix.friction) : btScalar(0);
    // Below the restitution threshold Bullet's solver uses 0.
    p.m_combinedRestitution = effects_.has(Effect::Restitution) ? static_cast<btScalar>(mix.restitution) : btScalar(0);
    p.m_combinedRollingFriction = 0;
    p.m_combinedSpinningFriction = 0;
}

// Bullet writes its own product into a point whenever the narrow phase adds or replaces it; the
// callback above overwrites it at once. Points Bullet keeps hold the values until the table or
// the effects change. Continuous collision's predictive points bypass the callback (made anew
// every step), and so do all points while another contact-added callback is installed.
void AnyphysDynamicsWorld::applyMaterials() {
    if (materials_ == nullptr) return;
    if (bouncing_ || pointsStale_ || !materialCallbackInstalled()) {
        btDispatcher* dispatcher = getDispatcher();
        writeMaterials(dispatcher->getInternalManifoldPointer(), dispatcher->getNumManifolds(), bouncing_);
        pointsStale_ = false;
    } else if (m_predictiveManifolds.size() > 0) {
        writeMaterials(&m_predictiveManifolds[0], m_predictiveManifolds.size(), false);
    }
}

void AnyphysDynamicsWorld::writeMaterials(btPersistentManifold* const* manifolds, int count, bool bouncing) {
    for (int m = 0; m < count; ++m) {
        btPersistentManifold* manifold = manifolds[m];
        const int points = manifold->getNumContacts();
        if (points == 0) continue;
        const auto* a = static_cast<const BulletBodyPeer*>(manifold->getBody0()->getUserPointer());
        const auto* b = static_cast<const BulletBodyPeer*>(manifold->getBody1()->getUserPointer());
        if (a == nullptr || b == nullptr) continue;
        const auto* bodyA = btRigidBody::upcast(manifold->getBody0());
        const auto* bodyB = btRigidBody::upcast(manifold->getBody1());
        for (int i = 0; i < points; ++i) {
            btManifoldPoint& p = manifold->getContactPoint(i);
            writeMaterial(p, *a, *b);
            if (bouncing) {
                judgeImpact(p, bodyA, bodyB);
            } else {
                p.m_contactPointFlags &= ~BT_CONTACT_FLAG_HAS_CONTACT_ERP;  // a bounce's, from before the change
            }
        }
    }
}

// An impact that bounces gets no Baumgarte push-out: the push would add to the rebound (+0.3 m/s
// for a ball landing at 6 m/s, +15 % height at e = 0.5); the overlap goes as the bodies separate.
// Nor does a rebound under way, separating faster than the restitution threshold: split impulse
// would push it out of the overlap it leaves on its own (a ball with e = 0.2 landing at 5.3 m/s,
// still 5 cm deep a step after its bounce, rose 18 % high). Resting and sliding contacts keep the
// push.
void AnyphysDynamicsWorld::judgeImpact(btManifoldPoint& p, const btRigidBody* bodyA, const btRigidBody* bodyB) const {
    bool bouncing = false, leaving = false;
    if (p.m_combinedRestitution > 0 && bodyA != nullptr && bodyB != nullptr) {
        const btVector3 va = bodyA->getVelocityInLocalPoint(p.getPositionWorldOnA() - bodyA->getCenterOfMassPosition());
        const btVector3 vb = bodyB->getVelocityInLocalPoint(p.getPositionWorldOnB() - bodyB->getCenterOfMassPosition());
        const btScalar closing = -(va - vb).dot(p.m_normalWorldOnB);
        bouncing = closing > restitutionThreshold_;
        leaving = closing < -restitutionThreshold_;
        // A speculative point (still apart by d): Bullet would let the bodies close the gap this
        // step and take d / dt off the rebound, so an impact that falls early in a step rebounds
        // at a fraction of e v. A gap this step closes bounces now, as if touching; a gap it does
        // not close waits for a later step without restitution.
        const btScalar gap = p.getDistance();
        if (bouncing && gap > 0) {
            if (gap < closing * timeStep_) {
                p.m_distance1 = 0;
            } else {
                p.m_combinedRestitution = 0;
                bouncing = false;
            }
        }
        // Bullet bounces at e times the closing speed from where it finds the pair, mostly in
        // the ground by up to a step's fall: the rebound is aimed at what a bounce at the instant
        // of contact would reach (reboundFromDepth), through the point's restitution.
        if (bouncing) {
            // Only bodies falling freely: a box resting on the ground does not fall with the ball.
            const auto fall = [](const btRigidBody* body) {
                const auto* peer = static_cast<const BulletBodyPeer*>(body->getUserPointer());
                return peer != nullptr && peer->fellLastStep() ? body->getGravity() : btVector3(0, 0, 0);
            };
            const btScalar g = -(fall(bodyA) - fall(bodyB)).dot(p.m_normalWorldOnB);
            const double leave = restitution::reboundFromDepth(p.m_combinedRestitution, closing, -gap, g, timeStep_);
            p.m_combinedRestitution = static_cast<btScalar>(leave / closing);
        }
    }
    if (bouncing || leaving) {
        p.m_contactPointFlags |= BT_CONTACT_FLAG_HAS_CONTACT_ERP;
        p.m_contactERP = 0;
    } else {
        p.m_contactPointFlags &= ~BT_CONTACT_FLAG_HAS_CONTACT_ERP;
    }
}

void AnyphysDynamicsWorld::solveConstraints(btContactSolverInfo& solverInfo) {
    timeStep_ = solverInfo.m_timeStep;
    applyMaterials();
    btDiscreteDynamicsWorld::solveConstraints(solverInfo);
}

// Bullet's own version with one change: a body wants to sleep after resting timeToSleep in this
// world (Bullet compares with the global gDeactivationTime). The island manager then puts an
// island to sleep once all its bodies want to, and wakes it together.
void AnyphysDynamicsWorld::updateActivationState(btScalar timeStep) {
    const bool sleeping = effects_.has(Effect::Sleeping);
    awakeBodies_ = 0;  // counted on the way: the last word on sleep in a step is here
    for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) {
        btRigidBody* body = m_nonStaticRigidBodies[i];
        if (body->isKinematicObject()) {  // moved by anyphys, never put to sleep here
            if (body->isActive()) ++awakeBodies_;
            continue;
        }
        body->updateDeactivation(timeStep);  // accumulates rest time under the thresholds
        const int state = body->getActivationState();
        if (state == DISABLE_DEACTIVATION || state == ISLAND_SLEEPING) {
            if (state == ISLAND_SLEEPING) {
                body->setLinearVelocity(btVector3(0, 0, 0));
                body->setAngularVelocity(btVector3(0, 0, 0));
            } else {
                ++awakeBodies_;
            }
            continue;
        }
        ++awakeBodies_;
        if (sleeping && body->getDeactivationTime() >= timeToSleep_)
            body->setActivationState(WANTS_DEACTIVATION);
        else
            body->setActivationState(ACTIVE_TAG);
    }
}

}  // namespace anyphys::bullet

#include "box2d_joints.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <string>

#include "anyphys/error.hpp"
#include "box2d_world.hpp"

namespace anyphys::box2d {
namespace {

// Frames arrive validated by the layer (axes within 1e-4 of Z or of the plane); this only
// refuses what the plane cannot hold at all, for peers used without the layer.
constexpr double kAxisTolerance = 1e-3;

bool alongZ(const Vec3& v) { return std::hypot(v.x(), v.y()) <= kAxisTolerance * v.norm(); }
bool inPlane(const Vec3& v) { return std::abs(v.z()) <= kAxisTolerance * v.norm(); }

// Box2D's soft springs (weld, wheel, distance) switch off at stiffness 0 (a weld even turns
// rigid): a damper without stiffness gets a stiffness too small to pull (1e-20 N/m or N m/rad
// moves nothing in a lifetime) so its damping acts.
float springStiffness(const JointSpringSI& s) { return std::max(static_cast<float>(s.stiffness), 1e-20f); }

// A soft spring (its stiffness applied here, explicitly) while k h^2 K times the sprung joints on
// the busier body stays under this: the rule of the native and ODE joints, well inside symplectic
// Euler's stable range (omega h)^2 < 4 (its swing's extremes are then at most 7 % wide), and
// shared by the springs of one body (several soft springs on one light body diverge together).
// The damping stays Box2D's, implicit, so it does not enter the test.
constexpr double kExplicitSpringLimit = 0.5;

// A Box2D body's inverse mass and inverse moment about its centre (0: static, kinematic, or a
// fixed rotation). b2Body::GetInertia is about the body origin.
double inverseMass(const b2Body& b) { return b.GetType() == b2_dynamicBody && b.GetMass() > 0.0f ? 1.0 / b.GetMass() : 0.0; }
double inverseInertia(const b2Body& b) {
    if (b.GetType() != b2_dynamicBody) return 0.0;
    const b2Vec2 c = b.GetLocalCenter();
    const double central = static_cast<double>(b.GetInertia()) - static_cast<double>(b.GetMass()) * b2Dot(c, c);
    return central > 0.0 ? 1.0 / central : 0.0;
}

// A hinge's spring row (wB - wA) with its pin acting: the Schur complement of the row against the
// pin's two point rows at `pin`, K = K_ss - K_sp K_pp^-1 K_ps, and the row's rate once the pin has
// taken the substep's gravity and forces, v = J_s v0 - K_sp K_pp^-1 J_p v0 (v0: the velocities
// after them). A body on an arm turns about the pin, far heavier than about its centre (a box on
// a 1 m arm: 150 times), and a load on the arm winds the spring through the pin. `peerA`,
// `peerB`: the layer's bodies (null: the ground), whose step forces Box2D holds privately.
struct PinnedTurn {
    double inverseInertia = 0.0;
    double rate = 0.0;
};

PinnedTurn pinnedTurn(const b2Body& a, const Box2dBody* peerA, const b2Body& b, const Box2dBody* peerB, const b2Vec2& pin,
                      double h) {
    const double ma = inverseMass(a), mb = inverseMass(b), ia = inverseInertia(a), ib = inverseInertia(b);
    const b2Vec2 ra = pin - a.GetWorldCenter(), rb = pin - b.GetWorldCenter();
    const b2Vec2 g = b.GetWorld()->GetGravity();
    // Velocities after the substep's gravity and forces: linear at the body's point at the pin,
    // and angular.
    struct Moving {
        std::array<double, 2> point;
        double w;
    };
    const auto moving = [&](const b2Body& body, const Box2dBody* peer, const b2Vec2& r, double invMass, double invI) {
        const bool pushed = body.GetType() == b2_dynamicBody && body.IsAwake();
        const b2Vec2 f = pushed && peer ? peer->stepForce() : b2Vec2(0.0f, 0.0f);
        const double scale = pushed ? h * body.GetGravityScale() : 0.0;
        const double w = body.GetAngularVelocity() + (pushed && peer ? h * invI * peer->stepTorque() : 0.0);
        const b2Vec2 v = body.GetLinearVelocity();
        return Moving{{v.x + scale * g.x + h * invMass * f.x - w * r.y, v.y + scale * g.y + h * invMass * f.y + w * r.x}, w};
    };
    const Moving movingB = moving(b, peerB, rb, mb, ib), movingA = moving(a, peerA, ra, ma, ia);
    const std::array<double, 2>& vb = movingB.point;
    const std::array<double, 2>& va = movingA.point;
    // Each point row's angular coefficients: B's r x e_i, A's -(r x e_i).
    const double armB[2] = {-rb.y, rb.x}, armA[2] = {-ra.y, ra.x};
    double ksp[2], kpp[2][2], pinRate[2];
    for (int i = 0; i < 2; ++i) {
        ksp[i] = ib * armB[i] + ia * armA[i];
        for (int j = 0; j < 2; ++j) kpp[i][j] = (i == j ? ma + mb : 0.0) + ib * armB[i] * armB[j] + ia * armA[i] * armA[j];
        pinRate[i] = vb[i] - va[i];
    }
    PinnedTurn turn{ia + ib, movingB.w - movingA.w};
    const double det = kpp[0][0] * kpp[1][1] - kpp[0][1] * kpp[1][0];
    if (!(det > 1e-12 * (kpp[0][0] * kpp[1][1]))) return turn;  // the pin holds nothing that moves
    const double x0 = (kpp[1][1] * ksp[0] - kpp[0][1] * ksp[1]) / det;
    const double x1 = (kpp[0][0] * ksp[1] - kpp[1][0] * ksp[0]) / det;
    turn.inverseInertia = std::clamp(turn.inverseInertia - (ksp[0] * x0 + ksp[1] * x1), 0.0, turn.inverseInertia);
    turn.rate -= x0 * pinRate[0] + x1 * pinRate[1];
    return turn;
}

// Box2D's distance range for the peer's definition: a rigid rod without minLength / maxLength
// (soft with a spring, free beyond the spring's pull), else the range (Box2D clamps the lower
// end to b2_linearSlop).
void distanceRange(const JointPeerDef& d, float& lower, float& upper) {
    if (!d.minLength && !d.maxLength) {
        lower = d.spring ? 0.0f : static_cast<float>(d.length);
        upper = d.spring ? FLT_MAX : static_cast<float>(d.length);
        return;
    }
    lower = static_cast<float>(d.minLength.value_or(0.0));
    upper = d.maxLength ? static_cast<float>(*d.maxLength) : FLT_MAX;
}

// A planar vector of X (in the XY plane) in a frame, normalised.
b2Vec2 planarX(const Quat& frame) {
    const Vec3 x = frame * Vec3::UnitX();
    b2Vec2 v(static_cast<float>(x.x()), static_cast<float>(x.y()));
    v.Normalize();
    return v;
}

}  // namespace

Box2dJoint::Box2dJoint(Box2dWorld& world, const JointPeerDef& def, b2Body* ground)
    : world_(&world),
      def_(def),
      a_(static_cast<Box2dBody*>(def.bodyA)),
      b_(static_cast<Box2dBody*>(def.bodyB)),
      ground_(ground) {
    if (!b_) throw Error(ErrorKind::Internal, "JointPeerDef.bodyB", "JointPeerDef.bodyB: is required, got null");
    // The joint frames on the Box2D bodies (A's is in the world when A is the world; the ground
    // body sits at the origin with angle 0, so world and ground coordinates agree).
    const Transform frameA = a_ ? a_->embedding().toBody(def.frameA) : def.frameA;
    const Transform frameB = b_->embedding().toBody(def.frameB);
    const Vec3 x = frameA.orientation * Vec3::UnitX();
    const Vec3 y = frameA.orientation * Vec3::UnitY();
    switch (def.type) {
        case JointType::Cone:
            throw Error(ErrorKind::Unsupported, "JointPeerDef.type", "JointPeerDef.type: box2d has no cone joint (its swing cone leaves the plane), got cone");
        case JointType::Hinge:
            if (!alongZ(x))
                throw Error(ErrorKind::Unsupported, "JointPeerDef.frameA", "JointPeerDef.frameA: a hinge axis (frame X) must be along Z in the plane (box2d)");
            sign_ = x.z() > 0 ? 1.0 : -1.0;
            break;
        case JointType::Ball:  // turns about Z only in the plane: a hinge about Z
            sign_ = 1.0;
            ballAxisZ_ = std::clamp(x.z() / x.norm(), -1.0, 1.0);
            break;
        case JointType::Slider:
        case JointType::Wheel:
            if (!inPlane(x))
                throw Error(ErrorKind::Unsupported, "JointPeerDef.frameA", "JointPeerDef.frameA: a slider or wheel axis (frame X) must lie in the XY plane (box2d)");
            localAxisA_ = planarX(frameA.orientation);
            if (def.type == JointType::Wheel) {
                if (!alongZ(y)) throw Error(ErrorKind::Unsupported, "JointPeerDef.frameA", "JointPeerDef.frameA: a wheel axle (frame Y) must be along Z (box2d)");
                sign_ = y.z() > 0 ? 1.0 : -1.0;
            }
            break;
        case JointType::Fixed:
        case JointType::Distance: break;
    }
    if (def.type == JointType::Distance) {
        const Vec3 anchorA = a_ ? a_->embedding().toBody({def.anchorA, Quat::Identity()}).position : def.anchorA;
        localAnchorA_ = toB2(anchorA);
        localAnchorB_ = toB2(b_->embedding().toBody({def.anchorB, Quat::Identity()}).position);
    } else {
        localAnchorA_ = toB2(frameA.position);
        localAnchorB_ = toB2(frameB.position);
    }
    // Frames coincide at creation: Box2D's angles count from the bodies' angles now.
    referenceAngle_ = bodyB()->GetAngle() - bodyA()->GetAngle();
}

Box2dJoint::~Box2dJoint() {
    if (world_) world_->forgetJoint(*this);
}

b2Body* Box2dJoint::bodyA() const { return a_ ? a_->b2() : ground_; }

void Box2dJoint::enable(b2World& world, bool on) {
    if (on == (joint_ != nullptr)) return;
    explicitSpring_ = false;  // a new Box2D joint holds the whole spring until the step chooses
    if (!on) {
        if (spring_) world.DestroyJoint(spring_);
        spring_ = nullptr;
        world.DestroyJoint(joint_);  // wakes both bodies
        joint_ = nullptr;
        return;
    }
    const auto common = [&](b2JointDef& jd) {
        jd.bodyA = bodyA();
        jd.bodyB = bodyB();
        jd.collideConnected = def_.collideConnected;
        jd.userData.pointer = reinterpret_cast<uintptr_t>(this);
    };
    const float sign = static_cast<float>(sign_);
    switch (def_.type) {
        case JointType::Fixed: {
            b2WeldJointDef jd;
            common(jd);
            jd.localAnchorA = localAnchorA_;
            jd.localAnchorB = localAnchorB_;
            jd.referenceAngle = referenceAngle_;
            joint_ = world.CreateJoint(&jd);
            break;
        }
        case JointType::Ball:
        case JointType::Hinge: {
            b2RevoluteJointDef jd;
            common(jd);
            jd.localAnchorA = localAnchorA_;
            jd.localAnchorB = localAnchorB_;
            jd.referenceAngle = referenceAngle_;
            if (def_.limits) {
                jd.enableLimit = true;
                jd.lowerAngle = static_cast<float>(sign_ > 0 ? def_.limits->lower : -def_.limits->upper);
                jd.upperAngle = static_cast<float>(sign_ > 0 ? def_.limits->upper : -def_.limits->lower);
            }
            if (def_.motor) {
                jd.enableMotor = true;
                jd.motorSpeed = sign * static_cast<float>(def_.motor->speed);
                jd.maxMotorTorque = static_cast<float>(def_.motor->maxForce);
            }
            joint_ = world.CreateJoint(&jd);
            break;
        }
        case JointType::Slider: {
            b2PrismaticJointDef jd;
            common(jd);
            jd.localAnchorA = localAnchorA_;
            jd.localAnchorB = localAnchorB_;
            jd.localAxisA = localAxisA_;
            jd.referenceAngle = referenceAngle_;
            if (def_.limits) {
                jd.enableLimit = true;
                jd.lowerTranslation = static_cast<float>(def_.limits->lower);
                jd.upperTranslation = static_cast<float>(def_.limits->upper);
            }
            if (def_.motor) {
                jd.enableMotor = true;
                jd.motorSpeed = static_cast<float>(def_.motor->speed);
                jd.maxMotorForce = static_cast<float>(def_.motor->maxForce);
            }
            joint_ = world.CreateJoint(&jd);
            break;
        }
        case JointType::Wheel: {
            b2WheelJointDef jd;
            common(jd);
            jd.localAnchorA = localAnchorA_;
            jd.localAnchorB = localAnchorB_;
            jd.localAxisA = localAxisA_;
            if (def_.limits) {
                jd.enableLimit = true;
                jd.lowerTranslation = static_cast<float>(def_.limits->lower);
                jd.upperTranslation = static_cast<float>(def_.limits->upper);
            }
            if (def_.motor) {
                jd.enableMotor = true;
                jd.motorSpeed = sign * static_cast<float>(def_.motor->speed);
                jd.maxMotorTorque = static_cast<float>(def_.motor->maxForce);
            }
            if (def_.spring) {
                jd.stiffness = springStiffness(*def_.spring);
                jd.damping = static_cast<float>(def_.spring->damping);
            }
            joint_ = world.CreateJoint(&jd);
            break;
        }
        case JointType::Distance: {
            b2DistanceJointDef jd;
            common(jd);
            jd.localAnchorA = localAnchorA_;
            jd.localAnchorB = localAnchorB_;
            jd.length = static_cast<float>(def_.length);
            distanceRange(def_, jd.minLength, jd.maxLength);
            if (def_.spring) {
                jd.stiffness = springStiffness(*def_.spring);
                jd.damping = static_cast<float>(def_.spring->damping);
            }
            joint_ = world.CreateJoint(&jd);
            break;
        }
        case JointType::Cone: break;  // refused in the constructor
    }
    if (def_.spring && springJoint()) spring_ = makeSpring(world);
    wake();
}

// Box2D 2.4's prismatic joint has no spring. Its wheel joint has one along an axis (the line
// held, what the prismatic joint holds anyway), so a sprung slider is two Box2D joints on the same
// anchors: the spring is solved in Box2D's solver, implicitly (a soft constraint), with gravity and
// contacts, like its own wheel and distance springs; a soft one keeps only its damping there and
// its stiffness is applied explicitly (beginStep, beforeSubstep). A hinge's spring is applied
// here whole (hingeSpringImpulse).
b2Joint* Box2dJoint::makeSpring(b2World& world) const {
    b2WheelJointDef jd;
    jd.bodyA = bodyA();
    jd.bodyB = bodyB();
    jd.collideConnected = def_.collideConnected;  // both must allow it for contacts
    jd.userData.pointer = reinterpret_cast<uintptr_t>(this);
    jd.localAnchorA = localAnchorA_;
    jd.localAnchorB = localAnchorB_;
    jd.localAxisA = localAxisA_;
    jd.stiffness = springStiffness(*def_.spring);
    jd.damping = static_cast<float>(def_.spring->damping);
    return world.CreateJoint(&jd);
}

void Box2dJoint::wake() {
    // A joint is a constraint between both bodies: a change must reach a sleeping pair (Box2D
    // keeps a joined pair in one island, so they sleep and wake together from then on).
    bodyA()->SetAwake(true);  // no-op on static bodies
    bodyB()->SetAwake(true);
}

// ---- what the joint reports ------------------------------------------------------------------

double Box2dJoint::position() const {
    if (!world_) return 0.0;
    const b2Body* a = bodyA();
    const b2Body* b = bodyB();
    switch (def_.type) {
        case JointType::Hinge:
            // Box2D's angles are not wrapped: the angle runs past +-pi.
            return sign_ * (static_cast<double>(b->GetAngle()) - a->GetAngle() - referenceAngle_);
        case JointType::Ball: {
            // The swing between the frames' X axes, as every backend reports a ball. The planar
            // ball the layer sends has X along Z (no swing); a peer given X in the plane swings
            // by the relative turn.
            const double turn = static_cast<double>(b->GetAngle()) - a->GetAngle() - referenceAngle_;
            const double z2 = ballAxisZ_ * ballAxisZ_;
            return std::acos(std::clamp(z2 + (1.0 - z2) * std::cos(turn), -1.0, 1.0));
        }
        case JointType::Slider:
        case JointType::Wheel: return b2Dot(anchorB() - anchorA(), axis());
        case JointType::Distance: return static_cast<double>((anchorB() - anchorA()).Length()) - def_.length;
        case JointType::Fixed:
        case JointType::Cone: break;
    }
    return 0.0;
}

double Box2dJoint::speed() const {
    if (!world_) return 0.0;
    const b2Body* a = bodyA();
    const b2Body* b = bodyB();
    const double relativeSpin = static_cast<double>(b->GetAngularVelocity()) - a->GetAngularVelocity();
    switch (def_.type) {
        case JointType::Hinge:
        case JointType::Wheel: return sign_ * relativeSpin;  // about frame X (hinge), frame Y (wheel axle)
        case JointType::Ball: {
            // d/dt acos(c) with c = z^2 + p^2 cos(turn): rate = p^2 sin(turn) turn' / sin(swing).
            const double turn = static_cast<double>(b->GetAngle()) - a->GetAngle() - referenceAngle_;
            const double p2 = 1.0 - ballAxisZ_ * ballAxisZ_;
            const double swingSine = std::sin(position());
            return swingSine > 1e-9 ? p2 * std::sin(turn) * relativeSpin / swingSine : 0.0;
        }
        case JointType::Slider: {
            // d/dt (d . x) with x turning with A: B's anchor against A's material point under it.
            const b2Vec2 p = anchorB();
            return b2Dot(b->GetLinearVelocityFromWorldPoint(p) - a->GetLinearVelocityFromWorldPoint(p), axis());
        }
        case JointType::Distance: {
            const b2Vec2 pa = anchorA(), pb = anchorB();
            b2Vec2 u = pb - pa;
            if (u.Normalize() < 1e-9f) return 0.0;
            return b2Dot(b->GetLinearVelocityFromWorldPoint(pb) - a->GetLinearVelocityFromWorldPoint(pa), u);
        }
        case JointType::Fixed:
        case JointType::Cone: break;
    }
    return 0.0;
}

// ---- changes ---------------------------------------------------------------------------------

void Box2dJoint::setMotor(const std::optional<JointMotor>& motor) {
    def_.motor = motor;
    applyMotor();
}

void Box2dJoint::setLimits(const std::optional<JointLimits>& limits) {
    def_.limits = limits;
    applyLimits();
}

void Box2dJoint::setSpring(const std::optional<JointSpringSI>& spring) {
    def_.spring = spring;
    applySpring();
}

void Box2dJoint::applyMotor() {
    if (!joint_) return;
    const bool on = def_.motor.has_value();
    const float speed = on ? static_cast<float>(def_.motor->speed) : 0.0f;
    const float most = on ? static_cast<float>(def_.motor->maxForce) : 0.0f;
    const float sign = static_cast<float>(sign_);
    switch (joint_->GetType()) {
        case e_revoluteJoint: {
            auto* j = static_cast<b2RevoluteJoint*>(joint_);
            j->SetMotorSpeed(sign * speed);
            j->SetMaxMotorTorque(most);
            j->EnableMotor(on);
            break;
        }
        case e_prismaticJoint: {
            auto* j = static_cast<b2PrismaticJoint*>(joint_);
            j->SetMotorSpeed(speed);
            j->SetMaxMotorForce(most);
            j->EnableMotor(on);
            break;
        }
        case e_wheelJoint: {
            auto* j = static_cast<b2WheelJoint*>(joint_);
            j->SetMotorSpeed(sign * speed);
            j->SetMaxMotorTorque(most);
            j->EnableMotor(on);
            break;
        }
        default: break;
    }
    wake();
}

void Box2dJoint::applyLimits() {
    if (!joint_) return;
    const bool on = def_.limits.has_value();
    const float lower = on ? static_cast<float>(def_.limits->lower) : 0.0f;
    const float upper = on ? static_cast<float>(def_.limits->upper) : 0.0f;
    switch (joint_->GetType()) {
        case e_revoluteJoint: {
            auto* j = static_cast<b2RevoluteJoint*>(joint_);
            if (sign_ > 0)
                j->SetLimits(lower, upper);
            else
                j->SetLimits(-upper, -lower);
            j->EnableLimit(on);
            break;
        }
        case e_prismaticJoint: {
            auto* j = static_cast<b2PrismaticJoint*>(joint_);
            j->SetLimits(lower, upper);
            j->EnableLimit(on);
            break;
        }
        case e_wheelJoint: {
            auto* j = static_cast<b2WheelJoint*>(joint_);
            j->SetLimits(lower, upper);
            j->EnableLimit(on);
            break;
        }
        default: break;
    }
    wake();
}

void Box2dJoint::applySpring() {
    if (!joint_) return;
    explicitSpring_ = false;  // Box2D holds the whole new spring until the next step chooses
    const float k = def_.spring ? springStiffness(*def_.spring) : 0.0f;
    const float c = def_.spring ? static_cast<float>(def_.spring->damping) : 0.0f;
    if (springJoint()) {  // slider: the spring's own joint comes and goes with it
        b2World& world = *bodyB()->GetWorld();
        if (spring_) world.DestroyJoint(spring_);
        spring_ = def_.spring ? makeSpring(world) : nullptr;
        wake();
        return;
    }
    switch (joint_->GetType()) {
        case e_wheelJoint: {
            auto* j = static_cast<b2WheelJoint*>(joint_);
            j->SetStiffness(k);
            j->SetDamping(c);
            break;
        }
        case e_distanceJoint: {
            auto* j = static_cast<b2DistanceJoint*>(joint_);
            j->SetStiffness(k);
            j->SetDamping(c);
            // With or without a spring a distance joint without a range changes between soft
            // and rigid: the range goes with it (set wide first, as Box2D clamps each end to
            // the other).
            float lower = 0.0f, upper = 0.0f;
            distanceRange(def_, lower, upper);
            j->SetMinLength(0.0f);
            j->SetMaxLength(upper);
            j->SetMinLength(lower);
            break;
        }
        default: break;
    }
    wake();
}

// ---- the step ----------------------------------------------------------------------------

bool Box2dJoint::sprung() const {
    if (!joint_ || !def_.spring) return false;
    switch (def_.type) {
        case JointType::Hinge:
        case JointType::Ball:
        case JointType::Slider:
        case JointType::Wheel: return true;
        case JointType::Distance: {  // a closed range is a rod: Box2D leaves the spring out
            float lower = 0.0f, upper = 0.0f;
            distanceRange(def_, lower, upper);
            return std::max(lower, b2_linearSlop) < upper;
        }
        case JointType::Fixed:
        case JointType::Cone: break;
    }
    return false;
}

b2Joint* Box2dJoint::springHolder() const {
    if (springJoint()) return spring_;
    return def_.type == JointType::Wheel || def_.type == JointType::Distance ? joint_ : nullptr;
}

void Box2dJoint::setImplicitStiffness(float stiffness) {
    b2Joint* j = springHolder();
    if (!j) return;
    switch (j->GetType()) {
        case e_wheelJoint: static_cast<b2WheelJoint*>(j)->SetStiffness(stiffness); break;
        case e_distanceJoint: static_cast<b2DistanceJoint*>(j)->SetStiffness(stiffness); break;
        default: break;
    }
}

// The spring's line of action now, as the Box2D joint that holds it sees it. Linear: it pulls
// B's point along `direction` and A's point the other way; angular: it turns B about +Z and A the
// other way. `stretch` is C (m or rad from rest, in Box2D's sense: a hinge's energy k C^2 / 2 is
// the same in the layer's sign_ C). `inverseMass` is K = J M^-1 J^T along it: a hinge's with the
// pin acting, the others' with both bodies free (the slider's line and the wheel's only lower the
// true K, so the soft test on it errs toward the implicit spring). `rate`: a hinge's, with the pin
// acting, after the substep's gravity and forces.
struct Box2dJoint::SpringAxis {
    bool angular = false;
    b2Vec2 direction{0.0f, 0.0f};
    b2Vec2 pointA{0.0f, 0.0f}, pointB{0.0f, 0.0f};
    double stretch = 0.0;
    double inverseMass = 0.0;
    double rate = 0.0;
};

bool Box2dJoint::springAxis(SpringAxis& out, double h) const {
    const b2Body& a = *bodyA();
    const b2Body& b = *bodyB();
    switch (def_.type) {
        case JointType::Hinge:
        case JointType::Ball: {  // the angle from the reference
            out.angular = true;
            out.stretch = static_cast<double>(b.GetAngle()) - a.GetAngle() - referenceAngle_;
            const PinnedTurn turn = pinnedTurn(a, a_, b, b_, anchorB(), h);
            out.inverseMass = turn.inverseInertia;
            out.rate = turn.rate;
            return true;
        }
        case JointType::Slider:
        case JointType::Wheel:
            // Along A's axis, at B's anchor on both bodies (A's material point under it), as the
            // wheel joint's spring row: its rate is what speed() reports.
            out.direction = axis();
            out.pointA = out.pointB = anchorB();
            out.stretch = b2Dot(anchorB() - anchorA(), out.direction);
            break;
        case JointType::Distance: {
            out.pointA = anchorA();
            out.pointB = anchorB();
            out.direction = out.pointB - out.pointA;
            const float length = out.direction.Normalize();
            if (length <= b2_linearSlop) return false;  // no line (Box2D drops its spring there too)
            out.stretch = static_cast<double>(length) - def_.length;
            break;
        }
        case JointType::Fixed:
        case JointType::Cone: return false;
    }
    const auto arm = [&](const b2Body& body, const b2Vec2& point) {
        return static_cast<double>(b2Cross(point - body.GetWorldCenter(), out.direction));
    };
    const double armA = arm(a, out.pointA), armB = arm(b, out.pointB);
    out.inverseMass = inverseMass(a) + inverseMass(b) + inverseInertia(a) * armA * armA + inverseInertia(b) * armB * armB;
    return true;
}

void Box2dJoint::beginStep(double h, int springsOnBusierBody) {
    impulse_ = {0.0, 0.0};
    angularImpulse_ = 0.0;
    if (!sprung()) return;
    const double k = def_.spring->stiffness, c = def_.spring->damping;
    SpringAxis line;
    const bool soft = springAxis(line, h) && k * h * h * line.inverseMass * springsOnBusierBody <= kExplicitSpringLimit;
    if (soft == explicitSpring_) return;
    explicitSpring_ = soft;
    // Soft: Box2D keeps only the damping (stiffness ~0, see springStiffness); stiff: all of it.
    // (A hinge's spring has no Box2D joint: hingeSpringImpulse.)
    setImplicitStiffness(springStiffness(soft ? JointSpringSI{0.0, c} : *def_.spring));
}

// A hinge's spring, all of it here, for the joint alone with its pin: P = -h (k C + (k' + c) v')
// with v' = v + K P the rate after it, k' = 0 where the stiffness is explicit (soft) and h k where
// it is implicit (backward Euler, stable at any stiffness). Box2D 2.4's revolute joint has no
// spring, and a soft weld solved beside it (this backend's earlier spring) does not carry the
// torque through the pin: a 3 700 N m/rad spring on a 2 kg box at 1 m spun it by 18 rad.
double Box2dJoint::hingeSpringImpulse(const SpringAxis& line, double h) const {
    const double k = def_.spring->stiffness, c = def_.spring->damping;
    const double rateFactor = (explicitSpring_ ? 0.0 : h * k) + c;
    return -h * (k * line.stretch + rateFactor * line.rate) / (1.0 + h * rateFactor * line.inverseMass);
}

void Box2dJoint::beforeSubstep(double h) {
    if (!sprung()) return;
    SpringAxis line;
    if (!springAxis(line, h)) return;
    if (!line.angular && !explicitSpring_) return;  // Box2D's joint holds the whole spring
    b2Body* a = bodyA();
    b2Body* b = bodyB();
    if (line.angular && !b->IsAwake() && !(a->GetType() == b2_dynamicBody && a->IsAwake())) {
        // Asleep, the pair is not stepped: the hinge reports the torque it last held (its rate
        // would leave out the load, which Box2D does not apply to sleeping bodies).
        angularImpulse_ += lastHingeImpulse_;
        return;
    }
    // The pull of the substep's start, on the velocities before Box2D's step: the step's solve
    // then sees it as it sees gravity. Sleeping and static bodies take nothing (wake = false).
    const double impulse = line.angular ? hingeSpringImpulse(line, h)
                                        : -h * def_.spring->stiffness * line.stretch;  // on B, along the spring
    const auto p = static_cast<float>(impulse);
    if (line.angular) {
        lastHingeImpulse_ = impulse;
        a->ApplyAngularImpulse(-p, false);
        b->ApplyAngularImpulse(p, false);
        angularImpulse_ += impulse;
        return;
    }
    a->ApplyLinearImpulse(-p * line.direction, line.pointA, false);
    b->ApplyLinearImpulse(p * line.direction, line.pointB, false);
    impulse_.x += impulse * line.direction.x;  // on B at B's anchor, as the reactions are
    impulse_.y += impulse * line.direction.y;
}

void Box2dJoint::afterSubstep() {
    // inv_dt = 1: the impulse of the Box2D step just taken (warm start included), applied to B
    // at B's anchor, and the angular impulse on B (so the torque is about B's anchor); the
    // spring's joint acts at the same anchor.
    for (const b2Joint* j : {joint_, spring_}) {
        if (!j) continue;
        const b2Vec2 impulse = j->GetReactionForce(1.0f);
        impulse_.x += impulse.x;
        impulse_.y += impulse.y;
        angularImpulse_ += j->GetReactionTorque(1.0f);
    }
}

void Box2dJoint::endStep(double dt) {
    reactionForce_ = Vec3(impulse_.x / dt, impulse_.y / dt, 0.0);
    reactionTorque_ = Vec3(0.0, 0.0, angularImpulse_ / dt);
}

void* Box2dJoint::nativeObject(const std::type_info& pointerType) {
    return pointerType == typeid(b2Joint*) ? static_cast<void*>(joint_) : nullptr;
}

}  // namespace anyphys::box2d

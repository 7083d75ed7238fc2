#include "ode_joints.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ode_joint_spring.hpp"
#include "ode_math.hpp"
#include "ode_tuning.hpp"
#include "ode_world.hpp"

namespace anyphys::ode {
namespace {

constexpr double kPi = std::numbers::pi;

// Angle in (-pi, pi].
double wrap(double angle) {
    angle = std::fmod(angle + kPi, 2.0 * kPi);
    if (angle <= 0.0) angle += 2.0 * kPi;
    return angle - kPi;
}

Transform compose(const Vec3& position, const Quat& orientation, const Transform& local) {
    return {position + orientation * local.position, (orientation * local.orientation).normalized()};
}

// ERP and CFM of a spring-damper row over an ODE step of h seconds (ODE manual): the row then
// behaves as an implicit spring of stiffness k and damping c. False when there is no spring.
bool springRow(const JointSpringSI& spring, double h, double& erp, double& cfm) {
    const double denominator = h * spring.stiffness + spring.damping;
    if (!(denominator > 0.0)) return false;
    erp = h * spring.stiffness / denominator;
    cfm = 1.0 / denominator;
    return true;
}

// Axes of the hinge's AMotors (user mode, every axis the hinge axis in the world), and of the
// slider's LMotor (motor and spring).
constexpr int kMotorAxis = 0;
constexpr int kSpringAxis = 1;
constexpr int kLowerAxis = 0;
constexpr int kUpperAxis = 1;
// Axes of the cone's AMotor.
constexpr int kSwingAxis = 0;
constexpr int kTwistLowerAxis = 1;
constexpr int kTwistUpperAxis = 2;

constexpr int group(int axis) { return axis * dParamGroup; }

// Declares AMotor axis `axis` a one-sided stop (lower: angle >= bound; upper: angle <= bound), or
// no stop at all.
void declareStop(dJointID motor, int axis, bool upper, bool present) {
    const double inf = dInfinity;
    dJointSetAMotorParam(motor, group(axis) + dParamLoStop, upper || !present ? -inf : 0.0);
    dJointSetAMotorParam(motor, group(axis) + dParamHiStop, !upper || !present ? inf : 0.0);
}

// Feeds a declared stop for the next ODE step. ODE's stop row is active when the angle it is
// given is past its stop value (0 here), with target rate -ERP/h (angle - stop). Fed |gap| past
// the stop: ahead of the bound (gap >= 0) with ERP -1, so the row lets the joint close at most
// the gap this step and pushes only if it would go further; past the bound with the world's ERP,
// so it pushes back like any ODE stop.
void feedStop(dJointID motor, int axis, bool upper, double angle, double bound, double erp) {
    const double gap = upper ? bound - angle : angle - bound;
    dJointSetAMotorParam(motor, group(axis) + dParamStopERP, gap >= 0.0 ? -1.0 : erp);
    dJointSetAMotorAngle(motor, axis, upper ? std::abs(gap) : -std::abs(gap));
}

// ODE's hinge2 acts its three point rows on body 1 at anchor 1 and on body 2 at anchor 2, both
// fixed in their bodies: once the suspension travels they part along the axis, and the rows
// across it push the bodies at two points, a couple on the pair (a free wheel sliding out on a
// turning pair gained 90x its angular momentum in 10 s). Placed every ODE step, anchor 1 is A's
// point at B's anchor and anchor 2 B's anchor: they part only by the drift to correct. ODE sets
// both from one world point, so body 2 is moved by their difference for the call.
void placeHinge2Anchors(dJointID joint, dBodyID body2, const Vec3& on1, const Vec3& on2) {
    const dReal* p = dBodyGetPosition(body2);
    const Vec3 held(p[0], p[1], p[2]);
    const Vec3 moved = held - (on2 - on1);
    dBodySetPosition(body2, moved.x(), moved.y(), moved.z());
    dJointSetHinge2Anchor(joint, on1.x(), on1.y(), on1.z());
    dBodySetPosition(body2, held.x(), held.y(), held.z());
}

// Placing the anchors makes ODE's angle 1 zero at the current pose, so the steering lock is fed
// its error each step: lo = hi = the angle 1 at which B's axle is at the steering angle (ODE's
// angle 1 is A's turn relative to B: the axle's error from A's steered axle, with its sign).
// The upper stop opens first so ODE never holds lo above hi.
void lockSteering(dJointID joint, const Transform& fa, const Transform& fb) {
    const Vec3 x = fa.orientation * Vec3::UnitX();
    const Vec3 yA = fa.orientation * Vec3::UnitY(), yB = fb.orientation * Vec3::UnitY();
    const double error = std::atan2(x.dot(yA.cross(yB)), yA.dot(yB));
    dJointSetHinge2Param(joint, dParamHiStop, dInfinity);
    dJointSetHinge2Param(joint, dParamLoStop, error);
    dJointSetHinge2Param(joint, dParamHiStop, error);
}

// A stiff (implicit) suspension spring is ODE's suspension row, whose target rate is
// ERP / h times the anchors' distance along the axis: they are kept this fraction of the travel
// apart, with the ERP scaled up by its inverse, so the row keeps its rate and its lever arms.
constexpr double kSuspensionGapShare = 1e-3;

// Without a spring a wheel's suspension is free: its row gets a CFM so large that it carries no
// force (1e9 m/N: a 1 kN load moves it at 1e-6 m/s).
constexpr double kFreeCfm = 1e9;

}  // namespace

OdeJoint::OdeJoint(OdeWorld& world, const JointPeerDef& def)
    : world_(world), def_(def), a_(static_cast<OdeBody*>(def.bodyA)), b_(static_cast<OdeBody*>(def.bodyB)) {
    const dWorldID w = world.id();
    // A static B (held by a dynamic A) has no dBody: a kinematic stand-in at its pose is body 1.
    idB_ = b_->id();
    if (!idB_) {
        bStandIn_ = standIn(b_->state());
        idB_ = bStandIn_;
    }
    const Transform fb = frameInB();
    const Vec3 anchor = fb.position;
    const Vec3 x = fb.orientation * Vec3::UnitX();
    switch (def_.type) {
        case JointType::Fixed:
            main_ = dJointCreateFixed(w, nullptr);
            attach(main_);
            dJointSetFixed(main_);
            dJointSetFixedParam(main_, dParamERP, kJointErp);
            addPart(main_, true);
            break;
        case JointType::Ball:
        case JointType::Cone:
            main_ = dJointCreateBall(w, nullptr);
            attach(main_);
            dJointSetBallAnchor(main_, anchor.x(), anchor.y(), anchor.z());
            dJointSetBallParam(main_, dParamERP, kJointErp);
            addPart(main_, true);
            if (def_.type == JointType::Cone) {
                amotor_ = dJointCreateAMotor(w, nullptr);
                attach(amotor_);
                dJointSetAMotorMode(amotor_, dAMotorUser);
                dJointSetAMotorNumAxes(amotor_, 3);
                for (int i = 0; i < 3; ++i) dJointSetAMotorAxis(amotor_, i, 0, x.x(), x.y(), x.z());
                addPart(amotor_, true);
                stopGroup_ = dJointGroupCreate(0);  // swing stop at B's centre (see centreStop)
            }
            break;
        case JointType::Hinge: {
            // A ball joint (its own ERP) and an AMotor whose two rows keep B's axis on A's: the
            // rows of ODE's hinge, with the joints' ERP instead of the world's (see kJointErp).
            main_ = dJointCreateBall(w, nullptr);
            attach(main_);
            dJointSetBallAnchor(main_, anchor.x(), anchor.y(), anchor.z());
            dJointSetBallParam(main_, dParamERP, kJointErp);
            addPart(main_, true);
            align_ = dJointCreateAMotor(w, nullptr);
            attach(align_);
            dJointSetAMotorMode(align_, dAMotorUser);
            dJointSetAMotorNumAxes(align_, 2);
            const Vec3 y = fb.orientation * Vec3::UnitY(), z = fb.orientation * Vec3::UnitZ();
            dJointSetAMotorAxis(align_, 0, 0, y.x(), y.y(), y.z());
            dJointSetAMotorAxis(align_, 1, 0, z.x(), z.y(), z.z());
            for (int i = 0; i < 2; ++i) {
                // lo = hi = 0: a two-sided row toward angle 0 at the stop's ERP.
                dJointSetAMotorParam(align_, group(i) + dParamLoStop, 0.0);
                dJointSetAMotorParam(align_, group(i) + dParamHiStop, 0.0);
                dJointSetAMotorParam(align_, group(i) + dParamStopERP, kJointErp);
                dJointSetAMotorParam(align_, group(i) + dParamStopCFM, world.cfm());
            }
            addPart(align_, true);
            amotor_ = dJointCreateAMotor(w, nullptr);
            stops_ = dJointCreateAMotor(w, nullptr);
            for (dJointID motor : {amotor_, stops_}) {
                attach(motor);
                dJointSetAMotorMode(motor, dAMotorUser);
                dJointSetAMotorNumAxes(motor, 2);
                for (int i = 0; i < 2; ++i) dJointSetAMotorAxis(motor, i, 0, x.x(), x.y(), x.z());
                addPart(motor, true);
            }
            stopGroup_ = dJointGroupCreate(0);  // stops at B's centre (see beforeOdeStep)
            break;
        }
        case JointType::Slider:
            main_ = dJointCreateSlider(w, nullptr);
            attach(main_);
            dJointSetSliderAxis(main_, x.x(), x.y(), x.z());
            addPart(main_, true);
            lmotor_ = dJointCreateLMotor(w, nullptr);
            attach(lmotor_);
            dJointSetLMotorNumAxes(lmotor_, 2);
            for (int i = 0; i < 2; ++i) dJointSetLMotorAxis(lmotor_, i, 0, x.x(), x.y(), x.z());
            addPart(lmotor_, true);
            stopGroup_ = dJointGroupCreate(0);  // the stops (limits may come later)
            break;
        case JointType::Distance: {
            main_ = dJointCreateDBall(w, nullptr);
            attach(main_);
            const Vec3 pa = anchorAWorld(), pb = anchorBWorld();
            dJointSetDBallAnchor1(main_, pb.x(), pb.y(), pb.z());
            dJointSetDBallAnchor2(main_, pa.x(), pa.y(), pa.z());
            dJointSetDBallDistance(main_, def_.length);
            addPart(main_, true);
            if (def_.minLength || def_.maxLength) stopGroup_ = dJointGroupCreate(0);
            break;
        }
        case JointType::Wheel: {
            // ODE's hinge2 is a car wheel: body 1 the chassis (axis 1, suspension and steering,
            // fixed in it), body 2 the wheel (axis 2, the axle). Held to the world, A is a
            // kinematic stand-in body (hinge2 needs a body 1).
            main_ = dJointCreateHinge2(w, nullptr);
            dBodyID chassis = a_ ? a_->id() : nullptr;
            if (!chassis) {
                anchorBody_ = standIn(stateA());
                chassis = anchorBody_;
            }
            dJointAttach(main_, chassis, idB_);
            dJointSetHinge2Anchor(main_, anchor.x(), anchor.y(), anchor.z());
            const Vec3 axle = fb.orientation * Vec3::UnitY();
            const dReal axis1[3] = {x.x(), x.y(), x.z()}, axis2[3] = {axle.x(), axle.y(), axle.z()};
            dJointSetHinge2Axes(main_, axis1, axis2);
            addPart(main_, false);
            stopGroup_ = dJointGroupCreate(0);  // suspension travel stops (limits may come later)
            break;
        }
    }
    enabled_ = world.effects().has(Effect::Joints);
    configureMotors();
    setEnabled(enabled_);
    wakeBodies();
}

OdeJoint::~OdeJoint() {
    for (std::size_t i = 0; i < partCount_; ++i) dJointDestroy(parts_[i].id);
    if (stopGroup_) dJointGroupDestroy(stopGroup_);
    if (anchorBody_) dBodyDestroy(anchorBody_);
    if (bStandIn_) dBodyDestroy(bStandIn_);
}

dBodyID OdeJoint::standIn(const BodyState& pose) const {
    // Kinematic: infinite mass to the solver, never moved. With ODE's auto-disable on (it is at
    // rest), so it sleeps with the island it is in instead of keeping the joined body awake.
    const dBodyID body = dBodyCreate(world_.id());
    dBodySetPosition(body, pose.position.x(), pose.position.y(), pose.position.z());
    dQuaternion q;
    toOde(pose.orientation, q);
    dBodySetQuaternion(body, q);
    dBodySetKinematic(body);
    dBodySetAutoDisableFlag(body, 1);
    return body;
}

void OdeJoint::attach(dJointID id) const {
    // B is body 1; A body 2, or the world (null) when A is the world or a static body.
    dJointAttach(id, idB_, a_ ? a_->id() : nullptr);
}

void OdeJoint::addPart(dJointID id, bool bIsBody1) {
    Part& part = parts_[partCount_++];
    part.id = id;
    part.bIsBody1 = bIsBody1;
    dJointSetFeedback(id, &part.feedback);
}

void OdeJoint::setEnabled(bool enabled) {
    enabled_ = enabled;
    for (std::size_t i = 0; i < partCount_; ++i) {
        if (enabled && (parts_[i].id != main_ || rod_))
            dJointEnable(parts_[i].id);
        else
            dJointDisable(parts_[i].id);
    }
}

void OdeJoint::wakeBodies() const {
    if (b_->id()) dBodyEnable(b_->id());
    if (a_ && a_->id()) dBodyEnable(a_->id());
}

void OdeJoint::configureMotors() {
    // What does not follow the bodies: motor speeds and limits. Rows without a value get no
    // force bound (fmax 0: no row) and open stops.
    switch (def_.type) {
        case JointType::Hinge:
            dJointSetAMotorParam(amotor_, group(kMotorAxis) + dParamVel, def_.motor ? def_.motor->speed : 0.0);
            dJointSetAMotorParam(amotor_, group(kMotorAxis) + dParamFMax, def_.motor ? def_.motor->maxForce : 0.0);
            if (!def_.spring) dJointSetAMotorParam(amotor_, group(kSpringAxis) + dParamFMax, 0.0);
            declareStop(stops_, kLowerAxis, false, def_.limits.has_value());
            declareStop(stops_, kUpperAxis, true, def_.limits.has_value());
            break;
        case JointType::Slider:
            dJointSetLMotorParam(lmotor_, group(kMotorAxis) + dParamVel, def_.motor ? def_.motor->speed : 0.0);
            dJointSetLMotorParam(lmotor_, group(kMotorAxis) + dParamFMax, def_.motor ? def_.motor->maxForce : 0.0);
            if (!def_.spring) dJointSetLMotorParam(lmotor_, group(kSpringAxis) + dParamFMax, 0.0);
            break;
        case JointType::Cone:
            declareStop(amotor_, kSwingAxis, true, def_.swingLimit < kPi);
            declareStop(amotor_, kTwistLowerAxis, false, def_.twistLimits.has_value());
            declareStop(amotor_, kTwistUpperAxis, true, def_.twistLimits.has_value());
            break;
        case JointType::Distance:
            if (!def_.spring) {
                dJointSetDBallParam(main_, dParamERP, kJointErp);
                dJointSetDBallParam(main_, dParamCFM, rowCfm());
            }
            // A range without a spring is free inside: the double ball is off.
            rod_ = def_.spring || !(def_.minLength || def_.maxLength);
            setEnabled(enabled_);
            break;
        case JointType::Wheel:
            // The spin motor on axis 2; ODE's rate there is w1 - w2 = A's spin relative to B.
            dJointSetHinge2Param(main_, dParamVel2, def_.motor ? -def_.motor->speed : 0.0);
            dJointSetHinge2Param(main_, dParamFMax2, def_.motor ? def_.motor->maxForce : 0.0);
            // Steering: axis 1 locked (a stop with lo = hi holds both ways), fed each ODE step
            // (lockSteering).
            break;
        case JointType::Fixed:
        case JointType::Ball:
            break;
    }
}

void OdeJoint::setMotor(const std::optional<JointMotor>& motor) {
    def_.motor = motor;
    configureMotors();
    wakeBodies();
}

void OdeJoint::setLimits(const std::optional<JointLimits>& limits) {
    def_.limits = limits;
    configureMotors();
    wakeBodies();
}

void OdeJoint::setSpring(const std::optional<JointSpringSI>& spring) {
    def_.spring = spring;
    configureMotors();
    wakeBodies();
}

void OdeJoint::setSteeringAngle(double angle) {
    steering_ = angle;
    configureMotors();
    wakeBodies();
}

void* OdeJoint::nativeObject(const std::type_info& pointerType) {
    if (pointerType == typeid(dxJoint*)) return main_;
    return nullptr;
}

// ---- geometry ---------------------------------------------------------------------------------

BodyState OdeJoint::stateA() const {
    if (a_) return a_->state();
    return {Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3::Zero()};
}

Transform OdeJoint::frameInA() const {
    const BodyState sa = stateA();
    Transform f = compose(sa.position, sa.orientation, def_.frameA);
    if (def_.type == JointType::Wheel && def_.steering)
        f.orientation = (f.orientation * Quat(Eigen::AngleAxisd(steering_, Vec3::UnitX()))).normalized();
    return f;
}

Transform OdeJoint::frameInB() const {
    const BodyState sb = b_->state();
    return compose(sb.position, sb.orientation, def_.frameB);
}

Vec3 OdeJoint::anchorAWorld() const {
    const BodyState sa = stateA();
    return sa.position + sa.orientation * (def_.type == JointType::Distance ? def_.anchorA : def_.frameA.position);
}

Vec3 OdeJoint::anchorBWorld() const {
    const BodyState sb = b_->state();
    return sb.position + sb.orientation * (def_.type == JointType::Distance ? def_.anchorB : def_.frameB.position);
}

double OdeJoint::twistAngle(const Transform& fa, const Transform& fb) const {
    const Quat rel = fa.orientation.conjugate() * fb.orientation;
    return wrap(2.0 * std::atan2(rel.x(), rel.w()));
}

double OdeJoint::hingeAngle(const Transform& fa, const Transform& fb) const {
    // Unwrapped: the turn nearest the last measurement, so the angle runs past +-pi.
    const double raw = twistAngle(fa, fb);
    return raw + 2.0 * kPi * std::round((lastAngle_ - raw) / (2.0 * kPi));
}

double OdeJoint::measurePosition() const {
    const Transform fa = frameInA(), fb = frameInB();
    const Vec3 x = fa.orientation * Vec3::UnitX();
    switch (def_.type) {
        case JointType::Hinge: return hingeAngle(fa, fb);
        case JointType::Slider:
        case JointType::Wheel: return (fb.position - fa.position).dot(x);
        case JointType::Distance: return (anchorBWorld() - anchorAWorld()).norm() - def_.length;
        case JointType::Ball:
        case JointType::Cone:
            return std::acos(std::clamp(x.dot(fb.orientation * Vec3::UnitX()), -1.0, 1.0));
        case JointType::Fixed: return 0.0;
    }
    return 0.0;
}

// ---- stepping ---------------------------------------------------------------------------------

double OdeJoint::pairMass() const { return heavierDynamicMass(a_, b_); }

double OdeJoint::rowWeightBound() const {
    return (a_ ? a_->rowWeightBound() : 0.0) + (b_ ? b_->rowWeightBound() : 0.0);
}

double OdeJoint::rowCfm() const {
    return conditionedCfm(pairCfm(world_.cfm(), pairMass()), world_.odeStep(), rowWeightBound());
}

void OdeJoint::applyRowCfm(double cfm) {
    // Each step, so a mass set after the joint's creation counts. For a pair of 1 t or less this
    // is the world's CFM, the value ODE gave these rows at creation: no change in its arithmetic.
    switch (def_.type) {
        case JointType::Fixed: dJointSetFixedParam(main_, dParamCFM, cfm); break;
        case JointType::Ball: dJointSetBallParam(main_, dParamCFM, cfm); break;
        case JointType::Cone:
            dJointSetBallParam(main_, dParamCFM, cfm);
            for (int i : {kSwingAxis, kTwistLowerAxis, kTwistUpperAxis})
                dJointSetAMotorParam(amotor_, group(i) + dParamStopCFM, cfm);
            break;
        case JointType::Hinge:
            dJointSetBallParam(main_, dParamCFM, cfm);
            for (int i = 0; i < 2; ++i) {
                dJointSetAMotorParam(align_, group(i) + dParamStopCFM, cfm);
                dJointSetAMotorParam(stops_, group(i) + dParamStopCFM, cfm);
            }
            dJointSetAMotorParam(amotor_, group(kMotorAxis) + dParamCFM, cfm);
            break;
        case JointType::Slider: dJointSetLMotorParam(lmotor_, group(kMotorAxis) + dParamCFM, cfm); break;
        case JointType::Distance:
            if (!def_.spring) dJointSetDBallParam(main_, dParamCFM, cfm);
            break;
        case JointType::Wheel:
            dJointSetHinge2Param(main_, dParamStopCFM, cfm);  // the steering lock
            dJointSetHinge2Param(main_, dParamCFM2, cfm);     // the spin motor
            break;
    }
}

// ODE takes back ERP x the gap per step as a velocity: a bob set 3 m off its hinge was flung back
// at 55 m/s, and the 40-link chain, whipping open by centimetres, was pulled back harder each
// step until its links flew at 1.7 km/s. Binds only where the gap exceeds kJointPushMaxVelocity x
// h / kJointErp (10 cm at 60 Hz): at rest and in a swing joints keep kJointErp.
void OdeJoint::capAnchorPull(const Transform& fa, const Transform& fb, double h) {
    const bool ball = def_.type == JointType::Ball || def_.type == JointType::Cone || def_.type == JointType::Hinge;
    if (!ball && def_.type != JointType::Fixed) return;
    const double gap = (fa.position - fb.position).norm();
    const double erp = gap * kJointErp > kJointPushMaxVelocity * h ? kJointPushMaxVelocity * h / gap : kJointErp;
    if (erp == anchorErp_) return;
    anchorErp_ = erp;
    if (ball) {
        dJointSetBallParam(main_, dParamERP, erp);
    } else {
        dJointSetFixedParam(main_, dParamERP, erp);
    }
}

void OdeJoint::beforeOdeStep(double h) {
    for (std::size_t i = 0; i < partCount_; ++i) parts_[i].feedback = dJointFeedback{};
    applyRowCfm(rowCfm());
    const Transform fa = frameInA(), fb = frameInB();
    capAnchorPull(fa, fb, h);
    const Vec3 x = fa.orientation * Vec3::UnitX();
    double erp = 0.0, cfm = 0.0;
    const bool spring = def_.spring && springRow(*def_.spring, h, erp, cfm);
    springPush_ = SpringPush{};
    // A soft spring's stiffness becomes a force of this ODE step; its row keeps the damping.
    const auto soften = [&](const SpringLine& line, double inverseMass) {
        const double k = def_.spring->stiffness;
        if (!springStepsExplicitly(k, h, inverseMass, springsOnBusierBody)) return;
        springPush_ = pushSpring(line, k, a_, b_);
        erp = 0.0;
        cfm = def_.spring->damping > 0.0 ? 1.0 / def_.spring->damping : kFreeCfm;
    };
    switch (def_.type) {
        case JointType::Hinge: {
            const double angle = hingeAngle(fa, fb);
            lastAngle_ = angle;
            {
                // Alignment: B's axis turned off A's by b = xA x xB; about A's Y and Z, the
                // components of b are the small angles to undo (each grows with (wB - wA) along it).
                const Vec3 y = fa.orientation * Vec3::UnitY(), z = fa.orientation * Vec3::UnitZ();
                const Vec3 bend = x.cross(fb.orientation * Vec3::UnitX());
                dJointSetAMotorAxis(align_, 0, 0, y.x(), y.y(), y.z());
                dJointSetAMotorAxis(align_, 1, 0, z.x(), z.y(), z.z());
                dJointSetAMotorAngle(align_, 0, bend.dot(y));
                dJointSetAMotorAngle(align_, 1, bend.dot(z));
            }
            for (dJointID motor : {amotor_, stops_})
                for (int i = 0; i < 2; ++i) dJointSetAMotorAxis(motor, i, 0, x.x(), x.y(), x.z());
            if (def_.limits) {
                // Where B swings on an arm, the stops act at its centre (see centreStop).
                Vec3 t;
                double lever = 0.0;
                const bool atCentre = centreStop(x, fb.position, t, lever);
                declareStop(stops_, kLowerAxis, false, !atCentre);
                declareStop(stops_, kUpperAxis, true, !atCentre);
                if (atCentre) {
                    const Vec3 centre = b_->state().position;
                    addStopRow(centre, -t, (def_.limits->upper - angle) * lever, h);
                    addStopRow(centre, t, (angle - def_.limits->lower) * lever, h);
                } else {
                    feedStop(stops_, kLowerAxis, false, angle, def_.limits->lower, world_.erp());
                    feedStop(stops_, kUpperAxis, true, angle, def_.limits->upper, world_.erp());
                }
            }
            if (spring) {
                soften({.axis = x, .angular = true, .stretch = angle}, hingeInverseInertia(x, fb.position, a_, b_));
                // A motor row whose target speed closes ERP of the error this step, softened by CFM.
                dJointSetAMotorParam(amotor_, group(kSpringAxis) + dParamVel, -erp / h * angle);
                dJointSetAMotorParam(amotor_, group(kSpringAxis) + dParamCFM, cfm);
                dJointSetAMotorParam(amotor_, group(kSpringAxis) + dParamFMax, dInfinity);
            }
            break;
        }
        case JointType::Slider: {
            for (int i = 0; i < 2; ++i) dJointSetLMotorAxis(lmotor_, i, 0, x.x(), x.y(), x.z());
            const double offset = (fb.position - fa.position).dot(x);
            if (def_.limits) {
                // Stops: one-sided speculative rows along the axis at B's anchor, as a wheel's.
                addStopRow(fb.position, -x, def_.limits->upper - offset, h);
                addStopRow(fb.position, x, offset - def_.limits->lower, h);
            }
            if (spring) {
                // The explicit force acts on both bodies at B's anchor: the offset is measured
                // there, so that is where -k C does its work, and one line of action for the
                // pair keeps its angular momentum (at the centres the pair of forces is a
                // couple that stops the pair turning). The LMotor's row (damping, or a stiff
                // spring) is consistent already: ODE acts it at the midpoint of the centres, on
                // one line for both bodies, and with their turn locked its rate is the anchor's.
                const SpringLine line{.axis = x, .atA = fb.position, .atB = fb.position, .stretch = offset};
                soften(line, inverseMassAlong(line, a_, b_));
                dJointSetLMotorParam(lmotor_, group(kSpringAxis) + dParamVel, -erp / h * offset);
                dJointSetLMotorParam(lmotor_, group(kSpringAxis) + dParamCFM, cfm);
                dJointSetLMotorParam(lmotor_, group(kSpringAxis) + dParamFMax, dInfinity);
            }
            break;
        }
        case JointType::Distance:
            if (spring) {
                const Vec3 pa = anchorAWorld(), pb = anchorBWorld();
                const double length = (pb - pa).norm();
                if (length > 1e-9) {  // else no line to push along: the row alone
                    const SpringLine line{.axis = (pb - pa) / length, .atA = pa, .atB = pb, .stretch = length - def_.length};
                    soften(line, inverseMassAlong(line, a_, b_));
                }
                dJointSetDBallParam(main_, dParamERP, erp);
                dJointSetDBallParam(main_, dParamCFM, cfm);
            }
            if (stopGroup_) ropeRows(h);
            break;
        case JointType::Cone: {
            // Swing: about n = xA x xB (the swing grows as B turns about n relative to A), the
            // angle between the X axes; twist: about A's X axis.
            const Vec3 xb = fb.orientation * Vec3::UnitX();
            const Vec3 bend = x.cross(xb);
            const double sine = bend.norm();
            const Vec3 n = sine > 1e-9 ? Vec3(bend / sine) : Vec3(fa.orientation * Vec3::UnitY());
            dJointSetAMotorAxis(amotor_, kSwingAxis, 0, n.x(), n.y(), n.z());
            if (def_.swingLimit < kPi) {
                const double swing = std::atan2(sine, x.dot(xb));
                Vec3 t;
                double lever = 0.0;
                const bool atCentre = centreStop(n, fb.position, t, lever);
                declareStop(amotor_, kSwingAxis, true, !atCentre);
                if (atCentre)
                    addStopRow(b_->state().position, -t, (def_.swingLimit - swing) * lever, h);
                else
                    feedStop(amotor_, kSwingAxis, true, swing, def_.swingLimit, world_.erp());
            }
            for (int i : {kTwistLowerAxis, kTwistUpperAxis}) dJointSetAMotorAxis(amotor_, i, 0, x.x(), x.y(), x.z());
            if (def_.twistLimits) {
                const double twist = twistAngle(fa, fb);
                feedStop(amotor_, kTwistLowerAxis, false, twist, def_.twistLimits->lower, world_.erp());
                feedStop(amotor_, kTwistUpperAxis, true, twist, def_.twistLimits->upper, world_.erp());
            }
            break;
        }
        case JointType::Wheel: {
            // Travel stops: the same one-sided rows as a rope's, along the suspension axis at B's
            // anchor (where the suspension acts on both bodies).
            const double travel = (fb.position - fa.position).dot(x);
            if (def_.limits) {
                addStopRow(fb.position, -x, def_.limits->upper - travel, h);
                addStopRow(fb.position, x, travel - def_.limits->lower, h);
            }
            if (spring) {
                const SpringLine line{.axis = x, .atA = fb.position, .atB = fb.position, .stretch = travel};
                soften(line, inverseMassAlong(line, a_, b_));
                dJointSetHinge2Param(main_, dParamSuspensionERP, erp / kSuspensionGapShare);
                dJointSetHinge2Param(main_, dParamSuspensionCFM, cfm);
            } else {
                erp = 0.0;
                dJointSetHinge2Param(main_, dParamSuspensionERP, 0.0);
                dJointSetHinge2Param(main_, dParamSuspensionCFM, kFreeCfm);
            }
            // With no stiffness in the row the anchors need not part along the axis at all.
            const double gap = erp > 0.0 ? kSuspensionGapShare * travel : 0.0;
            placeHinge2Anchors(main_, idB_, fa.position + (travel - gap) * x, fb.position);
            lockSteering(main_, fa, fb);
            break;
        }
        case JointType::Fixed:
        case JointType::Ball:
            break;
    }
}

bool OdeJoint::centreStop(const Vec3& axis, const Vec3& anchor, Vec3& t, double& lever) const {
    // An angular stop about `axis` through `anchor` can act at B's centre instead, along its
    // path: a one-sided row along t = axis x r (the way the centre moves as the angle grows),
    // the angular gap times the lever r. While the anchor holds, that row's rate is the angle's
    // rate times r, so it is the same stop; but it acts on B's mass rather than on its own
    // inertia, which quickstep converges far better where B swings on an arm (a 10 cm ball on a
    // 1 m arm: m r^2 / I = 250; measured on a hinge stop: 0.09 rad past it at 50 iterations as an
    // angular row, 0.0014 rad at the centre). Chosen when the orbit's m r^2 outweighs B's own
    // inertia about the axis; otherwise (a wheel turning about its centre) the angular row.
    const BodyState sb = b_->state();
    const MassProperties mp = b_->massProperties();
    const Vec3 r = sb.position - anchor;
    const Vec3 rPerp = r - r.dot(axis) * axis;
    lever = rPerp.norm();
    const Vec3 local = sb.orientation.conjugate() * axis;
    const double ownInertia = local.cwiseAbs2().dot(mp.inertia);
    if (!(mp.mass > 0.0 && mp.mass * lever * lever > ownInertia)) return false;
    t = axis.cross(rPerp) / lever;
    return true;
}

void OdeJoint::ropeRows(double h) {
    // maxLength pulls B toward A, minLength pushes it away; each is a frictionless ODE contact
    // at B's anchor with its normal along the line of the anchors. Its force acts along that
    // line, so the one contact point serves both bodies' lever arms exactly. Present every step
    // and speculative: ahead of the bound the contact's surface "moves" (dContactMotionN) so the
    // row lets the length close the remaining gap this step and acts only if it would go
    // further; past the bound, its depth is corrected with the world's ERP like a contact's.
    const Vec3 pa = anchorAWorld(), pb = anchorBWorld();
    const Vec3 d = pb - pa;
    const double length = d.norm();
    if (length < 1e-9) return;  // no direction to act along
    const Vec3 n = d / length;
    if (def_.maxLength) addStopRow(pb, -n, *def_.maxLength - length, h);
    if (def_.minLength) addStopRow(pb, n, length - *def_.minLength, h);
}

void OdeJoint::addStopRow(const Vec3& at, const Vec3& normal, double gap, double h) {
    dContact contact{};
    contact.surface.mode = dContactMotionN;  // frictionless (mu 0): the normal row only
    contact.surface.mu = 0.0;
    contact.surface.mode |= dContactSoftCFM;  // the joint's, not the world's (OdeWorld::step)
    contact.surface.soft_cfm = rowCfm();
    // ODE's row: B's speed along the normal relative to A >= ERP/h (depth - surface layer) + motionN.
    const double layer = dWorldGetContactSurfaceLayer(world_.id());
    contact.surface.motionN = gap > 0.0 ? -gap / h : 0.0;
    contact.geom.depth = (gap > 0.0 ? 0.0 : -gap) + layer;
    for (int k = 0; k < 3; ++k) {
        contact.geom.pos[k] = at[k];
        contact.geom.normal[k] = normal[k];  // ODE pushes body 1 (B) along the normal
    }
    const dJointID row = dJointCreateContact(world_.id(), stopGroup_, &contact);
    dJointAttach(row, idB_, a_ ? a_->id() : nullptr);
    stopFeedback_[stopRows_] = dJointFeedback{};
    dJointSetFeedback(row, &stopFeedback_[stopRows_++]);
}

void OdeJoint::afterOdeStep() {
    // ODE's feedback is the constraint force held over the step (N, N m about B's centre). A
    // joint between sleeping bodies was not stepped: it keeps the reactions it had.
    const bool awake = (b_->id() && dBodyIsEnabled(b_->id())) || (a_ && a_->id() && dBodyIsEnabled(a_->id()));
    if (stopGroup_) {
        if (awake)
            for (int i = 0; i < stopRows_; ++i) {
                sumForce_ += toVec3(stopFeedback_[i].f1);
                sumTorque_ += toVec3(stopFeedback_[i].t1);
            }
        dJointGroupEmpty(stopGroup_);
        stopRows_ = 0;
    }
    if (!awake || !enabled_) return;
    ++stepped_;
    sumForce_ += springPush_.force;
    sumTorque_ += springPush_.torque;
    for (std::size_t i = 0; i < partCount_; ++i) {
        const dJointFeedback& f = parts_[i].feedback;
        sumForce_ += parts_[i].bIsBody1 ? toVec3(f.f1) : toVec3(f.f2);
        sumTorque_ += parts_[i].bIsBody1 ? toVec3(f.t1) : toVec3(f.t2);
    }
}

void OdeJoint::finishStep(double dt, int substeps) {
    // Substeps are equal: the mean force over the step is the mean of theirs (a substep that
    // did not simulate the joint, all bodies asleep, counts as the others).
    const BodyState sa = stateA(), sb = b_->state();
    const Vec3 rB = anchorBWorld() - sb.position;
    if (stepped_ > 0 || !enabled_) {
        const double n = stepped_ > 0 ? stepped_ : substeps;
        const Vec3 force = sumForce_ / n, torqueAtCentre = sumTorque_ / n;
        reactionForce_ = force;
        reactionTorque_ = torqueAtCentre - rB.cross(force);  // about B's anchor
    }
    sumForce_.setZero();
    sumTorque_.setZero();
    stepped_ = 0;
    const Transform fa = frameInA(), fb = frameInB();
    const Vec3 x = fa.orientation * Vec3::UnitX();
    const Vec3 relW = sb.angularVelocity - sa.angularVelocity;
    const double previous = position_;
    switch (def_.type) {
        case JointType::Hinge:
            position_ = hingeAngle(fa, fb);
            lastAngle_ = position_;
            speed_ = relW.dot(x);
            break;
        case JointType::Slider: {
            const Vec3 d = fb.position - fa.position;
            position_ = d.dot(x);
            // d/dt (d . x) with x turning with A: B's anchor against A's point under it.
            const Vec3 vA = sa.linearVelocity + sa.angularVelocity.cross(fb.position - sa.position);
            const Vec3 vB = sb.linearVelocity + sb.angularVelocity.cross(rB);
            speed_ = (vB - vA).dot(x);
            break;
        }
        case JointType::Wheel:
            position_ = (fb.position - fa.position).dot(x);
            speed_ = relW.dot(fa.orientation * Vec3::UnitY());
            break;
        case JointType::Distance: {
            const Vec3 pa = anchorAWorld(), pb = anchorBWorld();
            const Vec3 d = pb - pa;
            const double length = d.norm();
            position_ = length - def_.length;
            const Vec3 vA = sa.linearVelocity + sa.angularVelocity.cross(pa - sa.position);
            const Vec3 vB = sb.linearVelocity + sb.angularVelocity.cross(rB);
            speed_ = length > 1e-12 ? (vB - vA).dot(d / length) : 0.0;
            break;
        }
        case JointType::Ball:
        case JointType::Cone:
            position_ = measurePosition();
            speed_ = (position_ - previous) / dt;
            break;
        case JointType::Fixed:
            position_ = speed_ = 0.0;
            break;
    }
}

}  // namespace anyphys::ode

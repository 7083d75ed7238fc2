#include "bullet_joints.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "anyphys/peers/joint_push.hpp"
#include "bullet_body.hpp"
#include "bullet_convert.hpp"
#include "bullet_joint_spring.hpp"
#include "bullet_world.hpp"

namespace anyphys::bullet {
namespace {

constexpr double kPi = std::numbers::pi;

double wrap(double angle) { return angle - 2.0 * kPi * std::round(angle / (2.0 * kPi)); }

btRigidBody& rigidOf(BulletWorld& world, BodyPeer* body) {
    // The world (a null body A): the world's static ground, whose frame is the world frame.
    if (body == nullptr) return world.ground();
    return static_cast<BulletBodyPeer*>(body)->rigidBody();
}

// 6-DOF spring 2 axis indices: translations 0..2, rotations 3..5.
constexpr int kLinX = 0, kAngX = 3, kAngY = 4;

// Scales the error targets of the first `rows` rows that are rigid (no bounds) and linear (a
// linear Jacobian: a ball's, a lock's, a rod's) so that together they ask for at most
// kJointPushMaxVelocity (joint_push.hpp; Bullet's rows ask for ERP x gap / h, without bound).
// Their axes are orthogonal unit vectors (a point's three, a slider's two, a rod's one), so the
// targets' norm is the speed at which the gap closes.
void capLinearPull(btTypedConstraint::btConstraintInfo2* info, int rows) {
    constexpr auto most = static_cast<btScalar>(kJointPushMaxVelocity);
    const auto rigidLinear = [info](int s) {
        if (info->m_lowerLimit[s] > -SIMD_INFINITY || info->m_upperLimit[s] < SIMD_INFINITY) return false;
        const btScalar* l = &info->m_J1linearAxis[s];
        const btScalar* l2 = info->m_J2linearAxis != nullptr ? &info->m_J2linearAxis[s] : nullptr;
        return l[0] != 0 || l[1] != 0 || l[2] != 0 || (l2 != nullptr && (l2[0] != 0 || l2[1] != 0 || l2[2] != 0));
    };
    btScalar squared = 0;
    for (int r = 0; r < rows; ++r) {
        const int s = r * info->rowskip;
        if (rigidLinear(s)) squared += info->m_constraintError[s] * info->m_constraintError[s];
    }
    if (squared <= most * most) return;
    const btScalar scale = most / btSqrt(squared);
    for (int r = 0; r < rows; ++r) {
        const int s = r * info->rowskip;
        if (rigidLinear(s)) info->m_constraintError[s] *= scale;
    }
}

// Free axis: lower > upper (Bullet's convention for an unlimited degree of freedom).
void freeAxis(btGeneric6DofSpring2Constraint& c, int axis) { c.setLimit(axis, 1, -1); }

}  // namespace

// ---- DistanceConstraint --------------------------------------------------------------------

DistanceConstraint::DistanceConstraint(btRigidBody& a, btRigidBody& b, const btVector3& anchorA,
                                       const btVector3& anchorB, double length)
    : btTypedConstraint(MAX_CONSTRAINT_TYPE, a, b), anchorA_(anchorA), anchorB_(anchorB), length_(length) {}

void DistanceConstraint::rows(Row out[2], int& count) const {
    count = 0;
    const btVector3 d = m_rbB.getCenterOfMassTransform() * anchorB_ - m_rbA.getCenterOfMassTransform() * anchorA_;
    if (d.length() < 1e-9) return;  // no direction to act along
    if (spring) out[count++] = Row::Spring;
    else if (!minLength && !maxLength) out[count++] = Row::Rigid;
    // A spring with both bounds needs three rows; the bound being approached is the one kept.
    const double length = d.length();
    if (count < 2 && minLength && maxLength) {
        out[count++] = length - *minLength < *maxLength - length ? Row::Min : Row::Max;
    } else {
        if (count < 2 && minLength) out[count++] = Row::Min;
        if (count < 2 && maxLength) out[count++] = Row::Max;
    }
}

void DistanceConstraint::getInfo1(btConstraintInfo1* info) {
    Row r[2];
    int count = 0;
    rows(r, count);
    info->m_numConstraintRows = count;
    info->nub = 6 - count;
}

void DistanceConstraint::getInfo2(btConstraintInfo2* info) {
    Row r[2];
    int count = 0;
    rows(r, count);
    const btTransform& ta = m_rbA.getCenterOfMassTransform();
    const btTransform& tb = m_rbB.getCenterOfMassTransform();
    const btVector3 pa = ta * anchorA_, pb = tb * anchorB_;
    const btVector3 ra = pa - ta.getOrigin(), rb = pb - tb.getOrigin();
    const btVector3 d = pb - pa;
    const btScalar length = d.length();
    if (count == 0) return;
    const btVector3 n = d / length;
    // J v = d(length)/dt; an impulse lambda pushes B along +n (A along -n).
    const btVector3 angA = -ra.cross(n), angB = rb.cross(n);
    const btScalar fps = info->fps, erp = erp_ >= 0 ? erp_ : info->erp;
    for (int i = 0; i < count; ++i) {
        const int s = i * info->rowskip;
        for (int k = 0; k < 3; ++k) {
            info->m_J1linearAxis[s + k] = -n[k];
            info->m_J1angularAxis[s + k] = angA[k];
            info->m_J2linearAxis[s + k] = n[k];
            info->m_J2angularAxis[s + k] = angB[k];
        }
        if (cfm_ != 0) info->cfm[s] = cfm_;
        switch (r[i]) {
            case Row::Rigid: {
                const btScalar C = length - static_cast<btScalar>(length_);
                info->m_constraintError[s] = -erp * fps * C;
                info->m_lowerLimit[s] = -SIMD_INFINITY;
                info->m_upperLimit[s] = SIMD_INFINITY;
                break;
            }
            case Row::Max: {  // pulls only: lambda <= 0; ahead of the bound the row lets the gap close
                const btScalar C = length - static_cast<btScalar>(*maxLength);
                info->m_constraintError[s] = -(C < 0 ? btScalar(1) : erp) * fps * C;
                info->m_lowerLimit[s] = -SIMD_INFINITY;
                info->m_upperLimit[s] = 0;
                break;
            }
            case Row::Min: {  // pushes only: lambda >= 0
                const btScalar C = length - static_cast<btScalar>(*minLength);
                info->m_constraintError[s] = -(C > 0 ? btScalar(1) : erp) * fps * C;
                info->m_lowerLimit[s] = 0;
                info->m_upperLimit[s] = SIMD_INFINITY;
                break;
            }
            case Row::Spring: {
                SpringRowInput in;
                in.spring = {-n, angA, n, angB};
                in.stretch = static_cast<double>(length) - length_;
                in.stiffness = spring->stiffness;
                in.damping = spring->damping;
                in.h = 1.0 / static_cast<double>(fps);
                in.softRows = softSpringRows;
                in.springsOnBusierBody = springsOnBusierBody;
                writeSpringRow(info, s, m_rbA, m_rbB, in);
                break;
            }
            case Row::None: break;
        }
    }
}

void DistanceConstraint::setParam(int num, btScalar value, int axis) {
    (void)axis;
    if (num == BT_CONSTRAINT_ERP || num == BT_CONSTRAINT_STOP_ERP) erp_ = value;
    if (num == BT_CONSTRAINT_CFM || num == BT_CONSTRAINT_STOP_CFM) cfm_ = value;
}

btScalar DistanceConstraint::getParam(int num, int axis) const {
    (void)axis;
    if (num == BT_CONSTRAINT_ERP || num == BT_CONSTRAINT_STOP_ERP) return erp_;
    return cfm_;
}

// ---- SlidingDofConstraint ------------------------------------------------------------------

void SlidingDofConstraint::getInfo1(btConstraintInfo1* info) {
    btGeneric6DofSpring2Constraint::getInfo1(info);
    rows_ = info->m_numConstraintRows;
}

// Some linear axis is not locked (lower != upper; free is lower > upper): B can travel along it.
bool SlidingDofConstraint::travels() const {
    for (int i = 0; i < 3; ++i)
        if (m_linearLimits.m_lowerLimit[i] != m_linearLimits.m_upperLimit[i]) return true;
    return false;
}

void SlidingDofConstraint::getInfo2(btConstraintInfo2* info) {
    btGeneric6DofSpring2Constraint::getInfo2(info);
    // Without travel the anchors coincide but for the error the rows close: Bullet's rows stand.
    // With a static B and locked rotations Bullet scales A's lever (by its m_factA, 0 then): left
    // as it is, the static body taking the torque. Otherwise A's lever is unscaled.
    if (!travels() || (m_hasStaticBody && m_factA < btScalar(1))) return;
    const btVector3 lever = m_calculatedTransformB.getOrigin() - m_rbA.getCenterOfMassPosition();
    for (int r = 0; r < rows_; ++r) {
        const int s = r * info->rowskip;
        const btVector3 axis(info->m_J1linearAxis[s], info->m_J1linearAxis[s + 1], info->m_J1linearAxis[s + 2]);
        // Angular rows leave the linear Jacobian as the solver hands it over: zero.
        if (axis.isZero()) continue;
        const btVector3 angular = lever.cross(axis);
        for (int k = 0; k < 3; ++k) info->m_J1angularAxis[s + k] = angular[k];
    }
}

// ---- DecoupledConstraint -------------------------------------------------------------------

DecoupledConstraint::DecoupledConstraint(btTypedConstraint& inner)
    : btTypedConstraint(inner.getConstraintType(), inner.getRigidBodyA(), inner.getRigidBodyB()), inner_(inner) {}

void DecoupledConstraint::getInfo1(btConstraintInfo1* info) {
    inner_.getInfo1(info);
    rows_ = info->m_numConstraintRows;
    const int added = (stops ? 2 : 0) + (spring ? 1 : 0);
    info->m_numConstraintRows += added;
    info->nub = std::max(0, info->nub - added);
}

DecoupledConstraint::AxisRow DecoupledConstraint::axisRow(const Axis& axis) const {
    const btTransform& ta = m_rbA.getCenterOfMassTransform();
    const btTransform& tb = m_rbB.getCenterOfMassTransform();
    const btTransform fa = ta * axis.frameA, fb = tb * axis.frameB;
    const btVector3 x = fa.getBasis().getColumn(0);
    btVector3 l1(0, 0, 0), a1, l2(0, 0, 0), a2;
    btScalar position;
    if (axis.angular) {
        // The angle of B about A's X: the relative rotation's twist about X.
        const btQuaternion rel = fa.getRotation().inverse() * fb.getRotation();
        position = btScalar(2) * btAtan2(rel.x(), rel.w());
        if (position > SIMD_PI) position -= SIMD_2_PI;
        if (position < -SIMD_PI) position += SIMD_2_PI;
        a1 = -x;
        a2 = x;
    } else {
        // The offset along A's X; x turns with A, so A's side acts at the point under B's anchor.
        const btVector3 d = fb.getOrigin() - fa.getOrigin();
        position = d.dot(x);
        l1 = -x;
        a1 = -(fa.getOrigin() + d - ta.getOrigin()).cross(x);
        l2 = x;
        a2 = (fb.getOrigin() - tb.getOrigin()).cross(x);
    }
    return {position, l1, a1, l2, a2};
}

int DecoupledConstraint::stopRows(btConstraintInfo2* info, int row) {
    const auto [position, l1, a1, l2, a2] = axisRow(*stops);
    const btScalar erp = info->erp, fps = info->fps;
    for (int side = 0; side < 2; ++side) {
        const btScalar sign = side == 0 ? btScalar(1) : btScalar(-1);  // lower: C = x - lower; upper: upper - x
        const btScalar C = side == 0 ? position - stops->lower : stops->upper - position;
        const int s = (row + side) * info->rowskip;
        for (int k = 0; k < 3; ++k) {
            info->m_J1linearAxis[s + k] = sign * l1[k];
            info->m_J1angularAxis[s + k] = sign * a1[k];
            if (info->m_J2linearAxis != nullptr) info->m_J2linearAxis[s + k] = sign * l2[k];
            if (info->m_J2angularAxis != nullptr) info->m_J2angularAxis[s + k] = sign * a2[k];
        }
        // J v = dC/dt >= -C / h ahead of the stop (reach it, not past it), >= -erp C / h past it.
        info->m_constraintError[s] = -(C > 0 ? btScalar(1) : erp) * fps * C;
        info->cfm[s] = 0;
        info->m_lowerLimit[s] = 0;
        info->m_upperLimit[s] = SIMD_INFINITY;
    }
    return 2;
}

void DecoupledConstraint::springRow(btConstraintInfo2* info, int innerRows, int row) {
    const auto [position, l1, a1, l2, a2] = axisRow(*spring);
    // The inner constraint's unbounded rows (already written) turn the spring's impulse into
    // motion about the joint: they are solved alongside it.
    constexpr int kMax = 6;
    JointRow rigid[kMax];
    btScalar targets[kMax];
    int count = 0;
    const auto at = [](const btScalar* axis, int s) { return axis ? btVector3(axis[s], axis[s + 1], axis[s + 2]) : btVector3(0, 0, 0); };
    for (int r = 0; r < innerRows && count < kMax; ++r) {
        const int s = r * info->rowskip;
        if (info->m_lowerLimit[s] > -SIMD_INFINITY || info->m_upperLimit[s] < SIMD_INFINITY) continue;
        rigid[count] = {at(info->m_J1linearAxis, s), at(info->m_J1angularAxis, s), at(info->m_J2linearAxis, s),
                        at(info->m_J2angularAxis, s)};
        targets[count++] = info->m_constraintError[s];
    }
    SpringRowInput in;
    in.spring = {l1, a1, l2, a2};
    in.stretch = static_cast<double>(position) + spring->turns;
    in.stiffness = spring->stiffness;
    in.damping = spring->damping;
    in.rigid = rigid;
    in.rigidTargets = targets;
    in.rigidCount = count;
    in.h = 1.0 / static_cast<double>(info->fps);
    in.softRows = softSpringRows;
    in.springsOnBusierBody = springsOnBusierBody;
    writeSpringRow(info, row * info->rowskip, m_rbA, m_rbB, in);
}

void DecoupledConstraint::getInfo2(btConstraintInfo2* info) {
    const int n = rows_;
    if (stops) stopRows(info, n);
    innerRows(info);
    if (spring) springRow(info, n, n + (stops ? 2 : 0));
}

void DecoupledConstraint::innerRows(btConstraintInfo2* info) {
    const int n = rows_;
    if (!decouple || n < 2) {
        inner_.getInfo2(info);
        capLinearPull(info, n);
        return;
    }
    // The inner constraint writes its rows into the scratch, initialised as the solver does
    // (Jacobians 0, no bounds, the global CFM in the first row).
    for (auto* a : {&j1l_, &j1a_, &j2l_, &j2a_, &error_, &cfm_}) {
        a->resize(3 * n);
        for (int i = 0; i < 3 * n; ++i) (*a)[i] = 0;
    }
    lower_.resize(3 * n);
    upper_.resize(3 * n);
    for (int i = 0; i < 3 * n; ++i) {
        lower_[i] = -SIMD_INFINITY;
        upper_[i] = SIMD_INFINITY;
    }
    cfm_[0] = info->cfm[0];
    btConstraintInfo2 scratch = *info;
    scratch.rowskip = 3;
    scratch.m_J1linearAxis = &j1l_[0];
    scratch.m_J1angularAxis = &j1a_[0];
    scratch.m_J2linearAxis = &j2l_[0];
    scratch.m_J2angularAxis = &j2a_[0];
    scratch.m_constraintError = &error_[0];
    scratch.cfm = &cfm_[0];
    scratch.m_lowerLimit = &lower_[0];
    scratch.m_upperLimit = &upper_[0];
    inner_.getInfo2(&scratch);
    capLinearPull(&scratch, n);
    info->m_damping = scratch.m_damping;

    // The rigid rows (no bounds, one CFM), at most 6.
    constexpr int kMax = 6;
    int rigid[kMax];
    int count = 0;
    bool decouplable = true;
    for (int r = 0; r < n; ++r) {
        if (lower_[3 * r] > -SIMD_INFINITY || upper_[3 * r] < SIMD_INFINITY) continue;
        if (count == kMax || (count > 0 && cfm_[3 * r] != cfm_[3 * rigid[0]])) {
            decouplable = false;
            break;
        }
        rigid[count++] = r;
    }
    const auto vec = [](const btAlignedObjectArray<btScalar>& a, int r) { return btVector3(a[3 * r], a[3 * r + 1], a[3 * r + 2]); };
    btVector3 lin1[kMax], ang1[kMax], lin2[kMax], ang2[kMax];
    btScalar err[kMax];
    if (decouplable && count >= 2) {
        // K = J M^-1 J^T as the solver applies impulses (factors mask directions, as in Bullet).
        const btRigidBody& a = m_rbA;
        const btRigidBody& b = m_rbB;
        using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;
        Block K(count, count);
        btVector3 dl1[kMax], da1[kMax], dl2[kMax], da2[kMax];
        for (int i = 0; i < count; ++i) {
            const int r = rigid[i];
            dl1[i] = vec(j1l_, r) * a.getInvMass() * a.getLinearFactor();
            da1[i] = (a.getInvInertiaTensorWorld() * vec(j1a_, r)) * a.getAngularFactor();
            dl2[i] = vec(j2l_, r) * b.getInvMass() * b.getLinearFactor();
            da2[i] = (b.getInvInertiaTensorWorld() * vec(j2a_, r)) * b.getAngularFactor();
        }
        for (int i = 0; i < count; ++i)
            for (int k = 0; k < count; ++k) {
                const int r = rigid[k];
                K(i, k) = static_cast<double>(vec(j1l_, r).dot(dl1[i]) + vec(j1a_, r).dot(da1[i]) + vec(j2l_, r).dot(dl2[i]) +
                                              vec(j2a_, r).dot(da2[i]));
            }
        const Block sym = 0.5 * (K + K.transpose());
        Eigen::SelfAdjointEigenSolver<Block> eigen(sym);
        if (eigen.info() == Eigen::Success) {
            const Block& Q = eigen.eigenvectors();  // columns: the new rows' weights
            for (int k = 0; k < count; ++k) {
                lin1[k] = ang1[k] = lin2[k] = ang2[k] = btVector3(0, 0, 0);
                err[k] = 0;
                for (int i = 0; i < count; ++i) {
                    const auto q = static_cast<btScalar>(Q(i, k));
                    const int r = rigid[i];
                    lin1[k] += q * vec(j1l_, r);
                    ang1[k] += q * vec(j1a_, r);
                    lin2[k] += q * vec(j2l_, r);
                    ang2[k] += q * vec(j2a_, r);
                    err[k] += q * error_[3 * r];
                }
            }
        } else {
            count = 0;
        }
    } else {
        count = 0;
    }
    // Out: the rigid rows' places take the new rows, the bounded rows pass through.
    int next = 0;
    for (int r = 0; r < n; ++r) {
        const int s = r * info->rowskip;
        const bool replaced = next < count && rigid[next] == r;
        const btVector3 l1 = replaced ? lin1[next] : vec(j1l_, r), a1 = replaced ? ang1[next] : vec(j1a_, r);
        const btVector3 l2 = replaced ? lin2[next] : vec(j2l_, r), a2 = replaced ? ang2[next] : vec(j2a_, r);
        for (int k = 0; k < 3; ++k) {
            info->m_J1linearAxis[s + k] = l1[k];
            info->m_J1angularAxis[s + k] = a1[k];
            if (info->m_J2linearAxis != nullptr) info->m_J2linearAxis[s + k] = l2[k];
            if (info->m_J2angularAxis != nullptr) info->m_J2angularAxis[s + k] = a2[k];
        }
        info->m_constraintError[s] = replaced ? err[next] : error_[3 * r];
        info->cfm[s] = cfm_[3 * r];
        info->m_lowerLimit[s] = lower_[3 * r];
        info->m_upperLimit[s] = upper_[3 * r];
        if (replaced) ++next;
    }
}

// ---- BulletJointPeer -------------------------------------------------------------------------

BulletJointPeer::BulletJointPeer(BulletWorld& world, const JointPeerDef& def) : world_(&world), def_(def) {
    btRigidBody& a = rigidOf(world, def.bodyA);
    btRigidBody& b = rigidOf(world, def.bodyB);
    const btTransform fa = toBt(def.frameA), fb = toBt(def.frameB);
    switch (def.type) {
        case JointType::Fixed: constraint_ = std::make_unique<btFixedConstraint>(a, b, fa, fb); break;
        case JointType::Ball:
            constraint_ = std::make_unique<btPoint2PointConstraint>(a, b, fa.getOrigin(), fb.getOrigin());
            break;
        case JointType::Hinge:
        case JointType::Slider:
        case JointType::Wheel: {
            // The free rotation comes first in the Euler order, so its angle has the full range
            // (the middle one is limited to +-pi/2): X for a hinge, Y (the axle) for a wheel.
            const RotateOrder order = def.type == JointType::Wheel ? RO_YXZ : RO_XYZ;
            auto dof = std::make_unique<SlidingDofConstraint>(a, b, fa, fb, order);
            dof_ = dof.get();
            for (int axis = 0; axis < 6; ++axis) dof_->setLimit(axis, 0, 0);  // locked
            if (def.type == JointType::Wheel) freeAxis(*dof_, kAngY);
            constraint_ = std::move(dof);
            break;
        }
        case JointType::Cone: {
            // Bullet's twist span is symmetric: B's frame turns about X to the middle of the range.
            btScalar twistSpan = SIMD_PI;  // no twist limit: the full turn
            if (def.twistLimits) {
                twistOffset_ = -0.5 * (def.twistLimits->lower + def.twistLimits->upper);
                twistSpan = static_cast<btScalar>(0.5 * (def.twistLimits->upper - def.twistLimits->lower));
            }
            const Transform turnedB{def.frameB.position,
                                    def.frameB.orientation * Quat(Eigen::AngleAxisd(twistOffset_, Vec3::UnitX()))};
            auto cone = std::make_unique<btConeTwistConstraint>(a, b, fa, toBt(turnedB));
            const auto swing = static_cast<btScalar>(std::min(def.swingLimit, kPi));
            cone->setLimit(swing, swing, twistSpan);
            constraint_ = std::move(cone);
            break;
        }
        case JointType::Distance: {
            auto distance = std::make_unique<DistanceConstraint>(a, b, toBt(def.anchorA), toBt(def.anchorB), def.length);
            distance_ = distance.get();
            distance_->minLength = def.minLength;
            distance_->maxLength = def.maxLength;
            constraint_ = std::move(distance);
            break;
        }
    }
    decoupled_ = std::make_unique<DecoupledConstraint>(*constraint_);
    decoupled_->decouple = world.decoupledJoints();
    decoupled_->softSpringRows = world.solvesRowsSoftly();
    if (distance_ != nullptr) distance_->softSpringRows = world.solvesRowsSoftly();
    feedback_ = {};
    decoupled_->setJointFeedback(&feedback_);
    decoupled_->enableFeedback(true);
    applyLimits();
    applyMotor();
    applySpring();
    measure();
    position_ = 0.0;  // frames coincide at creation
}

BulletJointPeer::~BulletJointPeer() {
    if (world_ != nullptr) world_->detachJoint(*this);
}

void* BulletJointPeer::nativeObject(const std::type_info& pointerType) {
    if (pointerType == typeid(btTypedConstraint*)) return decoupled_.get();  // the one in the Bullet world
    if (dof_ != nullptr && pointerType == typeid(btGeneric6DofSpring2Constraint*)) return dof_;
    if (pointerType == typeid(btPoint2PointConstraint*) && def_.type == JointType::Ball) return constraint_.get();
    if (pointerType == typeid(btFixedConstraint*) && def_.type == JointType::Fixed) return constraint_.get();
    if (pointerType == typeid(btConeTwistConstraint*) && def_.type == JointType::Cone) return constraint_.get();
    return nullptr;
}

void BulletJointPeer::setMotor(const std::optional<JointMotor>& motor) {
    def_.motor = motor;
    applyMotor();
    wakeBodies();
}

void BulletJointPeer::setLimits(const std::optional<JointLimits>& limits) {
    def_.limits = limits;
    applyLimits();
    wakeBodies();
}

void BulletJointPeer::setSpringsOnBusierBody(int count) {
    decoupled_->springsOnBusierBody = count;
    if (distance_ != nullptr) distance_->springsOnBusierBody = count;
}

void BulletJointPeer::setSpring(const std::optional<JointSpringSI>& spring) {
    def_.spring = spring;
    applySpring();
    wakeBodies();
}

void BulletJointPeer::setSteeringAngle(double angle) {
    if (def_.type != JointType::Wheel || !def_.steering || dof_ == nullptr) return;
    steeringAngle_ = angle;
    dof_->setFrames(toBt(steeredFrameA()), toBt(def_.frameB));
    if (decoupled_->stops) decoupled_->stops->frameA = toBt(steeredFrameA());
    if (decoupled_->spring) decoupled_->spring->frameA = toBt(steeredFrameA());
    wakeBodies();
}

// The axis the joint's limits, spring and motor act on, in the 6-DOF's numbering.
void BulletJointPeer::applyLimits() {
    if (dof_ == nullptr) return;
    // The axis stays free in the 6-DOF constraint; the stops are the wrapper's rows (AxisStops).
    freeAxis(*dof_, def_.type == JointType::Hinge ? kAngX : kLinX);
    if (!def_.limits) {
        decoupled_->stops.reset();
        return;
    }
    DecoupledConstraint::AxisStops stops;
    stops.angular = def_.type == JointType::Hinge;
    stops.frameA = toBt(steeredFrameA());
    stops.frameB = toBt(def_.frameB);
    stops.lower = static_cast<btScalar>(def_.limits->lower);
    stops.upper = static_cast<btScalar>(def_.limits->upper);
    decoupled_->stops = stops;
}

void BulletJointPeer::applyMotor() {
    if (dof_ == nullptr) return;
    const int axis = def_.type == JointType::Hinge ? kAngX : def_.type == JointType::Wheel ? kAngY : kLinX;
    if (!def_.motor) {
        dof_->enableMotor(axis, false);
        return;
    }
    // Bullet 3.24's 6-DOF spring 2 motor bounds each substep's impulse by maxMotorForce / fps:
    // a force (N, N m), as the layer's (checked by the spin-up test: w = tau t / I). Its row is
    // J = (+axis, -axis) with J v = target, the rate of A relative to B: negated (checked by the
    // sign tests, rotation and translation).
    const double sign = -1.0;
    dof_->enableMotor(axis, true);
    dof_->setTargetVelocity(axis, static_cast<btScalar>(sign * def_.motor->speed));
    dof_->setMaxMotorForce(axis, static_cast<btScalar>(def_.motor->maxForce));
}

void BulletJointPeer::applySpring() {
    if (distance_ != nullptr) {
        distance_->spring = def_.spring;
        return;
    }
    if (dof_ == nullptr) return;
    // The wrapper's spring row (DecoupledConstraint::AxisSpring, implicit when stiff), not
    // Bullet's 6-DOF spring, which diverges when stiff and, with limitIfNeeded, silently softens.
    if (!def_.spring) {
        decoupled_->spring.reset();
        return;
    }
    DecoupledConstraint::AxisSpring spring;
    spring.angular = def_.type == JointType::Hinge;
    spring.frameA = toBt(steeredFrameA());
    spring.frameB = toBt(def_.frameB);
    spring.stiffness = def_.spring->stiffness;
    spring.damping = def_.spring->damping;
    decoupled_->spring = spring;
}

void BulletJointPeer::wakeBodies() {
    if (def_.bodyA != nullptr) def_.bodyA->setAwake(true);
    if (def_.bodyB != nullptr) def_.bodyB->setAwake(true);
}

void BulletJointPeer::beginStep() {
    stepImpulse_.setZero();
    stepAngularImpulse_.setZero();
    solved_ = false;
}

void BulletJointPeer::beginSubstep() {
    if (def_.type == JointType::Hinge && decoupled_->spring) {
        // The spring row's angle is wrapped to (-pi, pi], the layer's runs on past +-pi (whole
        // turns count): a spring wound k turns pulls back through them.
        const double angle = hingeAngle();
        decoupled_->spring->turns = 2.0 * kPi * std::round((angle - wrap(angle)) / (2.0 * kPi));
    }
    feedback_.m_appliedForceBodyA.setZero();
    feedback_.m_appliedForceBodyB.setZero();
    feedback_.m_appliedTorqueBodyA.setZero();
    feedback_.m_appliedTorqueBodyB.setZero();
}

void BulletJointPeer::endSubstep(double h) {
    const btRigidBody& a = decoupled_->getRigidBodyA();
    const btRigidBody& b = decoupled_->getRigidBodyB();
    // A sleeping island is not solved: its joints keep the reactions they last reported.
    if (!a.isActive() && !b.isActive()) return;
    solved_ = true;
    // Bullet's feedback is the substep's impulse / h: a force on B and a torque about B's centre
    // of mass. The torque about B's anchor: tau - r x F, r from the centre of mass to the anchor.
    const Vec3 force = fromBt(feedback_.m_appliedForceBodyB);
    const Vec3 torque = fromBt(feedback_.m_appliedTorqueBodyB);
    const btTransform& tb = b.getCenterOfMassTransform();
    const Vec3 local = def_.type == JointType::Distance ? def_.anchorB : def_.frameB.position;
    const Vec3 r = fromBt(tb.getBasis() * toBt(local));
    stepImpulse_ += h * force;
    stepAngularImpulse_ += h * (torque - r.cross(force));
}

void BulletJointPeer::endStep(double dt) {
    if (solved_) {
        reactionForce_ = stepImpulse_ / dt;
        reactionTorque_ = stepAngularImpulse_ / dt;
    }
    measure();
}

BodyState BulletJointPeer::stateA() const {
    if (def_.bodyA == nullptr) return {};
    return def_.bodyA->state();
}
BodyState BulletJointPeer::stateB() const { return def_.bodyB->state(); }

// Frame A turned by the steering angle about X (wheels with steering; the frame as given otherwise).
Transform BulletJointPeer::steeredFrameA() const {
    if (def_.type != JointType::Wheel || !def_.steering) return def_.frameA;
    return {def_.frameA.position, def_.frameA.orientation * Quat(Eigen::AngleAxisd(steeringAngle_, Vec3::UnitX()))};
}

// The hinge angle now, unwrapped against the last reported one.
double BulletJointPeer::hingeAngle() const {
    const BodyState a = stateA(), b = stateB();
    const Quat rel = (a.orientation * def_.frameA.orientation).conjugate() * (b.orientation * def_.frameB.orientation);
    const double raw = wrap(2.0 * std::atan2(rel.x(), rel.w()));
    return raw + 2.0 * kPi * std::round((position_ - raw) / (2.0 * kPi));
}

// Position and speed from the bodies' states, by the contract's definitions (joint_peer.hpp).
void BulletJointPeer::measure() {
    const BodyState a = stateA(), b = stateB();
    Quat qA = a.orientation * def_.frameA.orientation;
    if (def_.type == JointType::Wheel && def_.steering) qA = qA * Quat(Eigen::AngleAxisd(steeringAngle_, Vec3::UnitX()));
    const Quat qB = b.orientation * def_.frameB.orientation;
    const bool distance = def_.type == JointType::Distance;
    const Vec3 rA = a.orientation * (distance ? def_.anchorA : def_.frameA.position);
    const Vec3 rB = b.orientation * (distance ? def_.anchorB : def_.frameB.position);
    const Vec3 d = (b.position + rB) - (a.position + rA);
    const Vec3 x = qA * Vec3::UnitX();
    const Vec3 relW = b.angularVelocity - a.angularVelocity;
    switch (def_.type) {
        case JointType::Hinge:
            // Unwrapped: the turn nearest the last angle, so the angle runs past +-pi.
            position_ = hingeAngle();
            speed_ = relW.dot(x);
            break;
        case JointType::Slider: {
            position_ = d.dot(x);
            // d/dt (d . x) with x turning with A: B's anchor against A's point under it.
            const Vec3 vA = a.linearVelocity + a.angularVelocity.cross(rA + d);
            const Vec3 vB = b.linearVelocity + b.angularVelocity.cross(rB);
            speed_ = (vB - vA).dot(x);
            break;
        }
        case JointType::Wheel:
            position_ = d.dot(x);
            speed_ = relW.dot(qA * Vec3::UnitY());
            break;
        case JointType::Distance: {
            const double length = d.norm();
            position_ = length - def_.length;
            const Vec3 vA = a.linearVelocity + a.angularVelocity.cross(rA);
            const Vec3 vB = b.linearVelocity + b.angularVelocity.cross(rB);
            speed_ = length > 1e-12 ? (vB - vA).dot(d / length) : 0.0;
            break;
        }
        case JointType::Ball:
        case JointType::Cone: {
            // swing = acos(xA . xB); d/dt (xA . xB) = (wB - wA) . (xB x xA) = -sin(swing) swing'.
            const Vec3 xB = qB * Vec3::UnitX();
            const Vec3 bend = x.cross(xB);
            const double sine = bend.norm();
            position_ = std::atan2(sine, x.dot(xB));
            speed_ = sine > 1e-9 ? relW.dot(bend) / sine : 0.0;
            break;
        }
        case JointType::Fixed:
            position_ = 0.0;
            speed_ = 0.0;
            break;
    }
}

}  // namespace anyphys::bullet

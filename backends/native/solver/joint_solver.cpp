#include "solver/joint_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include "solver/body_integration.hpp"

namespace anyphys::native {
namespace {

constexpr double kPi = std::numbers::pi;

// One side of a joint during a pass: current pose and velocity, inverse mass and inertia.
struct Side {
    std::int32_t index = kStaticBody;
    bool takesImpulses = false;
    Vec3 invMass = Vec3::Zero();
    Mat3 invI = Mat3::Zero();
    Vec3 x = Vec3::Zero();
    Quat q = Quat::Identity();
    Vec3 v = Vec3::Zero(), w = Vec3::Zero();
};

Side load(std::int32_t index, const Transform& fixed, const SolverBody* bodies, const SolverState* states) {
    Side s;
    s.index = index;
    if (index == kStaticBody) {
        s.x = fixed.position;
        s.q = fixed.orientation;
        return s;
    }
    const SolverBody& b = bodies[index];
    const SolverState& st = states[index];
    s.takesImpulses = b.dynamic;
    s.invMass = b.invMass;
    s.invI = b.invInertia;
    // A body held by joints alone turns through the inverse inertia of the pose it has turned to
    // since the step began: the rows' anchors turn with the body (JointPass), and an impulse
    // through a turned anchor must act through the inertia of the same pose. Through the step's
    // first inertia, a disc spinning at 100 rad/s on a ball joint through its axis gained 0.6 rad/s
    // of spin in 10 s as the axis tipped, where nothing acts about that axis. A body with contacts
    // keeps the step's first inertia, as its contact rows do (they are linearised at the step's
    // start): with two inertias on one body, 15 nudged runs of the pinched ragdoll pile
    // (test_assemblies.cpp) opened their joints wider, median worst gap 45 -> 54 mm, one run to
    // 194 mm; with one inertia per body, 50 mm, within the runs' spread of 31 to 98 mm.
    if (!b.contacted) {
        const Mat3 turned = Quat(st.dq[0], st.dq[1], st.dq[2], st.dq[3]).toRotationMatrix();
        s.invI = turned * b.invInertia * turned.transpose();
    }
    s.x = b.position0 + Vec3(st.dp[0], st.dp[1], st.dp[2]);
    s.q = (Quat(st.dq[0], st.dq[1], st.dq[2], st.dq[3]) * b.orientation0).normalized();
    s.v = Vec3(st.v[0], st.v[1], st.v[2]);
    s.w = Vec3(st.w[0], st.w[1], st.w[2]);
    return s;
}

void store(const Side& s, SolverState* states) {
    if (!s.takesImpulses) return;
    SolverState& st = states[s.index];
    for (int k = 0; k < 3; ++k) {
        st.v[k] = s.v[k];
        st.w[k] = s.w[k];
    }
}

// A scalar row: Cdot = J . (vA, wA, vB, wB).
struct Jacobian {
    Vec3 linA = Vec3::Zero(), angA = Vec3::Zero(), linB = Vec3::Zero(), angB = Vec3::Zero();
};

Jacobian linearRow(const Vec3& n, const Vec3& leverA, const Vec3& rB) {
    return {-n, -leverA.cross(n), n, rB.cross(n)};
}
Jacobian angularRow(const Vec3& axis) { return {Vec3::Zero(), -axis, Vec3::Zero(), axis}; }

// J_i M^-1 J_k^T.
double coupling(const Jacobian& i, const Jacobian& k, const Side& a, const Side& b) {
    return i.linA.dot(a.invMass.cwiseProduct(k.linA)) + i.angA.dot(a.invI * k.angA) +
           i.linB.dot(b.invMass.cwiseProduct(k.linB)) + i.angB.dot(b.invI * k.angB);
}
double inverseMass(const Jacobian& j, const Side& a, const Side& b) { return coupling(j, j, a, b); }
double rate(const Jacobian& j, const Side& a, const Side& b) {
    return j.linA.dot(a.v) + j.angA.dot(a.w) + j.linB.dot(b.v) + j.angB.dot(b.w);
}
void apply(const Jacobian& j, double impulse, Side& a, Side& b) {
    a.v += a.invMass.cwiseProduct(impulse * j.linA);
    a.w += a.invI * (impulse * j.angA);
    b.v += b.invMass.cwiseProduct(impulse * j.linB);
    b.w += b.invI * (impulse * j.angB);
}

// Angle in (-pi, pi].
double wrap(double angle) {
    angle = std::fmod(angle + kPi, 2.0 * kPi);
    if (angle <= 0.0) angle += 2.0 * kPi;
    return angle - kPi;
}

// What a pass does with each row. Position: PGS's position pass (correctJointPosition), which
// moves the bodies instead of changing their velocities.
enum class Mode { WarmStart, Solve, Relax, Position };

// The geometry of one joint in the current pass, and the driver that solves, warm starts or
// sums its rows.
class JointPass {
public:
    JointPass(const JointConstraint& c, const SolverBody* bodies, const SolverState* states, const JointSolveParams& p,
              Mode mode)
        : joint_(*c.joint), def_(c.joint->def), p_(p), mode_(mode), springsOnBusierBody_(c.springsOnBusierBody),
          a_(load(c.a, c.fixedA, bodies, states)), b_(load(c.b, c.fixedB, bodies, states)) {
        if (mode_ == Mode::Position) {  // v and w carry the pass's displacement and turn
            a_.v = a_.w = b_.v = b_.w = Vec3::Zero();
        }
        frameA_ = a_.q * def_.frameA.orientation;
        frameB_ = b_.q * def_.frameB.orientation;
        if (def_.type == JointType::Wheel && def_.steering)
            frameA_ = frameA_ * Quat(Eigen::AngleAxisd(joint_.steeringAngle, Vec3::UnitX()));
        const Vec3 localA = def_.type == JointType::Distance ? def_.anchorA : def_.frameA.position;
        const Vec3 localB = def_.type == JointType::Distance ? def_.anchorB : def_.frameB.position;
        rA_ = a_.q * localA;
        rB_ = b_.q * localB;
        d_ = (b_.x + rB_) - (a_.x + rA_);
    }

    void run(bool useBias, bool endOfSubstep) {
        useBias_ = useBias;
        endOfSubstep_ = endOfSubstep;
        switch (def_.type) {
            case JointType::Ball: point(); break;
            case JointType::Fixed:
                angularLock();
                point();
                break;
            case JointType::Hinge:
                axisRows(angularRow(axisX()), hingeAngle(), false);
                hingeLocks(0);  // about frame X
                point();
                break;
            case JointType::Slider:
                axisRows(linearRow(axisX(), rA_ + d_, rB_), d_.dot(axisX()), true);
                angularLock();
                slidingLocks();
                break;
            case JointType::Cone:
                coneLimits();
                point();
                break;
            case JointType::Distance: distance(); break;
            case JointType::Wheel:
                wheel();
                break;
        }
        solveLocks();
    }

    void finish(SolverState* states) {
        for (const Side* side : {&a_, &b_}) {
            if (mode_ != Mode::Position)
                store(*side, states);
            else if (side->takesImpulses)
                displaceBody(states[side->index], side->v, side->w);
        }
    }

    // For reports.
    double hingeAngle() const {
        const Quat rel = frameA_.conjugate() * frameB_;
        const double raw = wrap(2.0 * std::atan2(rel.x(), rel.w()));
        // Unwrapped: the turn nearest to the last reported angle, so the angle runs past +-pi.
        return raw + 2.0 * kPi * std::round((joint_.position - raw) / (2.0 * kPi));
    }
    double swingAngle() const {
        return std::acos(std::clamp(axisX().dot(frameB_ * Vec3::UnitX()), -1.0, 1.0));
    }
    Vec3 axisX() const { return frameA_ * Vec3::UnitX(); }
    Vec3 axle() const { return frameA_ * Vec3::UnitY(); }
    const Vec3& separation() const { return d_; }
    const Side& a() const { return a_; }
    const Side& b() const { return b_; }
    const Vec3& rA() const { return rA_; }
    const Vec3& rB() const { return rB_; }

private:
    // ---- bias of a position error -----------------------------------------------------------

    // Velocity bias and softness of a rigid row with position error C (Cdot + bias -> 0). PGS
    // corrects positions in their own pass, where the bias is the share of C to take back now: a
    // velocity bias (Baumgarte) stays in the accumulated impulses, and warm starting it made a
    // hanging 40-link chain ring up until it flew apart, even at 1 substep x 50 iterations.
    struct Bias {
        double bias = 0.0, massScale = 1.0, impulseScale = 0.0;
    };
    Bias rigidBias(double C) const {
        if (mode_ == Mode::Position) return {p_.baumgarte * C, 1.0, 0.0};
        if (mode_ == Mode::Relax || !useBias_ || !p_.soft) return {};
        return {p_.softness.biasRate * C, p_.softness.massScale, p_.softness.impulseScale};
    }
    // The position pass changes no impulse: they are the velocity passes' (and warm starts').
    void releaseImpulse(int slot) {
        if (mode_ != Mode::Position) joint_.impulse[slot] = 0.0;
    }

    // ---- rows ---------------------------------------------------------------------------------

    // Solves, warm starts or sums one scalar row. lower / upper bound the accumulated impulse.
    void row(int slot, const Jacobian& j, const Bias& bias, double lower, double upper) {
        if (mode_ == Mode::Position) return;
        double& acc = joint_.impulse[slot];
        if (mode_ == Mode::WarmStart) {
            apply(j, acc, a_, b_);
            return;
        }
        const double k = inverseMass(j, a_, b_);
        if (k > 0.0) {
            const double delta = -bias.massScale / k * (rate(j, a_, b_) + bias.bias) - bias.impulseScale * acc;
            const double total = std::clamp(acc + delta, lower, upper);
            apply(j, total - acc, a_, b_);
            acc = total;
        }
        sum(j, acc);
    }
    // A limit (C >= 0 allowed, impulse >= 0) joins the rigid block, so a stop holds against a
    // long lever too (a row of its own would only stop the small body's spin).
    void limitRow(int slot, const Jacobian& j, double C, double biasScale = 1.0) {
        locks_[lockCount_++] = {.j = j, .C = C, .slot = slot, .row = Row::Limit, .biasScale = biasScale};
    }
    static constexpr double kLockedRange = 1e-12;  // a range this narrow is a lock
    // A range [lower, upper] on `position` along j: only the nearer stop joins the block. Both
    // would be two rows with opposite Jacobians, a singular K whose rounding-sized pivot blew a
    // ragdoll pile up; the far stop cannot act this substep anyway. A range of zero width is a lock.
    // `linear`: the position is a length, whose correction is capped (anchorBiasScale).
    void limitPair(int lowerSlot, int upperSlot, const Jacobian& j, double position, double lower, double upper,
                   bool linear = false) {
        const auto scale = [&](double C) { return linear ? anchorBiasScale(C) : 1.0; };
        if (upper - lower <= kLockedRange) {
            lock(lowerSlot, j, position - lower, scale(position - lower));
            releaseImpulse(upperSlot);
        } else if (position - lower <= upper - position) {
            limitRow(lowerSlot, j, position - lower, scale(position - lower));
            releaseImpulse(upperSlot);
        } else {
            limitRow(upperSlot, negate(j), upper - position, scale(upper - position));
            releaseImpulse(lowerSlot);
        }
    }
    // Drives Cdot toward `speed` with at most maxForce per second, in the block: row by row, a
    // motor turning a point-like bob on a 1 m arm overshot its speed by 57 %, and one straining
    // against a stiff spring gained a sliver of its torque per pass. `apart`: the axis is locked
    // (limits of zero width), a rigid row along the same Jacobian that would make the block
    // singular; the motor is then solved here, row by row, and joins the block as a fixed row, so
    // the block's softness still counts its impulse (left out, a 1 000 N m motor straining
    // against a 1e6 N m/rad spring let a pin on a 1 m lever give 0.6 m).
    void motorRow(int slot, const Jacobian& j, const JointMotor& motor, bool apart) {
        if (mode_ == Mode::Position) return;  // a motor drives velocity only
        const double most = motor.maxForce * p_.h;
        if (apart) row(slot, j, {-motor.speed, 1.0, 0.0}, -most, most);
        locks_[lockCount_++] = {j, -motor.speed, slot, apart ? Row::MotorApart : Row::Motor, 0.0, most};
    }
    // Spring-damper toward C = 0. It joins the joint's block: solved alone, its row turns the body
    // about its own centre, and at a long lever (a bob on a 1 m arm, 1 000 times its own inertia)
    // Gauss-Seidel between it and the pin did not settle a stiff spring in 2 s (PGS diverged).
    // The damping is implicit (on the velocity after the impulse). The stiffness is explicit
    // where the substep resolves the spring's own frequency: its impulse is -h k C from the
    // substep's start, kept through the relax pass, which is symplectic Euler and keeps an
    // undamped spring's energy. An implicit stiffness damps by itself, as if with h k N s/m: an
    // undamped 0.7 Hz slider spring kept 70 % of its swing after 10 s. A spring too stiff for
    // the substep stays implicit, where explicit steps would diverge. Decided once per substep,
    // at its warm start (for a hinge a 5 x 5 solve): the solve passes see the same pose, and the
    // relax passes, after the positions moved, keep that substep's law.
    void springRow(int slot, const Jacobian& j, double C, const JointSpringSI& spring) {
        if (mode_ == Mode::Position) return;  // a spring's error is its own to keep
        if (mode_ == Mode::WarmStart)
            joint_.springExplicit =
                spring.stiffness * p_.h * p_.h * springInverseMass(j) * springsOnBusierBody_ <= kExplicitSpring;
        const bool resolved = joint_.springExplicit;
        const double springDamping = spring.damping + (resolved ? 0.0 : p_.h * spring.stiffness);
        if (resolved && (mode_ == Mode::Relax || !(springDamping > 0.0))) {
            // The substep's stiffness impulse (undamped), or the solve pass's impulse kept.
            const double total = mode_ == Mode::Relax ? joint_.impulse[slot] : -p_.h * spring.stiffness * C;
            locks_[lockCount_++] = {j, total, slot, Row::SpringHeld};
            return;
        }
        if (!(springDamping > 0.0)) return;  // no spring: its impulse stays 0
        const double gamma = 1.0 / (p_.h * springDamping);
        if (!(gamma > 0.0)) return lock(slot, j, C);  // beyond double's range: rigid
        locks_[lockCount_++] = {j, C * p_.h * spring.stiffness * gamma, slot, Row::Spring, gamma};
    }
    // (omega h)^2 of a spring whose stiffness is stepped explicitly, times the count of springs on
    // its busier body: at most 0.5. Explicit stepping is stable while h^2 times the largest
    // eigenvalue of M^-1 K stays under 4; a body's springs together bound that by 1.5 times this
    // sum (a row sum of M^-1/2 K M^-1/2), so 0.75 at most. Counted per spring alone, twelve
    // springs on one light body diverged. The ODE and Box2D backends use the same rule.
    static constexpr double kExplicitSpring = 0.5;
    // The spring row's inverse mass for that rule: a hinge's with its pin and axis locks acting
    // (the Schur complement K_ss - K_sp K_pp^-1 K_ps), as a body on an arm turns about the pin
    // (a box on a 1 m arm: 150 times its own inertia; judged by the row alone, a 40 N m/rad
    // spring there was implicit at one substep and lost 95 % of its swing in 10 s). Other rows'
    // own, which their locks only lower.
    double springInverseMass(const Jacobian& spring) const {
        const double alone = inverseMass(spring, a_, b_);
        if (def_.type != JointType::Hinge) return alone;
        std::array<Jacobian, 5> pin;
        for (int k = 0; k < 3; ++k) pin[k] = linearRow(Vec3::Unit(k), rA_, rB_);
        pin[3] = angularRow(frameA_ * Vec3::UnitY());
        pin[4] = angularRow(frameA_ * Vec3::UnitZ());
        Eigen::Matrix<double, 5, 5> kpp;
        Eigen::Matrix<double, 5, 1> kps;
        for (int i = 0; i < 5; ++i) {
            kps[i] = coupling(pin[i], spring, a_, b_);
            for (int k = 0; k < 5; ++k) kpp(i, k) = coupling(pin[i], pin[k], a_, b_);
        }
        // A pin to the world holds fewer directions than it has rows: the least-squares solution.
        const Eigen::Matrix<double, 5, 1> x = kpp.completeOrthogonalDecomposition().solve(kps);
        if (!x.allFinite()) return alone;
        return std::clamp(alone - kps.dot(x), 0.0, alone);
    }
    // The axis rows of hinge, slider: limits, motor and spring on position C along j (`linear`:
    // a length, the slider's).
    void axisRows(const Jacobian& j, double position, bool linear) {
        if (def_.spring) springRow(kSpring, j, position, *def_.spring);
        const bool locked = def_.limits && def_.limits->upper - def_.limits->lower <= kLockedRange;
        if (def_.motor) motorRow(kMotor, j, *def_.motor, locked);
        if (def_.limits) {
            limitPair(kLower, kUpper, j, position, def_.limits->lower, def_.limits->upper, linear);
            Lock& stop = locks_[lockCount_ - 1];
            if (def_.motor && stop.row == Row::Limit)
                stop.motorSide = stop.j.angB.dot(j.angB) + stop.j.linB.dot(j.linB) > 0.0 ? 1.0 : -1.0;
        }
    }
    static Jacobian negate(const Jacobian& j) { return {-j.linA, -j.angA, -j.linB, -j.angB}; }

    // ---- the rigid rows and limits, solved together ---------------------------------------------
    // Anchor points, rotation and sliding locks, limits, the spring and the motor are gathered
    // and solved as one block per pass (K = J M^-1 J^T, at most 8 x 8: a hinge's or slider's five
    // locks, a limit, the spring and the motor). Row by row, Gauss-Seidel converges slowly where
    // a lever is long against a small inertia (a bob on a 1 m arm: m L^2 / I = 250): PGS with
    // Baumgarte went unstable out of a hinge's plane, and a hinge limit let the bob through.
    // Limits push only (impulse >= 0): a limit whose impulse would pull is fixed at 0 and the
    // rest solved again (an active set; at most one round per row); a motor past its bound is
    // held there the same way.
    static constexpr int kMaxLocks = 8;
    enum class Row {
        Rigid,       // C = 0, in the block's softness
        Limit,       // unilateral: C >= 0, impulse >= 0
        Spring,      // Cdot + bias + gamma impulse = 0: its own softness
        SpringHeld,  // an explicit spring's impulse, given (C holds the total); fixed in the block
        Motor,       // Cdot + bias = 0 (bias = -speed), impulse within +-most
        MotorApart,  // solved before the block (motorRow); fixed in it
    };
    struct Lock {
        Jacobian j;
        double C = 0.0;  // position error; a spring's or motor's row: its velocity bias
        int slot = 0;
        Row row = Row::Rigid;
        double gamma = 0.0;  // Spring
        double most = 0.0;   // Motor
        // A limit on the motor's axis: +1 or -1 as its Jacobian is the motor's or its negation.
        double motorSide = 0.0;
        // Soft step: the share of the velocity bias kept. Below 1 on an anchor's rows whose error
        // the bias would close faster than JointSolveParams::anchorPushMaxVelocity.
        double biasScale = 1.0;
        // Spring and motor rows keep their own law, outside the block's softness.
        bool ownLaw() const { return row == Row::Spring || row == Row::Motor; }
    };
    void lock(int slot, const Jacobian& j, double C, double biasScale = 1.0) {
        locks_[lockCount_++] = {.j = j, .C = C, .slot = slot, .row = Row::Rigid, .biasScale = biasScale};
    }
    // The bias scale that keeps an anchor error of this length (m) closing at most at
    // anchorPushMaxVelocity. A pendulum's bob set 3 m off was pulled back at the softness' rate
    // times the error, 400 m/s: light to turn on its 1 m lever, it turned half a radian a
    // substep, the relax pass took back only the part along the turned rows, and it circled at
    // 226 m/s.
    double anchorBiasScale(double error) const {
        const double pull = p_.softness.biasRate * std::abs(error);  // m/s
        return pull > p_.anchorPushMaxVelocity ? p_.anchorPushMaxVelocity / pull : 1.0;
    }
    // The velocity bias of a lock's row (Cdot + bias -> 0) in this pass.
    double lockBias(const Lock& l, const Bias& soft) const {
        const bool ahead = l.row == Row::Limit && l.C > 0.0;
        if (l.ownLaw()) return l.C;
        // A limit short of its stop may close the gap, not pass it: the velocity passes allow
        // C / h, the position pass C (all of it, else a stop ahead of a turn held it back).
        if (ahead) return mode_ == Mode::Position ? l.C : l.C * p_.invH;
        return mode_ == Mode::Position ? soft.bias * l.C : soft.bias * l.biasScale * l.C;
    }

    void solveLocks() {
        const int n = lockCount_;
        lockCount_ = 0;
        if (n == 0) return;
        if (mode_ == Mode::WarmStart) {
            for (int i = 0; i < n; ++i)
                if (locks_[i].row != Row::MotorApart) apply(locks_[i].j, joint_.impulse[locks_[i].slot], a_, b_);
            return;
        }
        using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxLocks, kMaxLocks>;
        using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLocks, 1>;
        Block K(n, n);
        Column rhs(n), acc(n);
        // Softness is the block's (uniform); the velocity bias is each row's. A limit short of
        // its stop lets the gap close exactly this substep (speculative), as contacts do.
        const Bias soft = rigidBias(1.0);
        const double s = soft.massScale, t = soft.impulseScale;
        for (int i = 0; i < n; ++i) {
            const Jacobian& ji = locks_[i].j;
            const Vec3 la = a_.invMass.cwiseProduct(ji.linA), aa = a_.invI * ji.angA;
            const Vec3 lb = b_.invMass.cwiseProduct(ji.linB), ab = b_.invI * ji.angB;
            for (int k = i; k < n; ++k) {
                const Jacobian& jk = locks_[k].j;
                K(k, i) = K(i, k) = jk.linA.dot(la) + jk.angA.dot(aa) + jk.linB.dot(lb) + jk.angB.dot(ab);
            }
            rhs[i] = rate(ji, a_, b_) + lockBias(locks_[i], soft);
            acc[i] = mode_ == Mode::Position ? 0.0 : joint_.impulse[locks_[i].slot];
        }
        // The unknowns are z = delta + t acc (s + t = 1). Rigid rows: (K z)_rigid = -s rhs, the
        // block's soft step; its softness acts on all the joint's impulses, the spring's too, so
        // a pin gives only as much as its load asks (a spring row left out of it let a pin holding
        // a 1 m lever give 2 cm). A spring's row, K delta + gamma (acc + delta) = -rhs in its own
        // softness, written in z: (K z + gamma z)_spring = -rhs + t (K acc)_spring - s gamma acc;
        // a motor's the same with gamma 0. Without them A = K and the right side is -s rhs.
        Block A = K;
        Column right = -s * rhs;
        for (int i = 0; i < n; ++i) {
            if (!locks_[i].ownLaw()) continue;
            A(i, i) += locks_[i].gamma;
            right[i] = -rhs[i] + t * K.row(i).dot(acc) - s * locks_[i].gamma * acc[i];
        }
        // Solve A z = right over the free rows, with fixed rows' z moved to the right-hand side.
        // A row no body can answer (a planar body's tilt or lift) has no diagonal: it is left
        // out, at 0, rather than divided by a rounding residue.
        Column delta = Column::Zero(n);
        std::array<bool, kMaxLocks> fixed{};
        const double largest = K.diagonal().maxCoeff();
        for (int i = 0; i < n; ++i) {
            fixed[i] = locks_[i].row == Row::MotorApart || locks_[i].row == Row::SpringHeld || !(K(i, i) > 1e-12 * largest);
            if (locks_[i].row == Row::SpringHeld && K(i, i) > 1e-12 * largest) delta[i] = locks_[i].C - acc[i];
        }
        // A limit on the motor's axis would make the block singular beside it (one Jacobian, two
        // rigid rows). It starts released and joins only if the joint would pass it (below).
        int motor = -1, motorLimit = -1;
        for (int i = 0; i < n; ++i) {
            if (locks_[i].row == Row::Motor && !fixed[i]) motor = i;
            if (locks_[i].motorSide != 0.0 && !fixed[i]) motorLimit = i;
        }
        if (motor < 0) motorLimit = -1;
        if (motorLimit >= 0) {
            fixed[motorLimit] = true;
            delta[motorLimit] = -acc[motorLimit];
        }
        for (int round = 0; round <= n + 1; ++round) {
            int free[kMaxLocks], m = 0;
            for (int i = 0; i < n; ++i)
                if (!fixed[i]) free[m++] = i;
            if (m == 0) break;
            Block Af(m, m);
            Column r(m);
            for (int a = 0; a < m; ++a) {
                r[a] = right[free[a]];
                for (int i = 0; i < n; ++i)
                    if (fixed[i]) r[a] -= A(free[a], i) * (delta[i] + t * acc[i]);
                for (int b = 0; b < m; ++b) Af(a, b) = A(free[a], free[b]);
            }
            const Column y = Af.ldlt().solve(r);
            for (int a = 0; a < m; ++a) delta[free[a]] = std::isfinite(y[a]) ? y[a] - t * acc[free[a]] : 0.0;
            // Limits first: a limit that pulls is released and the rest solved again. Only then
            // is a motor held at its bound (a speculative stop pulling in the same round sent a
            // car's drive motor to full brake).
            bool clamped = false;
            for (Row kind : {Row::Limit, Row::Motor}) {
                for (int a = 0; a < m; ++a) {
                    const int i = free[a];
                    if (locks_[i].row != kind) continue;
                    const double total = acc[i] + delta[i];
                    const double bound = kind == Row::Limit ? std::max(total, 0.0)  // released: no pull
                                                            : std::clamp(total, -locks_[i].most, locks_[i].most);
                    if (bound == total) continue;
                    delta[i] = bound - acc[i];
                    fixed[i] = true;
                    clamped = true;
                }
                if (clamped) break;
            }
            if (clamped) continue;
            // The stop on the motor's axis, released so far: if the joint would pass it, it joins,
            // and the motor, which cannot then reach its speed, pushes toward that speed with all
            // it has (into the stop, or away from it where a heavier load holds the joint there).
            if (motorLimit < 0) break;
            const int l = motorLimit;
            motorLimit = -1;
            if (rhs[l] + K.row(l).dot(delta) >= 0.0) break;
            const Lock& stop = locks_[l];
            const double rateAtStop = -stop.motorSide * lockBias(stop, soft);
            fixed[l] = false;
            delta[l] = 0.0;
            fixed[motor] = true;
            const double most = locks_[motor].most;
            delta[motor] = (-locks_[motor].C > rateAtStop ? most : -most) - acc[motor];
        }
        for (int i = 0; i < n; ++i) {
            if (locks_[i].row == Row::MotorApart) continue;  // its delta is 0, its impulse summed
            apply(locks_[i].j, delta[i], a_, b_);
            if (mode_ == Mode::Position) continue;
            joint_.impulse[locks_[i].slot] += delta[i];
            sum(locks_[i].j, joint_.impulse[locks_[i].slot]);
        }
    }

    // Anchor coincidence: B's anchor on A's, along the world axes.
    void point() {
        const double scale = anchorBiasScale(d_.norm());  // one scale: the pull keeps its direction
        for (int k = 0; k < 3; ++k) lock(kPointX + k, linearRow(Vec3::Unit(k), rA_, rB_), d_[k], scale);
    }

    // No relative rotation: the rotation error of B's frame against A's as a small rotation
    // vector in the world, one row per world axis.
    void angularLock() {
        Quat rel = frameA_.conjugate() * frameB_;
        if (rel.w() < 0.0) rel.coeffs() = -rel.coeffs();
        const Vec3 error = frameA_ * (2.0 * rel.vec());
        for (int k = 0; k < 3; ++k) lock(kAngle0 + k, angularRow(Vec3::Unit(k)), error[k]);
    }

    // B turns relative to A about A's frame axis `free` only. With rel = (s, v) the rotation from
    // A's frame to B's, the two other components of v are held at zero: C = 2 v.e, whose exact
    // rate is (wB - wA) . frameA (s e + v x e). The lever |s e + v x e|^2 = 1 - (v.e)^2 stays near
    // full at wide errors (the small-angle rows axis . yB lost it: an elbow wrenched 70 degrees in
    // a ragdoll pile asked for 400 rad/s through a row of a third of its strength and the pile blew
    // up). The rows are the gradient of their error: their impulses do no work on a motion that
    // keeps it (the free turn), and the hinge has one rest pose (those rows also rested with B
    // turned right over).
    void hingeLocks(int free) {
        const Quat rel = frameA_.conjugate() * frameB_;
        const Vec3 v = rel.vec();
        int slot = kAngle0;
        for (int k = 0; k < 3; ++k) {
            if (k == free) continue;
            const Vec3 e = Vec3::Unit(k);
            lock(slot++, angularRow(frameA_ * (rel.w() * e + v.cross(e))), 2.0 * v[k]);
        }
    }

    // B's anchor stays on A's line along frame X (slider) or along the suspension (wheel).
    void slidingLocks() {
        const Vec3 y = frameA_ * Vec3::UnitY(), z = frameA_ * Vec3::UnitZ();
        const double scale = anchorBiasScale(std::hypot(d_.dot(y), d_.dot(z)));
        lock(kLinear0, linearRow(y, rA_ + d_, rB_), d_.dot(y), scale);
        lock(kLinear1, linearRow(z, rA_ + d_, rB_), d_.dot(z), scale);
    }

    void coneLimits() {
        const Vec3 xA = axisX(), xB = frameB_ * Vec3::UnitX();
        if (def_.swingLimit < kPi) {
            const Vec3 bend = xA.cross(xB);
            const double sine = bend.norm();
            if (sine > 1e-9) {
                const Vec3 n = bend / sine;  // swing grows as B turns about n relative to A
                const double swing = std::atan2(sine, xA.dot(xB));
                limitRow(kLower, {Vec3::Zero(), n, Vec3::Zero(), -n}, def_.swingLimit - swing);
            }
        }
        if (def_.twistLimits) {
            // Twist: the part about X of rel = swing * twist. It turns about the axis halfway
            // between A's and B's X axes (turning about A's axis alone is off by the swing, which
            // at a wide swing fed the limit the wrong rate: a ragdoll's shoulders pulled apart).
            // Near a half-turn swing the twist has no meaning: its rows rest.
            const Quat rel = frameA_.conjugate() * frameB_;
            const Vec3 half = xA + xB;
            if (std::hypot(rel.w(), rel.x()) > 0.05 && half.squaredNorm() > 1e-6) {
                const double twist = wrap(2.0 * std::atan2(rel.x(), rel.w()));
                limitPair(kTwistLower, kTwistUpper, angularRow(half.normalized()), twist, def_.twistLimits->lower,
                          def_.twistLimits->upper);
            } else {
                releaseImpulse(kTwistLower);
                releaseImpulse(kTwistUpper);
            }
        }
    }

    void distance() {
        const double length = d_.norm();
        if (length < 1e-9) return;  // no direction to push along
        const Vec3 n = d_ / length;
        const Jacobian j = linearRow(n, rA_, rB_);
        const double C = length - def_.length;
        const bool range = def_.minLength || def_.maxLength;
        if (def_.spring) springRow(kSpring, j, C, *def_.spring);
        else if (!range) lock(kLength, j, C, anchorBiasScale(C));
        if (def_.minLength && def_.maxLength)
            limitPair(kLower, kUpper, j, length, *def_.minLength, *def_.maxLength, true);
        else if (def_.minLength)
            limitRow(kLower, j, length - *def_.minLength, anchorBiasScale(length - *def_.minLength));
        else if (def_.maxLength)
            limitRow(kUpper, negate(j), *def_.maxLength - length, anchorBiasScale(*def_.maxLength - length));
    }

    void wheel() {
        const Vec3 s = axisX();  // suspension
        const Vec3 axle = this->axle();
        const double travel = d_.dot(s);
        const Jacobian along = linearRow(s, rA_ + d_, rB_);
        if (def_.spring) springRow(kSpring, along, travel, *def_.spring);
        if (def_.limits) {
            limitPair(kLower, kUpper, along, travel, def_.limits->lower, def_.limits->upper, true);
        }
        if (def_.motor) motorRow(kMotor, angularRow(axle), *def_.motor, false);  // limits are the suspension's
        hingeLocks(1);  // about the axle, frame Y
        const Vec3 z = frameA_ * Vec3::UnitZ();
        const double scale = anchorBiasScale(std::hypot(d_.dot(axle), d_.dot(z)));
        lock(kLinear0, linearRow(axle, rA_ + d_, rB_), d_.dot(axle), scale);
        lock(kLinear1, linearRow(z, rA_ + d_, rB_), d_.dot(z), scale);
    }

    void sum(const Jacobian& j, double impulse) {
        if (!endOfSubstep_) return;
        joint_.stepLinear += impulse * j.linB;
        joint_.stepAngular += impulse * j.angB;
    }

    NativeJoint& joint_;
    const JointPeerDef& def_;
    const JointSolveParams& p_;
    Mode mode_;
    int springsOnBusierBody_;
    Side a_, b_;
    Quat frameA_, frameB_;
    Vec3 rA_ = Vec3::Zero(), rB_ = Vec3::Zero(), d_ = Vec3::Zero();
    bool useBias_ = false;
    bool endOfSubstep_ = false;
    std::array<Lock, kMaxLocks> locks_;
    int lockCount_ = 0;
};

}  // namespace

void warmStartJoint(const JointConstraint& c, const SolverBody* bodies, SolverState* states, const JointSolveParams& p) {
    NativeJoint& j = *c.joint;
    if (j.solvedImpulseFresh) j.impulse = j.solvedImpulse;
    j.solvedImpulseFresh = false;
    JointPass pass(c, bodies, states, p, Mode::WarmStart);
    pass.run(false, false);
    pass.finish(states);
}

void solveJoint(const JointConstraint& c, const SolverBody* bodies, SolverState* states, const JointSolveParams& p,
                bool useBias, bool endOfSubstep) {
    JointPass pass(c, bodies, states, p, useBias ? Mode::Solve : Mode::Relax);
    pass.run(useBias, endOfSubstep);
    pass.finish(states);
}

void correctJointPosition(const JointConstraint& c, const SolverBody* bodies, SolverState* states, const JointSolveParams& p) {
    c.joint->solvedImpulse = c.joint->impulse;
    c.joint->solvedImpulseFresh = true;
    JointPass pass(c, bodies, states, p, Mode::Position);
    pass.run(false, false);
    pass.finish(states);
}

void reportJoint(const JointConstraint& c, const SolverBody* bodies, const SolverState* states, double dt) {
    NativeJoint& j = *c.joint;
    const JointSolveParams none;
    const JointPass pass(c, bodies, states, none, Mode::Relax);
    j.reactionForce = j.stepLinear / dt;
    j.reactionTorque = (j.stepAngular - pass.rB().cross(j.stepLinear)) / dt;
    j.stepLinear.setZero();
    j.stepAngular.setZero();
    const Vec3 relW = pass.b().w - pass.a().w;
    switch (j.def.type) {
        case JointType::Hinge:
            j.position = pass.hingeAngle();
            j.speed = relW.dot(pass.axisX());
            break;
        case JointType::Slider: {
            const Vec3 x = pass.axisX();
            j.position = pass.separation().dot(x);
            // d/dt (d . x) with x turning with A: B's anchor against A's point under it.
            const Vec3 vA = pass.a().v + pass.a().w.cross(pass.rA() + pass.separation());
            const Vec3 vB = pass.b().v + pass.b().w.cross(pass.rB());
            j.speed = (vB - vA).dot(x);
            break;
        }
        case JointType::Wheel:
            j.position = pass.separation().dot(pass.axisX());
            j.speed = relW.dot(pass.axle());
            break;
        case JointType::Distance: {
            const double length = pass.separation().norm();
            j.position = length - j.def.length;
            const Vec3 vB = pass.b().v + pass.b().w.cross(pass.rB());
            const Vec3 vA = pass.a().v + pass.a().w.cross(pass.rA());
            j.speed = length > 1e-12 ? (vB - vA).dot(pass.separation() / length) : 0.0;
            break;
        }
        case JointType::Ball:
        case JointType::Cone: {
            const double previous = j.position;
            j.position = pass.swingAngle();
            j.speed = (j.position - previous) / dt;
            break;
        }
        case JointType::Fixed:
            j.position = 0.0;
            j.speed = 0.0;
            break;
    }
}

}  // namespace anyphys::native

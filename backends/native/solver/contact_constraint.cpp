#include "solver/contact_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contacts.hpp"
#include "solver/prefetch.hpp"
#include "solver/restitution_math.hpp"

namespace anyphys::native {

using namespace wide;

Softness makeSoftness(double hertz, double zeta, double h) {
    if (hertz == 0.0) return {};
    const double omega = 2.0 * std::numbers::pi * hertz;
    const double a1 = 2.0 * zeta + h * omega;
    const double a2 = h * omega * a1;
    const double a3 = 1.0 / (1.0 + a2);
    return {omega / a1, a2 * a3, a3};
}

Softness contactSoftness(const ContactPrepareParams& params, bool againstStatic, const ContactManifold& m, double invMassA,
                         double invMassB) {
    // Contacts with static bodies are already twice as stiff; stiffening them with their load too
    // opened the joints of a pinched ragdoll pile (median worst gap 31.7 -> 49.6 mm of 50).
    if (againstStatic) return params.staticSoftness;
    const LoadStiffening& load = params.load;
    const double invPairMass = invMassA + invMassB;
    if (!params.warmStart || load.gravity <= 0.0 || load.hertz <= 0.0 || invPairMass <= 0.0) return params.dynamicSoftness;
    const double ratio = m.carriedImpulse() * invPairMass / (load.gravity * load.h);  // carried mass / pair mass
    if (ratio <= 1.0) return params.dynamicSoftness;
    return makeSoftness(std::min(load.maxHertz, load.hertz * std::sqrt(ratio)), load.dampingRatio, load.h);
}

double restitutionTarget(const ContactPrepareParams& params, double e, double s, double vn, double an, double slide) {
    // Gravity (or any relative acceleration) speeds the approach until the surfaces meet, part way
    // into the step: a bounce off the step-start speed rebounds low (2 % of the height for a ball
    // landing at 9 m/s, on every integrator).
    const double trueApproach = vn - an * params.velocityTimeOffset;
    const double impact = timeToImpact(s, -trueApproach, -an, params.stepTime);
    // The solver's substeps are semi-implicit Euler: their velocity lags by half a substep.
    return bounceVelocity(e, {.vn = vn,
                              .an = an,
                              .impact = impact,
                              .offset = params.velocityTimeOffset,
                              .solverOffset = -0.5 * params.substep,
                              .margin = params.speculativeDistance,
                              .h = params.stepTime,
                              .gap = substepGapAtStepEnd(s, vn, an, params.stepTime, params.substep),
                              .lateGap = gapAtStepEnd(s, -trueApproach, -an, params.stepTime),
                              .slide = slide});
}

namespace {

// ---- preparing one lane (scalar) ---------------------------------------------------------------

Vec3 perpendicular(const Vec3& n) {
    // In a planar world the normal lies in XY: this picks the in-plane tangent first, the
    // locked Z direction second.
    const Vec3 axis = std::abs(n.z()) < 0.57735 ? Vec3::UnitZ() : Vec3::UnitX();
    return axis.cross(n).normalized();
}

// Inverse of a symmetric 2x2 matrix; a direction with no mass (a planar body's Z) gets none.
// "No mass" is relative: a direction a billion times lighter than the other is rounding noise,
// and inverting it would give huge entries and a huge impulse along it.
void invertTangentMass(double k11, double k12, double k22, double out[3]) {
    const double scale = std::max(k11, k22);
    const bool has1 = k11 > 1e-9 * scale, has2 = k22 > 1e-9 * scale;
    const double det = k11 * k22 - k12 * k12;
    if (has1 && has2 && det > 1e-12 * k11 * k22) {
        const double inv = 1.0 / det;
        out[0] = inv * k22;
        out[1] = -inv * k12;
        out[2] = inv * k11;
        return;
    }
    out[0] = has1 ? 1.0 / k11 : 0.0;
    out[1] = 0.0;
    out[2] = has2 ? 1.0 / k22 : 0.0;
}

void setLane(Vec3W& to, int lane, const Vec3& v) {
    to.x[lane] = v.x();
    to.y[lane] = v.y();
    to.z[lane] = v.z();
}

void setLane(SymMat3W& to, int lane, const Mat3& m) {
    to.xx[lane] = m(0, 0);
    to.xy[lane] = m(0, 1);
    to.xz[lane] = m(0, 2);
    to.yy[lane] = m(1, 1);
    to.yz[lane] = m(1, 2);
    to.zz[lane] = m(2, 2);
}

struct BodyView {
    Vec3 invMass = Vec3::Zero();
    Mat3 invI = Mat3::Zero();
    Vec3 center = Vec3::Zero();
    Vec3 v = Vec3::Zero(), w = Vec3::Zero();
    Vec3 acceleration = Vec3::Zero();  // SolverBody::bounceAcceleration (restitution)
    bool moves = false;  // has a solver state (dynamic or kinematic)
};

// viewOf and effectiveMass are forced inline: called out of line (GCC chose to, at -O3), the body
// views went through the stack on every call, and the two took a third of the prepare stage's
// samples (pyramid3d).
[[gnu::always_inline]] inline BodyView viewOf(std::int32_t index, const SolverBody* bodies, const SolverState* states) {
    BodyView view;
    if (index == kStaticBody) return view;
    const SolverBody& b = bodies[index];
    const SolverState& s = states[index];
    view.invMass = b.invMass;
    view.invI = b.invInertia;
    view.center = b.position0;
    view.v = Vec3(s.v[0], s.v[1], s.v[2]);
    view.w = Vec3(s.w[0], s.w[1], s.w[2]);
    view.acceleration = b.bounceAcceleration;
    view.moves = true;
    return view;
}

[[gnu::always_inline]] inline double effectiveMass(const BodyView& a, const Vec3& rA, const BodyView& b, const Vec3& rB,
                                                   const Vec3& dir) {
    const Vec3 ra = rA.cross(dir), rb = rB.cross(dir);
    return dir.dot(a.invMass.cwiseProduct(dir)) + dir.dot(b.invMass.cwiseProduct(dir)) + ra.dot(a.invI * ra) +
           rb.dot(b.invI * rb);
}

void prepareLane(WideContact& wc, WideContactCold& cold, int lane, const ContactLane& in, const SolverBody* bodies,
                 const SolverState* states, const ContactPrepareParams& params) {
    ContactManifold& m = *in.manifold;
    const BodyView a = viewOf(in.bodyA, bodies, states), b = viewOf(in.bodyB, bodies, states);
    wc.bodyA[lane] = in.bodyA;
    wc.bodyB[lane] = in.bodyB;
    wc.writeA[lane] = in.bodyA != kStaticBody && bodies[in.bodyA].dynamic;
    wc.writeB[lane] = in.bodyB != kStaticBody && bodies[in.bodyB].dynamic;
    wc.unjointed[lane] = !heldByJoint(bodies, in.bodyA) && !heldByJoint(bodies, in.bodyB);
    wc.multiPoint[lane] = m.pointCount > 1;
    wc.turnArmA[lane] = turnsFrictionArm(in, in.bodyA, bodies, a.w.norm() * params.stepTime);
    wc.turnArmB[lane] = turnsFrictionArm(in, in.bodyB, bodies, b.w.norm() * params.stepTime);
    wc.turnsArms = wc.turnsArms || wc.turnArmA[lane] || wc.turnArmB[lane];
    cold.manifold[lane] = &m;
    wc.pointCount = std::max(wc.pointCount, m.pointCount);

    wc.invMassA[lane] = a.invMass.x();
    wc.invMassB[lane] = b.invMass.x();
    setLane(wc.invIA, lane, a.invI);
    setLane(wc.invIB, lane, b.invI);
    const Vec3 n = m.normal;
    const Vec3 t1 = perpendicular(n), t2 = n.cross(t1);
    setLane(wc.normal, lane, n);
    setLane(wc.tangent1, lane, t1);
    wc.friction[lane] = in.friction;
    cold.restitution[lane] = in.restitution;
    const bool againstStatic = a.invMass.isZero(0) || b.invMass.isZero(0);
    const Softness soft = contactSoftness(params, againstStatic, m, a.invMass.x(), b.invMass.x());
    wc.biasRate[lane] = soft.biasRate;
    wc.massScale[lane] = soft.massScale;
    wc.impulseScale[lane] = soft.impulseScale;

    const double normalAcceleration = n.dot(b.acceleration - a.acceleration);
    // A bounce's target only where the pair can bounce: the restitution stage skips the others.
    const bool bounces = in.restitution > 0.0;
    const Vec3 relative = b.v - a.v;
    const double slide = bounces ? (relative - n.dot(relative) * n).norm() : 0.0;  // the bodies' speed along the surface
    const double invTau = params.speculativeDistance > 0.0 ? 1.0 / params.speculativeDistance : 0.0;
    Vec3 center = Vec3::Zero();
    double totalWeight = 0.0, gap = 0.0;
    for (int i = 0; i < m.pointCount; ++i) {
        const ContactPointState& mp = m.points[i];
        WideContactPoint& cp = wc.points[i];
        const Vec3 p = mp.geometry.point;
        // A static body's anchor is the point itself (zero offset): it never moves or turns.
        // A round shape's anchor lies on its core (contactAnchor), where turning the body does not
        // move the surface: a ball's surface point turned with the ball rose, so the contact
        // unloaded within each step, the ball sank and a sliding one lost speed 28 % faster than
        // mu g.
        // The narrow phase placed both (ContactManager), and a recycled manifold keeps them.
        const Vec3 rA = a.moves ? mp.anchorA : Vec3::Zero();
        const Vec3 rB = b.moves ? mp.anchorB : Vec3::Zero();
        setLane(cp.anchorA, lane, rA);
        setLane(cp.anchorB, lane, rB);
        const double s = mp.geometry.separation;
        cp.baseSeparation[lane] = s - n.dot(rB - rA);
        const double k = effectiveMass(a, rA, b, rB, n);
        cp.normalMass[lane] = k > 0.0 ? 1.0 / k : 0.0;
        cp.normalImpulse[lane] = params.warmStart ? mp.normalImpulse : 0.0;
        cp.stepImpulse[lane] = 0.0;
        cp.maxImpulse[lane] = 0.0;
        const double vn = n.dot(b.v + b.w.cross(rB) - a.v - a.w.cross(rA));
        cold.relativeVelocity[i][lane] = vn;
        cold.touching[i][lane] = s <= params.linearSlop ? -1 : 0;
        cold.restitutionTarget[i][lane] = bounces ? restitutionTarget(params, in.restitution, s, vn, normalAcceleration, slide) : 0.0;
        // Points well beyond the speculative distance only matter for fast approach; they
        // must not pull the friction centre around as they come and go.
        const double weight = std::clamp(2.0 - s * invTau, 1e-3, 1.0);
        center += weight * p;
        gap += weight * s;
        totalWeight += weight;
    }
    center /= totalWeight;
    gap /= totalWeight;
    for (int i = 0; i < m.pointCount; ++i) wc.points[i].leverArm[lane] = (m.points[i].geometry.point - center).norm();
    // Friction acts where the surfaces touch: each body's anchor is on its own surface, half the
    // gap from the midway point. At the midway point, a ball landing from a speculative contact
    // took its friction 2.5 cm below its surface and left sliding and over-spun.
    const Vec3 cA = a.moves ? Vec3(center - 0.5 * gap * n - a.center) : Vec3::Zero();
    const Vec3 cB = b.moves ? Vec3(center + 0.5 * gap * n - b.center) : Vec3::Zero();
    setLane(wc.centerA, lane, cA);
    setLane(wc.centerB, lane, cB);

    const Vec3 a1 = cA.cross(t1), a2 = cA.cross(t2), b1 = cB.cross(t1), b2 = cB.cross(t2);
    const double k11 = effectiveMass(a, cA, b, cB, t1);
    const double k22 = effectiveMass(a, cA, b, cB, t2);
    const double k12 = t1.dot(a.invMass.cwiseProduct(t2)) + t1.dot(b.invMass.cwiseProduct(t2)) + a1.dot(a.invI * a2) +
                       b1.dot(b.invI * b2);
    double tangentMass[3];
    invertTangentMass(k11, k12, k22, tangentMass);
    wc.tangentMass.xx[lane] = tangentMass[0];
    wc.tangentMass.xy[lane] = tangentMass[1];
    wc.tangentMass.yy[lane] = tangentMass[2];
    const double kt = n.dot((a.invI + b.invI) * n);
    wc.twistMass[lane] = kt > 0.0 ? 1.0 / kt : 0.0;
    const double warm = params.warmStart ? 1.0 : 0.0;
    wc.frictionImpulse1[lane] = warm * t1.dot(m.frictionImpulse);
    wc.frictionImpulse2[lane] = warm * t2.dot(m.frictionImpulse);
    wc.twistImpulse[lane] = warm * m.twistImpulse;
}

}  // namespace

void prepareContacts(WideContact& wc, WideContactCold& cold, const ContactLane* lanes, int count,
                     const SolverBody* bodies, const SolverState* states, const ContactPrepareParams& params) {
    wc = WideContact{};
    cold = WideContactCold{};
    for (int lane = 0; lane < kLanes; ++lane) {
        wc.bodyA[lane] = wc.bodyB[lane] = kStaticBody;
        wc.massScale[lane] = 1.0;
    }
    for (int lane = 0; lane < count; ++lane) prepareLane(wc, cold, lane, lanes[lane], bodies, states, params);
}

void storeImpulses(const WideContact* contacts, const WideContactCold* cold, int count) {
    for (int i = 0; i < count; ++i) {
        if (i + kRecordsAhead < count)
            for (ContactManifold* m : cold[i + kRecordsAhead].manifold)
                if (m) prefetchBytes<true>(m, sizeof(ContactManifold));
        const WideContact& c = contacts[i];
        const Vec3W tangent2 = secondTangent(c);
        for (int lane = 0; lane < kLanes; ++lane) {
            ContactManifold* m = cold[i].manifold[lane];
            if (!m) continue;
            for (int j = 0; j < m->pointCount; ++j) {
                m->points[j].normalImpulse =
                    storedNormalImpulse(cold[i], j, lane, c.points[j].normalImpulse[lane], m->points[j].normalImpulse);
                m->points[j].stepImpulse = c.points[j].stepImpulse[lane];
            }
            const Vec3 t1(c.tangent1.x[lane], c.tangent1.y[lane], c.tangent1.z[lane]);
            const Vec3 t2(tangent2.x[lane], tangent2.y[lane], tangent2.z[lane]);
            m->frictionImpulse = c.frictionImpulse1[lane] * t1 + c.frictionImpulse2[lane] * t2;
            m->twistImpulse = c.twistImpulse[lane];
        }
    }
}

}  // namespace anyphys::native

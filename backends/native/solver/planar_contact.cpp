// Preparing and storing planar contact constraints (scalar, once per step; see planar_contact.hpp).
#include "solver/planar_contact.hpp"

#include <algorithm>
#include <cmath>

#include "contacts.hpp"

namespace anyphys::native {

namespace {

struct PlanarView {
    double invMass = 0.0, invI = 0.0;
    double cx = 0.0, cy = 0.0;             // centre of mass
    double vx = 0.0, vy = 0.0, w = 0.0;
    double ax = 0.0, ay = 0.0;             // SolverBody::bounceAcceleration (restitution)
    bool moves = false;
};

PlanarView planarViewOf(std::int32_t index, const SolverBody* bodies, const SolverState* states) {
    PlanarView view;
    if (index == kStaticBody) return view;
    const SolverBody& b = bodies[index];
    const SolverState& s = states[index];
    view.invMass = b.invMass.x();
    view.invI = b.invInertia(2, 2);
    view.cx = b.position0.x();
    view.cy = b.position0.y();
    view.vx = s.v[0];
    view.vy = s.v[1];
    view.w = s.w[2];
    view.ax = b.bounceAcceleration.x();
    view.ay = b.bounceAcceleration.y();
    view.moves = true;
    return view;
}

double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

void prepareLane(PlanarContact& pc, PlanarContactCold& cold, int lane, const ContactLane& in, const SolverBody* bodies,
                 const SolverState* states, const ContactPrepareParams& params) {
    ContactManifold& m = *in.manifold;
    const PlanarView a = planarViewOf(in.bodyA, bodies, states), b = planarViewOf(in.bodyB, bodies, states);
    pc.bodyA[lane] = in.bodyA;
    pc.bodyB[lane] = in.bodyB;
    pc.writeA[lane] = in.bodyA != kStaticBody && bodies[in.bodyA].dynamic;
    pc.writeB[lane] = in.bodyB != kStaticBody && bodies[in.bodyB].dynamic;
    pc.unjointed[lane] = !heldByJoint(bodies, in.bodyA) && !heldByJoint(bodies, in.bodyB);
    pc.multiPoint[lane] = m.pointCount > 1;
    pc.turnArmA[lane] = turnsFrictionArm(in, in.bodyA, bodies, std::abs(a.w) * params.stepTime);
    pc.turnArmB[lane] = turnsFrictionArm(in, in.bodyB, bodies, std::abs(b.w) * params.stepTime);
    pc.turnsArms = pc.turnsArms || pc.turnArmA[lane] || pc.turnArmB[lane];
    cold.manifold[lane] = &m;
    pc.pointCount = std::max(pc.pointCount, m.pointCount);
    pc.invMassA[lane] = a.invMass;
    pc.invMassB[lane] = b.invMass;
    pc.invIA[lane] = a.invI;
    pc.invIB[lane] = b.invI;
    // The narrow phase put the normal in the plane (flattenPlanarManifold).
    const double nx = m.normal.x(), ny = m.normal.y();
    const double tx = -ny, ty = nx;
    pc.normalX[lane] = nx;
    pc.normalY[lane] = ny;
    pc.friction[lane] = in.friction;
    cold.restitution[lane] = in.restitution;
    const bool againstStatic = a.invMass == 0.0 || b.invMass == 0.0;
    const Softness soft = contactSoftness(params, againstStatic, m, a.invMass, b.invMass);
    pc.biasRate[lane] = soft.biasRate;
    pc.massScale[lane] = soft.massScale;
    pc.impulseScale[lane] = soft.impulseScale;

    const double normalAcceleration = nx * (b.ax - a.ax) + ny * (b.ay - a.ay);
    // A bounce's target only where the pair can bounce: the restitution stage skips the others.
    const bool bounces = in.restitution > 0.0;
    const double slide = std::abs(-ny * (b.vx - a.vx) + nx * (b.vy - a.vy));  // the bodies' speed along the surface
    const double invTau = params.speculativeDistance > 0.0 ? 1.0 / params.speculativeDistance : 0.0;
    double centerX = 0.0, centerY = 0.0, totalWeight = 0.0, gap = 0.0;
    for (int i = 0; i < m.pointCount; ++i) {
        const ContactPointState& mp = m.points[i];
        PlanarContactPoint& cp = pc.points[i];
        const double px = mp.geometry.point.x(), py = mp.geometry.point.y();
        // A static body's anchor is the point itself (zero offset): it never moves or turns. A
        // round shape's anchor lies on its core, as in the 3D path (contact_constraint.cpp).
        const Vec3 rA = a.moves ? mp.anchorA : Vec3::Zero();
        const Vec3 rB = b.moves ? mp.anchorB : Vec3::Zero();
        const double rAx = rA.x(), rAy = rA.y(), rBx = rB.x(), rBy = rB.y();
        cp.anchorAx[lane] = rAx;
        cp.anchorAy[lane] = rAy;
        cp.anchorBx[lane] = rBx;
        cp.anchorBy[lane] = rBy;
        const double s = mp.geometry.separation;
        cp.baseSeparation[lane] = s - (nx * (rBx - rAx) + ny * (rBy - rAy));
        const double rnA = cross2(rAx, rAy, nx, ny), rnB = cross2(rBx, rBy, nx, ny);
        const double k = a.invMass + b.invMass + a.invI * rnA * rnA + b.invI * rnB * rnB;
        cp.normalMass[lane] = k > 0.0 ? 1.0 / k : 0.0;
        cp.normalImpulse[lane] = params.warmStart ? mp.normalImpulse : 0.0;
        cp.maxImpulse[lane] = 0.0;
        cp.stepImpulse[lane] = 0.0;
        const double vn = nx * ((b.vx - b.w * rBy) - (a.vx - a.w * rAy)) + ny * ((b.vy + b.w * rBx) - (a.vy + a.w * rAx));
        cold.relativeVelocity[i][lane] = vn;
        cold.touching[i][lane] = s <= params.linearSlop ? -1 : 0;
        cold.restitutionTarget[i][lane] = bounces ? restitutionTarget(params, in.restitution, s, vn, normalAcceleration, slide) : 0.0;
        // Points well beyond the speculative distance must not pull the friction centre around.
        const double weight = std::clamp(2.0 - s * invTau, 1e-3, 1.0);
        centerX += weight * px;
        centerY += weight * py;
        gap += weight * s;
        totalWeight += weight;
    }
    centerX /= totalWeight;
    centerY /= totalWeight;
    gap /= totalWeight;
    // Each body's friction anchor on its own surface, half the gap from the midway point (as in 3D).
    const double halfGapX = 0.5 * gap * nx, halfGapY = 0.5 * gap * ny;
    const double cAx = a.moves ? centerX - halfGapX - a.cx : 0.0, cAy = a.moves ? centerY - halfGapY - a.cy : 0.0;
    const double cBx = b.moves ? centerX + halfGapX - b.cx : 0.0, cBy = b.moves ? centerY + halfGapY - b.cy : 0.0;
    pc.centerAx[lane] = cAx;
    pc.centerAy[lane] = cAy;
    pc.centerBx[lane] = cBx;
    pc.centerBy[lane] = cBy;
    const double rtA = cross2(cAx, cAy, tx, ty), rtB = cross2(cBx, cBy, tx, ty);
    const double kt = a.invMass + b.invMass + a.invI * rtA * rtA + b.invI * rtB * rtB;
    pc.tangentMass[lane] = kt > 0.0 ? 1.0 / kt : 0.0;
    pc.frictionImpulse[lane] = params.warmStart ? tx * m.frictionImpulse.x() + ty * m.frictionImpulse.y() : 0.0;
}

}  // namespace

void preparePlanarContacts(PlanarContact& pc, PlanarContactCold& cold, const ContactLane* lanes, int count,
                           const SolverBody* bodies, const SolverState* states, const ContactPrepareParams& params) {
    pc = PlanarContact{};
    cold = PlanarContactCold{};
    for (int lane = 0; lane < wide::kLanes; ++lane) {
        pc.bodyA[lane] = pc.bodyB[lane] = kStaticBody;
        pc.massScale[lane] = 1.0;
    }
    for (int lane = 0; lane < count; ++lane) prepareLane(pc, cold, lane, lanes[lane], bodies, states, params);
}

void storePlanarImpulses(const PlanarContact* contacts, const PlanarContactCold* cold, int count) {
    for (int i = 0; i < count; ++i) {
        const PlanarContact& c = contacts[i];
        for (int lane = 0; lane < wide::kLanes; ++lane) {
            ContactManifold* m = cold[i].manifold[lane];
            if (!m) continue;
            for (int j = 0; j < m->pointCount; ++j) {
                m->points[j].normalImpulse =
                    storedNormalImpulse(cold[i], j, lane, c.points[j].normalImpulse[lane], m->points[j].normalImpulse);
                m->points[j].stepImpulse = c.points[j].stepImpulse[lane];
            }
            const double f = c.frictionImpulse[lane];
            m->frictionImpulse = Vec3(-c.normalY[lane] * f, c.normalX[lane] * f, 0.0);
            m->twistImpulse = 0.0;
        }
    }
}

}  // namespace anyphys::native

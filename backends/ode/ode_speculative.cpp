#include "ode_speculative.hpp"

#include <algorithm>
#include <cmath>

#include "ode_ahead_sweep.hpp"
#include "ode_body.hpp"
#include "ode_math.hpp"
#include "ode_shapes.hpp"
#include "ode_slip_friction.hpp"
#include "ode_tuning.hpp"
#include "ode_world.hpp"

namespace anyphys::ode {
namespace {

struct Motion {
    Vec3 velocity = Vec3::Zero(), spin = Vec3::Zero(), centre = Vec3::Zero();
};

Motion motionOf(const OdeShape& shape) {
    Motion m;
    const dBodyID body = shape.owner() ? shape.owner()->id() : nullptr;
    if (!body) return m;  // static: a geom without a body
    m.velocity = toVec3(dBodyGetLinearVel(body));
    m.spin = toVec3(dBodyGetAngularVel(body));
    m.centre = toVec3(dBodyGetPosition(body));
    return m;
}

// The point of `shape`'s true surface nearest `p` on its side facing along -`normal` (ODE's normal
// points into the shape): a grown shape's contact lies on the grown surface, up to the growth
// outside the true one, where friction would have a longer lever.
Vec3 onTrueSurface(const OdeShape& shape, const Vec3& p, const Vec3& normal) {
    const dGeomID g = shape.geom();
    const Vec3 centre = toVec3(dGeomGetPosition(g));
    switch (shape.type()) {
        case ShapeType::Box: {
            dVector3 lengths;
            dGeomBoxGetLengths(g, lengths);
            const Mat3 axes = toMat3(dGeomGetRotation(g));
            Vec3 local = axes.transpose() * (p - centre);
            for (int k = 0; k < 3; ++k) local[k] = std::clamp(local[k], -0.5 * lengths[k], 0.5 * lengths[k]);
            return centre + axes * local;
        }
        case ShapeType::Sphere: return centre - dGeomSphereGetRadius(g) * normal;
        case ShapeType::Capsule: {
            dReal radius = 0, length = 0;
            dGeomCapsuleGetParams(g, &radius, &length);
            const Vec3 axis = toMat3(dGeomGetRotation(g)).col(2);  // ODE's capsules lie along their Z
            const double along = std::clamp((p - centre).dot(axis), -0.5 * length, 0.5 * length);
            return centre + along * axis - radius * normal;
        }
        default: return p;
    }
}

bool measurable(ShapeType type) {  // depthInside knows it
    return type == ShapeType::Box || type == ShapeType::Sphere || type == ShapeType::Capsule || type == ShapeType::Plane;
}

// How deep `p` lies inside `shape` (negative: outside, by the distance to its surface), for the
// measurable shapes.
double depthInside(const OdeShape& shape, const Vec3& p) {
    const dGeomID g = shape.geom();
    switch (shape.type()) {
        case ShapeType::Box: {
            // Not dGeomBoxPointDepth: outside, it gives the distance to the farthest face.
            dVector3 lengths;
            dGeomBoxGetLengths(g, lengths);
            const Vec3 local = toMat3(dGeomGetRotation(g)).transpose() * (p - toVec3(dGeomGetPosition(g)));
            const Vec3 beyond = local.cwiseAbs() - 0.5 * Vec3(lengths[0], lengths[1], lengths[2]);  // per axis, > 0 outside
            if (beyond.maxCoeff() <= 0.0) return -beyond.maxCoeff();
            return -beyond.cwiseMax(0.0).norm();
        }
        case ShapeType::Sphere: return dGeomSpherePointDepth(g, p.x(), p.y(), p.z());
        case ShapeType::Capsule: return dGeomCapsulePointDepth(g, p.x(), p.y(), p.z());
        case ShapeType::Plane: return dGeomPlanePointDepth(g, p.x(), p.y(), p.z());
        default: return 0.0;
    }
}

// How far a moving shape reaches from its body's centre of mass: the distance to the far corner
// of its bounds (ODE's order: min x, max x, min y, ...), so its spin moves no point of it faster
// than spin x reach.
double reachFromBounds(const dReal box[6], const Vec3& centre) {
    Vec3 farthest = Vec3::Zero();
    for (int k = 0; k < 3; ++k) farthest[k] = std::max(std::abs(box[2 * k] - centre[k]), std::abs(box[2 * k + 1] - centre[k]));
    return farthest.norm();
}

double shapeReach(const OdeShape& shape) {
    dReal box[6];
    dGeomGetAABB(shape.geom(), box);
    return reachFromBounds(box, motionOf(shape).centre);
}

}  // namespace

double stepApproach(const OdeShape& a, const OdeShape& b, double h) {
    const Motion ma = motionOf(a), mb = motionOf(b);
    double speed = (ma.velocity - mb.velocity).norm();
    if (ma.spin != Vec3::Zero()) speed += ma.spin.norm() * shapeReach(a);
    if (mb.spin != Vec3::Zero()) speed += mb.spin.norm() * shapeReach(b);
    return speed * h;
}

int speculativeContacts(NearProbe& probe, const OdeShape& a, const OdeShape& b, const StepAhead& step, dContact* out, int most) {
    const auto& [touching, fall, approach, slop, h] = step;
    const Motion ma = motionOf(a), mb = motionOf(b);
    // Where a ends the step relative to b (b's own turn left out: a first-order look ahead). ODE
    // moves the bodies with the step's last velocity, gravity's share included.
    const Vec3 move = (ma.velocity - mb.velocity + fall) * h;
    const double turnAngle = ma.spin.norm() * h;
    const Quat turn = turnAngle > 0.0 ? Quat(Eigen::AngleAxisd(turnAngle, ma.spin / ma.spin.norm())) : Quat::Identity();
    if (!touching && !probe.meetsAfter(a, ma.centre, move, turn, b, slop)) return 0;
    dContactGeom found[kMaxContactsPerPair];
    const int n = probe.collide(a, b, approach + slop, found, std::min(most, kMaxContactsPerPair));
    int kept = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 normal = toVec3(found[i].normal);  // into a
        // The grown shape's point taken back to a's true surface, and its own gap to b measured
        // there: a grown box is wide at its corners by up to 0.73 of the growth. Against a hull or
        // a mesh, the grown pair's depth less the growth (exact where faces meet).
        const Vec3 point = onTrueSurface(a, toVec3(found[i].pos), normal);
        const double depth = measurable(b.type()) ? depthInside(b, point) : found[i].depth;
        if (depth < 0.0) {
            const Vec3 relative = pointVelocity(a.owner() ? a.owner()->id() : nullptr, point) -
                                  pointVelocity(b.owner() ? b.owner()->id() : nullptr, point) + fall;
            // Does not reach b this step, to within the least approach that gets speculative
            // contacts (an overlap that small stays inside ODE's surface layer, which ERP leaves
            // alone). Within linearSlop instead, every side neighbour a hair from a jittering box
            // in a resting pyramid got four rows: 2.3 % more contact joints than ODE's own.
            const double closing = -relative.dot(normal);
            if (closing * h < -depth - kLeastApproach * slop) continue;
        }
        dContact& c = out[kept++];
        c = dContact{};
        c.geom = found[i];
        c.geom.g1 = a.geom();  // not the probe's scratch geom
        c.geom.g2 = b.geom();
        c.geom.depth = depth;
        for (int k = 0; k < 3; ++k) c.geom.pos[k] = point[k];
    }
    return kept;
}

double OdeWorld::speculativeApproach(const OdeShape& a, const OdeShape& b, const GeomSurface& sa,
                                     const GeomSurface& sb) const {
    if (!NearProbe::growable(a.type()) || a.type() == ShapeType::Plane) return 0.0;
    const double approach = stepApproach(a, b, odeStep());
    if (approach <= kLeastApproach * settings_.linearSlop) return 0.0;
    // A bounce is aimed from the depth ODE finds it at (aimBounce): bouncing pairs keep ODE's contacts.
    if (effects_.has(Effect::Restitution) && materials_.get(sa.material, sb.material).restitution > 0) return 0.0;
    // A body closing by more than half its core in a step is continuous collision's
    // (ode_continuous.cpp), and a shape grown that far is a poor guess at the surfaces.
    for (const OdeBody* body : {a.owner(), b.owner()})
        if (body && body->isDynamic() && approach > kMostApproach * body->coreExtent()) return 0.0;
    return approach;
}

void OdeWorld::collideAhead() {
    if (awakeBodies_ == 0) return;  // only awake bodies move
    const double h = odeStep(), slop = settings_.linearSlop;
    aheadShapes_.clear();
    aheadBounds_.clear();
    bool anyMoves = false;
    for (const OdeBody* body : bodies_) {
        const bool awakeMover = body->moves() && body->activeInPass;
        const double speed = awakeMover ? toVec3(dBodyGetLinearVel(body->id())).norm() : 0.0;
        const double spin = awakeMover ? toVec3(dBodyGetAngularVel(body->id())).norm() : 0.0;
        const Vec3 centre = spin > 0.0 ? toVec3(dBodyGetPosition(body->id())) : Vec3::Zero();
        for (std::size_t i = 0; i < body->shapeCount(); ++i) {
            const OdeShape& shape = body->shape(i);
            if (shape.surface().trigger) continue;  // a sensor's pairs are overlaps: never speculative
            dReal box[6];
            dGeomGetAABB(shape.geom(), box);
            // A plane's are infinite, at most on one side along an axis it faces; NaN bounds
            // (a body whose state went bad) meet nothing and would break the sweep's sort.
            if (std::any_of(box, box + 6, [](dReal x) { return std::isnan(x); })) continue;
            // How far it may reach: its own travel twice over, as a pair closing head on is found
            // from the faster body; nothing unless it travels more than kLeastApproach.
            const double travel = (speed + (spin > 0.0 ? spin * reachFromBounds(box, centre) : 0.0)) * h;
            const bool reaches = travel > kLeastApproach * slop && NearProbe::growable(shape.type());
            anyMoves = anyMoves || reaches;
            aheadShapes_.push_back(&shape);
            aheadBounds_.push_back({{box[0], box[2], box[4]}, {box[1], box[3], box[5]}, reaches ? 2.0 * travel + slop : 0.0});
        }
    }
    if (!anyMoves) return;
    for (const auto& [own, other] : aheadSweep_.find(aheadBounds_)) {
        const OdeShape& mover = *aheadShapes_[own];
        const OdeShape& found = *aheadShapes_[other];
        if (found.owner() == mover.owner()) continue;
        // Bodies moving together (a falling grid's neighbours) never meet.
        if (stepApproach(mover, found, h) <= kLeastApproach * slop) continue;
        collidePair(mover.geom(), found.geom());
    }
}

}  // namespace anyphys::ode

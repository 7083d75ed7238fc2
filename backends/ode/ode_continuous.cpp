// Continuous collision, approximated: ODE has none. A body that moved more than half its inner
// radius in one ODE step is stopped where the ray from its start centre along its motion first
// meets other geometry, its inner radius (less a sliver of overlap) before the hit point, keeping
// its velocity. It then overlaps the surface, so ODE's discrete contact stops it next step.
// Limits: other bodies are taken where they are at the end of the step (two fast bodies crossing
// each other's paths are not swept against each other's motion), and only the centre's path is
// swept (a fast body can still clip an edge its centre passes by).
#include <cmath>
#include <limits>

#include "ode_math.hpp"
#include "ode_world.hpp"

namespace anyphys::ode {
namespace {

struct SweepQuery {
    dGeomID ray;
    const OdeWorld* world;
    const OdeBody* body;
    Vec3 start;
    double hit = std::numeric_limits<double>::infinity();  // m along the ray
};

// Positive when `p` lies inside the geom (ODE's point-depth functions), 0 if unknown.
double pointDepth(dGeomID g, const Vec3& p) {
    switch (dGeomGetClass(g)) {
        case dSphereClass: return dGeomSpherePointDepth(g, p.x(), p.y(), p.z());
        case dBoxClass: return dGeomBoxPointDepth(g, p.x(), p.y(), p.z());
        case dCapsuleClass: return dGeomCapsulePointDepth(g, p.x(), p.y(), p.z());
        case dPlaneClass: return dGeomPlanePointDepth(g, p.x(), p.y(), p.z());
        default: return 0.0;
    }
}

void sweepCallback(void* data, dGeomID o1, dGeomID o2) {
    auto& q = *static_cast<SweepQuery*>(data);
    const dGeomID other = o1 == q.ray ? o2 : o1;
    const OdeShape* shape = shapeOfGeom(other);
    const OdeBody* target = shape ? shape->owner() : nullptr;
    if (!target || target == q.body) return;
    // A joint that keeps the pair apart from contacts keeps it from sweeps too: a limb pulled
    // through its own chest was otherwise stopped at the chest's face every step, for good.
    if (q.world->jointExcludes(q.body, target)) return;
    // The moving body's centre ray stands for all its geoms (their union of layers and masks).
    const GeomSurface& surface = shape->surface();
    if (surface.trigger || !layersCollide(q.body->layer(), q.body->mask(), surface.layer, surface.mask)) return;
    // Already inside: the discrete contact handles it; the ray would only find the way out.
    if (pointDepth(other, q.start) > 0) return;
    dContactGeom hit;
    if (dCollide(q.ray, other, 1, &hit, sizeof(dContactGeom)) < 1) return;
    q.hit = std::min(q.hit, hit.depth);
}

}  // namespace

void OdeWorld::continuousCollision(const std::vector<Vec3>& before) {
    // A sliver of overlap left at the stop, so ODE's discrete collider reports the contact.
    const double overlap = 0.5 * settings_.linearSlop;
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
        OdeBody& b = *bodies_[i];
        if (!b.isDynamic() || b.isTrigger() || !b.isActive()) continue;
        const double core = b.coreExtent();
        if (!(core > 0.0) || !std::isfinite(core)) continue;
        const Vec3 after = toVec3(dBodyGetPosition(b.id()));
        const Vec3 motion = after - before[i];
        const double distance = motion.norm();
        if (distance <= 0.5 * core) continue;  // cannot have passed through anything
        const Vec3 direction = motion / distance;
        dGeomRaySetLength(ray_, distance + core);
        dGeomRaySet(ray_, before[i].x(), before[i].y(), before[i].z(), direction.x(), direction.y(), direction.z());
        dGeomRaySetFirstContact(ray_, 0);
        dGeomRaySetBackfaceCull(ray_, 1);  // mesh back faces are exits: culled
        dGeomRaySetClosestHit(ray_, 1);
        SweepQuery q{ray_, this, &b, before[i]};
        dSpaceCollide2(ray_, reinterpret_cast<dGeomID>(space_), &q, &sweepCallback);
        if (!std::isfinite(q.hit)) continue;
        const double stop = std::max(0.0, q.hit - core + overlap);
        if (stop >= distance) continue;
        const Vec3 at = before[i] + stop * direction;
        dBodySetPosition(b.id(), at.x(), at.y(), at.z());
    }
}

}  // namespace anyphys::ode

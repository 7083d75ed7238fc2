// Queries against the space: ray casts and shape overlap, both through ODE's own colliders
// (dSpaceCollide2 for the broad phase, dCollide for the exact test).
#include <algorithm>
#include <limits>
#include <optional>
#include <unordered_map>

#include "ode_init.hpp"
#include "ode_math.hpp"
#include "ode_world.hpp"

namespace anyphys::ode {
namespace {

struct RayQuery {
    dGeomID ray;
    std::uint32_t mask;
    Vec3 origin;
    Vec3 direction;
    double maxDistance;
    std::unordered_map<const OdeShape*, PeerRayHit> nearest;  // per shape (a compound's child too): its nearest hit
};

// Whether `p` lies strictly inside the shape's solid (below a plane). A ray from there does not
// hit the shape, as on the other backends. A mesh is a surface: nothing is inside it.
bool holds(const OdeShape& shape, const Vec3& p) {
    const dGeomID g = shape.geom();
    switch (dGeomGetClass(g)) {
        case dSphereClass: return dGeomSpherePointDepth(g, p.x(), p.y(), p.z()) > 0;
        case dBoxClass: return dGeomBoxPointDepth(g, p.x(), p.y(), p.z()) > 0;
        case dCapsuleClass: return dGeomCapsulePointDepth(g, p.x(), p.y(), p.z()) > 0;
        case dPlaneClass: return dGeomPlanePointDepth(g, p.x(), p.y(), p.z()) > 0;
        case dConvexClass: {
            const HullData& hull = *shape.hull();
            const Vec3 local = toMat3(dGeomGetRotation(g)).transpose() * (p - toVec3(dGeomGetPosition(g)));
            for (std::size_t f = 0; f < hull.faceNormals.size(); ++f)
                if (!(hull.faceNormals[f].dot(local) < hull.faceOffsets[f])) return false;
            return true;
        }
        default: return false;
    }
}

// Where the ray enters a hull, clipped against its face planes in the geom's frame. ODE 0.16's own
// ray-convex test (dCollideRayConvex) is wrong for a turned hull: a cube turned 0.3 rad about the
// ray's normal axis was hit 17 cm early, and missed where the ray crossed it 0.7 m off centre.
// Only for an origin outside the hull (holds() has let the others go).
std::optional<PeerRayHit> rayIntoHull(const OdeShape& shape, const Vec3& origin, const Vec3& direction, double maxDistance) {
    const HullData& hull = *shape.hull();
    const dGeomID g = shape.geom();
    const Mat3 rotation = toMat3(dGeomGetRotation(g));
    const Vec3 o = rotation.transpose() * (origin - toVec3(dGeomGetPosition(g)));
    const Vec3 d = rotation.transpose() * direction;
    // On the hull where n . (o + t d) <= offset for every face: each face bounds t from below
    // (the ray enters through its plane) or from above (leaves), or, parallel, keeps all or none.
    double enter = -std::numeric_limits<double>::infinity(), leave = maxDistance;
    std::size_t entryFace = hull.faceNormals.size();
    for (std::size_t f = 0; f < hull.faceNormals.size(); ++f) {
        const double along = hull.faceNormals[f].dot(d), gap = hull.faceOffsets[f] - hull.faceNormals[f].dot(o);
        if (along < 0.0) {
            if (gap / along > enter) {
                enter = gap / along;
                entryFace = f;
            }
        } else if (along > 0.0) {
            leave = std::min(leave, gap / along);
        } else if (gap < 0.0) {
            return std::nullopt;  // parallel to a face, outside it
        }
    }
    if (entryFace == hull.faceNormals.size() || enter > leave || enter < 0.0) return std::nullopt;
    return PeerRayHit{0, origin + enter * direction, rotation * hull.faceNormals[entryFace], enter};
}

void rayCallback(void* data, dGeomID o1, dGeomID o2) {
    auto& q = *static_cast<RayQuery*>(data);
    const dGeomID other = o1 == q.ray ? o2 : o1;
    const OdeShape* shape = shapeOfGeom(other);
    const OdeBody* body = shape ? shape->owner() : nullptr;
    if (!body || shape->surface().trigger || (shape->surface().layer & q.mask) == 0) return;
    if (holds(*shape, q.origin)) return;  // ODE would report where the ray leaves it
    PeerRayHit h{body->userData(), Vec3::Zero(), Vec3::Zero(), 0.0};
    if (dGeomGetClass(other) == dConvexClass) {
        const std::optional<PeerRayHit> entry = rayIntoHull(*shape, q.origin, q.direction, q.maxDistance);
        if (!entry) return;
        h.point = entry->point;
        h.normal = entry->normal;
        h.distance = entry->distance;
    } else {
        dContactGeom hit;
        if (dCollide(q.ray, other, 1, &hit, sizeof(dContactGeom)) < 1) return;
        h.point = toVec3(hit.pos);
        h.normal = toVec3(hit.normal);
        if (h.normal.dot(q.direction) > 0) h.normal = -h.normal;  // the surface normal facing the ray
        h.distance = hit.depth;  // depth: distance along the ray
    }
    const auto [it, inserted] = q.nearest.try_emplace(shape, h);
    if (!inserted && h.distance < it->second.distance) it->second = h;
}

struct OverlapQuery {
    const OdeShape* probe;
    std::uint32_t mask;
    bool movingOnly;  // wakeTouching: only bodies that can be woken
    std::vector<std::uint64_t>* found;
    std::vector<const OdeBody*>* bodies;
};

void overlapCallback(void* data, dGeomID o1, dGeomID o2) {
    auto& q = *static_cast<OverlapQuery*>(data);
    const dGeomID probe = q.probe->geom();
    const dGeomID other = o1 == probe ? o2 : o1;
    if (other == probe) return;
    const OdeShape* shape = shapeOfGeom(other);
    const OdeBody* body = shape ? shape->owner() : nullptr;
    if (!body || (shape->surface().layer & q.mask) == 0) return;
    if (q.movingOnly ? !body->moves() : shape->surface().trigger) return;
    if (!collidable(q.probe->type(), shape->type())) return;
    dContactGeom contact;
    if (dCollide(probe, other, 1, &contact, sizeof(dContactGeom)) < 1) return;
    if (q.found) q.found->push_back(body->userData());
    if (q.bodies) q.bodies->push_back(body);
}

}  // namespace

std::vector<PeerRayHit> OdeWorld::raycast(const Vec3& origin, const Vec3& direction, double maxDistance,
                                          bool closestOnly, std::uint32_t mask) {
    if (!(maxDistance > 0.0)) return {};  // ODE rays need a length
    ensureOdeThreadData();
    dGeomRaySetLength(ray_, maxDistance);
    dGeomRaySet(ray_, origin.x(), origin.y(), origin.z(), direction.x(), direction.y(), direction.z());
    dGeomRaySetFirstContact(ray_, 0);  // the nearest hit per geom, not the first found
    dGeomRaySetBackfaceCull(ray_, 0);  // mesh back faces count too
    dGeomRaySetClosestHit(ray_, 1); // per mesh: its nearest triangle
    RayQuery q{ray_, mask, origin, direction, maxDistance, {}};
    dSpaceCollide2(ray_, reinterpret_cast<dGeomID>(space_), &q, &rayCallback);
    std::vector<PeerRayHit> hits;
    hits.reserve(q.nearest.size());
    for (const auto& [key, hit] : q.nearest) hits.push_back(hit);
    // Nearest first in a fixed order (the map's is the pointers'); two of a compound's children
    // hit at one point where they meet count once, as on the other backends.
    std::sort(hits.begin(), hits.end(), [](const PeerRayHit& x, const PeerRayHit& y) {
        return x.distance != y.distance ? x.distance < y.distance : x.body < y.body;
    });
    sortAndMergeSeamHits(hits);
    if (closestOnly && hits.size() > 1) hits.resize(1);
    return hits;
}

std::vector<std::uint64_t> OdeWorld::overlap(const std::vector<PeerShape>& shapes, const Transform& pose,
                                             std::uint32_t mask) {
    ensureOdeThreadData();
    std::vector<std::uint64_t> found;
    for (const PeerShape& ps : shapes) {
        OdeShape probe(ps, nullptr);  // in no space: never part of the simulation
        probe.place(pose);
        dGeomSetCategoryBits(probe.geom(), ~0ul);
        dGeomSetCollideBits(probe.geom(), ~0ul);
        OverlapQuery q{&probe, mask, false, &found, nullptr};
        dSpaceCollide2(probe.geom(), reinterpret_cast<dGeomID>(space_), &q, &overlapCallback);
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
}

void OdeWorld::wakeTouching(const OdeBody& body) {
    std::vector<const OdeBody*> touching;
    for (std::size_t i = 0; i < body.shapeCount(); ++i) {
        OverlapQuery q{&body.shape(i), ~0u, true, nullptr, &touching};
        dSpaceCollide2(body.shape(i).geom(), reinterpret_cast<dGeomID>(space_), &q, &overlapCallback);
    }
    for (const OdeBody* b : touching)
        if (b != &body) dBodyEnable(b->id());
}

}  // namespace anyphys::ode

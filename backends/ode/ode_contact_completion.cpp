#include "ode_contact_completion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "ode_math.hpp"

namespace anyphys::ode {
namespace {

// Tilts: eight axes around the normal, so each corner of a face gets a turn at being deepest.
constexpr int kTilts = 8;
// m: how far the tilt moves the geom's farthest point. Far more than rounding, so the deepest
// point really changes; small enough that ODE still meets the same face of the other geom.
constexpr double kTiltTravel = 0.005;
constexpr double kMaxTiltAngle = 0.1;  // rad
// The contact normal within this of a face normal of the other geom: resting on that face.
const double kFaceNormalCosine = std::cos(1.0 * std::numbers::pi / 180.0);
// A tilted contact whose normal turned more than this from the first belongs to another feature.
const double kMinNormalCosine = std::cos(15.0 * std::numbers::pi / 180.0);

bool hasFlatOrStraightSides(int geomClass) { return geomClass == dBoxClass || geomClass == dConvexClass || geomClass == dCapsuleClass; }

Vec3 tangentTo(const Vec3& n) {
    const Vec3 axis = std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : Vec3::UnitY();
    return n.cross(axis).normalized();
}

struct Candidate {
    dContactGeom geom;
    Vec3 inPlane;  // position projected onto the contact plane (for spacing)
};

// Whether ODE's collider can give one point where `moving` rests on a face of `other`.
bool collidesAtOnePoint(dGeomID moving, dGeomID other) {
    const int a = dGeomGetClass(moving), b = dGeomGetClass(other);
    if (!hasFlatOrStraightSides(a) || !(b == dBoxClass || b == dConvexClass)) return false;
    return a == dConvexClass || b == dConvexClass || a == dCapsuleClass;
}

// The same contact seen from the other geom: normal reversed, geoms and sides swapped.
void flip(dContactGeom& g) {
    for (int k = 0; k < 3; ++k) g.normal[k] = -g.normal[k];
    std::swap(g.g1, g.g2);
    std::swap(g.side1, g.side2);
}

// completeOnePointContact with `moving` as geom 1 (the contact's normal into it).
int completeManifold(const OdeShape& movingShape, const OdeShape& otherShape, dContact* contacts, int capacity) {
    const dContactGeom first = contacts[0].geom;
    const Vec3 normal = toVec3(first.normal);  // into `moving`: it leaves along +normal
    // Against an edge or a corner of `other` a tilted point's depth would be measured to a plane
    // that is not there (in a ragdoll pile, limbs on the edges of torsos: the pile never came to
    // rest): one point is then the contact.
    if (!otherShape.hasFaceAlong(normal, kFaceNormalCosine)) return 1;
    const dGeomID moving = movingShape.geom(), twin = movingShape.twin(), other = otherShape.geom();
    if (!twin) return 1;
    const Vec3 center = toVec3(dGeomGetPosition(moving));
    dQuaternion q;
    dGeomGetQuaternion(moving, q);
    const Quat orientation = toQuat(q);
    dReal box[6];
    dGeomGetAABB(moving, box);
    const double reach = 0.5 * Vec3(box[1] - box[0], box[3] - box[2], box[5] - box[4]).norm();
    const double angle = std::min(kMaxTiltAngle, kTiltTravel / std::max(reach, 1e-9));
    const Vec3 t1 = tangentTo(normal), t2 = normal.cross(t1);
    const auto inPlane = [&](const Vec3& p) { return Vec3(p - normal.dot(p - center) * normal); };

    // Tilt axes: eight around the normal. A capsule is round about its own axis: turning it
    // about that axis moves no material point to where ODE reports the contact (its lowest
    // line), and a point carried back would land off that line and start a roll. It tilts only
    // about the axis across both the normal and its length, which raises one end or the other.
    std::array<Vec3, kTilts> axes;
    int tilts = 0;
    if (dGeomGetClass(moving) == dCapsuleClass) {
        const Vec3 length = orientation * Vec3::UnitZ();  // ODE capsules lie along their z
        const Vec3 across = normal.cross(length);
        if (across.norm() < 1e-6) return 1;  // standing on an end: one point is the whole contact
        axes[tilts++] = across.normalized();
        axes[tilts++] = -across.normalized();
    } else {
        for (int k = 0; k < kTilts; ++k) {
            const double around = 2.0 * std::numbers::pi * k / kTilts;
            axes[tilts++] = std::cos(around) * t1 + std::sin(around) * t2;
        }
    }

    std::array<Candidate, kTilts + 1> found;
    int count = 0;
    found[count++] = {first, inPlane(toVec3(first.pos))};
    dGeomSetPosition(twin, center.x(), center.y(), center.z());
    for (int k = 0; k < tilts; ++k) {
        const Quat tilt(Eigen::AngleAxisd(angle, axes[k]));
        dQuaternion tilted;
        toOde(tilt * orientation, tilted);
        dGeomSetQuaternion(twin, tilted);
        dContactGeom hit;
        if (dCollide(twin, other, 1, &hit, sizeof(dContactGeom)) < 1) continue;
        const Vec3 n = toVec3(hit.normal), p = toVec3(hit.pos);
        if (!p.allFinite() || !std::isfinite(hit.depth) || !(n.dot(normal) >= kMinNormalCosine)) continue;
        // The point as the same material point of the untilted geom, and its depth there along
        // the first normal (deeper where it lies lower along the normal).
        const Vec3 back = center + tilt.conjugate() * (p - center);
        const double depth = hit.depth + (p - back).dot(normal);
        if (!(depth > 0.0)) continue;  // not touching without the tilt
        dContactGeom g = first;
        g.pos[0] = back.x();
        g.pos[1] = back.y();
        g.pos[2] = back.z();
        g.depth = depth;
        found[count++] = {g, inPlane(back)};
    }

    // The most spread-out points, ODE's first one kept: each next one is the candidate farthest
    // from those already taken (within 1 % of the geom's reach, a point is the same point).
    const double same = 0.01 * reach;
    std::array<bool, kTilts + 1> taken{};
    taken[0] = true;
    int kept = 1;
    while (kept < capacity) {
        int best = -1;
        double bestDistance = same;
        for (int i = 1; i < count; ++i) {
            if (taken[i]) continue;
            double nearest = std::numeric_limits<double>::infinity();
            for (int j = 0; j < count; ++j)
                if (taken[j]) nearest = std::min(nearest, (found[i].inPlane - found[j].inPlane).norm());
            if (nearest > bestDistance) {
                bestDistance = nearest;
                best = i;
            }
        }
        if (best < 0) break;
        taken[best] = true;
        contacts[kept++].geom = found[best].geom;
    }
    return kept;
}

}  // namespace

int completeOnePointContact(const OdeShape& first, const OdeShape& second, dContact* contacts, int capacity) {
    if (collidesAtOnePoint(first.geom(), second.geom())) return completeManifold(first, second, contacts, capacity);
    if (!collidesAtOnePoint(second.geom(), first.geom())) return 1;
    // A capsule or hull lying on a box (or hull) that comes first: tilt the second geom instead.
    flip(contacts[0].geom);
    const int count = completeManifold(second, first, contacts, capacity);
    for (int i = 0; i < count; ++i) flip(contacts[i].geom);
    return count;
}

}  // namespace anyphys::ode

#include "ode_convex_capsule.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "ode_collider_output.hpp"
#include "ode_hull_geometry.hpp"
#include "ode_math.hpp"
#include "ode_shapes.hpp"

namespace anyphys::ode {
namespace {

/// A contact in the hull's frame: the point (on a face, the capsule's deepest; else midway
/// through the overlap), the way out of the hull towards the capsule, and how deep they overlap.
struct HullContact {
    Vec3 point, outward;
    double depth;
};

/// The capsule's core, segment ab in the hull's frame, and its radius.
struct Segment {
    Vec3 a, b;
    double radius;
};

/// Whether the segment has a point inside the hull (on the inner side of every face plane).
bool segmentEntersHull(const HullData& hull, const Segment& s) {
    double enter = 0.0, leave = 1.0;  // the stretch of the segment, as a fraction, inside the planes so far
    for (std::size_t f = 0; f < hull.faces.size(); ++f) {
        const double ha = hull.faceNormals[f].dot(s.a) - hull.faceOffsets[f];
        const double hb = hull.faceNormals[f].dot(s.b) - hull.faceOffsets[f];
        if (!(ha <= 0.0 || hb <= 0.0)) return false;  // both ends in front of this face (or a NaN)
        if (ha > 0.0) enter = std::max(enter, ha / (ha - hb));
        if (hb > 0.0) leave = std::min(leave, ha / (ha - hb));
    }
    return enter <= leave;
}

/// The stretch of the segment over face f (within the prism its edges raise along its normal),
/// as the fractions [t0, t1] of ab; empty when t0 > t1.
std::array<double, 2> stretchOverFace(const HullData& hull, std::size_t f, const Segment& s) {
    const Vec3& n = hull.faceNormals[f];
    const std::vector<int>& loop = hull.faces[f];
    double t0 = 0.0, t1 = 1.0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
        const Vec3& p = hull.vertices[loop[k]];
        const Vec3 inward = n.cross(hull.vertices[loop[(k + 1) % loop.size()]] - p);  // the loop is counter-clockwise
        const double da = inward.dot(s.a - p), db = inward.dot(s.b - p);
        if (da < 0.0 && db < 0.0) return {1.0, 0.0};
        if (da < 0.0) t0 = std::max(t0, da / (da - db));
        if (db < 0.0) t1 = std::min(t1, da / (da - db));
    }
    return {t0, t1};
}

/// The capsule against face f: a contact at each end of its stretch over the face that lies
/// within the capsule's radius of the face's plane, at the capsule's deepest point there (where
/// ODE's capsule-plane collider puts it): a capsule rolls about its own surface, and a point
/// midway through a 1 mm overlap, half a millimetre nearer the core of a 0.1 m capsule, had it
/// roll 0.33 % slow. None when the stretch is empty.
int faceContacts(const HullData& hull, std::size_t f, const Segment& s, std::array<HullContact, 2>& out) {
    const auto [t0, t1] = stretchOverFace(hull, f, s);
    if (t0 > t1) return 0;
    const Vec3& n = hull.faceNormals[f];
    int count = 0;
    const int ends = t1 > t0 ? 2 : 1;  // a stretch of one point gives one contact
    for (int e = 0; e < ends; ++e) {
        const Vec3 q = s.a + (e == 0 ? t0 : t1) * (s.b - s.a);
        const double height = n.dot(q) - hull.faceOffsets[f];
        if (height > s.radius) continue;
        out[count++] = {q - s.radius * n, n, s.radius - height};
    }
    return count;
}

/// The face whose normal is nearest to `direction`.
std::size_t faceFacing(const HullData& hull, const Vec3& direction) {
    std::size_t best = 0;
    for (std::size_t f = 1; f < hull.faces.size(); ++f)
        if (hull.faceNormals[f].dot(direction) > hull.faceNormals[best].dot(direction)) best = f;
    return best;
}

/// The segment outside the hull: the nearest points of the two, exact (an end against the
/// surface, or the segment against an edge), then the face contacts when the way out is a face's
/// normal, else the one nearest contact. None beyond the radius.
int separatedContacts(const HullData& hull, const Segment& s, std::array<HullContact, 2>& out) {
    Vec3 onHull = nearestOnSurface(hull, s.a), onSegment = s.a;
    double best = (onSegment - onHull).squaredNorm();
    const auto consider = [&](const Vec3& segmentPoint, const Vec3& hullPoint) {
        if (const double d2 = (segmentPoint - hullPoint).squaredNorm(); d2 < best) {
            best = d2;
            onSegment = segmentPoint;
            onHull = hullPoint;
        }
    };
    consider(s.b, nearestOnSurface(hull, s.b));
    for (const std::vector<int>& loop : hull.faces)
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const SegmentPair pair = nearestBetweenSegments(s.a, s.b, hull.vertices[loop[k]], hull.vertices[loop[(k + 1) % loop.size()]]);
            consider(pair.onP, pair.onQ);
        }
    const double distance = std::sqrt(best);
    if (!(distance <= s.radius)) return 0;  // apart (and a NaN is never a contact)
    // Touching with no gap leaves no direction between the nearest points: the face in front.
    const Vec3 outward = distance > 0.0 ? Vec3((onSegment - onHull) / distance) : hull.faceNormals[faceFacing(hull, onSegment - hull.centroid)];
    // Within about 2.6 degrees of a face's normal the face holds the capsule: a capsule lying on
    // it (or almost) gets a contact at each end of its stretch over it, and does not rock.
    constexpr double kFaceAlignment = 0.999;
    const std::size_t face = faceFacing(hull, outward);
    if (hull.faceNormals[face].dot(outward) >= kFaceAlignment)
        if (const int count = faceContacts(hull, face, s, out)) return count;
    out[0] = {onHull + 0.5 * (distance - s.radius) * outward, outward, s.radius - distance};
    return 1;
}

/// The segment's core inside the hull: the way out that moves the segment least, among the faces'
/// normals and the directions square to the segment and an edge (the separating-axis test over
/// every candidate, measured against all the hull's vertices).
int overlappingContacts(const HullData& hull, const Segment& s, std::array<HullContact, 2>& out) {
    // Separation along an outward direction: the segment's lowest point less the hull's highest.
    const auto separation = [&](const Vec3& direction, double hullTop) { return std::min(direction.dot(s.a), direction.dot(s.b)) - hullTop; };
    std::size_t face = 0;
    double faceSeparation = -std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < hull.faces.size(); ++f)
        if (const double sep = separation(hull.faceNormals[f], hull.faceOffsets[f]); sep > faceSeparation) {
            faceSeparation = sep;
            face = f;
        }
    const Vec3 axis = s.b - s.a;
    double edgeSeparation = -std::numeric_limits<double>::infinity();
    Vec3 edgeOutward = Vec3::Zero();
    std::array<int, 2> edge{0, 0};
    for (const std::vector<int>& loop : hull.faces)
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const int i = loop[k], j = loop[(k + 1) % loop.size()];
            if (i > j) continue;  // each edge once: its two faces walk it both ways
            Vec3 direction = axis.cross(hull.vertices[j] - hull.vertices[i]);
            const double length = direction.norm();
            if (!(length > 1e-12 * axis.norm() * (hull.vertices[j] - hull.vertices[i]).norm())) continue;  // parallel
            direction /= length;
            for (const double sign : {1.0, -1.0}) {
                const Vec3 d = sign * direction;
                double hullTop = -std::numeric_limits<double>::infinity();
                for (const Vec3& v : hull.vertices) hullTop = std::max(hullTop, d.dot(v));
                // Parallel edges share the direction; the contact is on the one the hull ends at.
                if (d.dot(hull.vertices[i]) < hullTop - 1e-9 * (1.0 + std::abs(hullTop))) continue;
                if (const double sep = separation(d, hullTop); sep > edgeSeparation) {
                    edgeSeparation = sep;
                    edgeOutward = d;
                    edge = {i, j};
                }
            }
        }
    // A face holds the capsule along a stretch (two contacts, steady), an edge at one point: the
    // edge only when it is clearly the shorter way out.
    const bool edgeIsShorter = edgeSeparation > faceSeparation + 1e-3 * std::abs(faceSeparation) + 1e-9;
    if (!edgeIsShorter)
        if (const int count = faceContacts(hull, face, s, out)) return count;
    if (edgeIsShorter) {
        const SegmentPair pair = nearestBetweenSegments(s.a, s.b, hull.vertices[edge[0]], hull.vertices[edge[1]]);
        // Midway between the edge and the capsule's deepest point along the way out.
        out[0] = {0.5 * (pair.onQ + pair.onP - s.radius * edgeOutward), edgeOutward, s.radius - edgeSeparation};
        return 1;
    }
    // The segment passes through the hull beside the face's own polygon: its deepest end.
    const Vec3& n = hull.faceNormals[face];
    const Vec3 deepest = n.dot(s.a) <= n.dot(s.b) ? s.a : s.b;
    const double height = n.dot(deepest) - hull.faceOffsets[face];
    out[0] = {deepest - 0.5 * (height + s.radius) * n, n, s.radius - faceSeparation};
    return 1;
}

/// ODE's box as a hull in its own frame, for the hull-capsule collider: vertex i at (+-x, +-y, +-z)
/// by its bits 1, 2 and 4, faces counter-clockwise seen from outside. One per thread, its
/// vertices and offsets rewritten for each box (no allocation per pair).
const HullData& boxHull(const Vec3& half) {
    thread_local HullData box = [] {
        HullData h;
        h.vertices.resize(8);
        h.faces = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
        h.faceNormals = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
        h.faceOffsets.resize(6);
        return h;
    }();
    for (int i = 0; i < 8; ++i)
        box.vertices[i] = Vec3(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(), i & 4 ? half.z() : -half.z());
    for (int f = 0; f < 6; ++f) box.faceOffsets[f] = half[f / 2];
    return box;
}

/// The hull-capsule collider over `hull`, o1's shape in o1's frame.
int collideHullCapsule(const HullData& hull, dGeomID o1, dGeomID o2, int room, dContactGeom* contact, int skip) {
    const Vec3 origin = toVec3(dGeomGetPosition(o1));
    const Mat3 rotation = toMat3(dGeomGetRotation(o1));
    dReal radius = 0.0, length = 0.0;
    dGeomCapsuleGetParams(o2, &radius, &length);
    const Mat3 capsuleRotation = toMat3(dGeomGetRotation(o2));
    const Vec3 centre = toVec3(dGeomGetPosition(o2));
    const Vec3 halfAxis = 0.5 * length * capsuleRotation.col(2);  // ODE's capsules lie along their z
    const Segment segment{rotation.transpose() * (centre - halfAxis - origin), rotation.transpose() * (centre + halfAxis - origin), radius};
    if (!segment.a.allFinite() || !segment.b.allFinite()) return 0;

    std::array<HullContact, 2> found{};  // zeroed: GCC cannot see that a second contact is set when counted
    int count = segmentEntersHull(hull, segment) ? overlappingContacts(hull, segment, found) : separatedContacts(hull, segment, found);
    if (count > room) {  // room for one: the deeper
        if (found[1].depth > found[0].depth) found[0] = found[1];
        count = room;
    }
    for (int c = 0; c < count; ++c) {
        const Vec3 normal = -(rotation * found[c].outward);  // into o1: moving the hull along it parts them
        writeContact(contactAt(contact, c, skip), origin + rotation * found[c].point, normal, found[c].depth, o1, o2);
    }
    return count;
}

}  // namespace

int collideConvexCapsule(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip) {
    const OdeShape* shape = shapeOfGeom(o1);
    const int room = contactRoom(flags);
    if (room == 0 || !shape || !shape->hull()) return 0;
    return collideHullCapsule(*shape->hull(), o1, o2, room, contact, skip);
}

int collideBoxCapsule(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip) {
    const int room = contactRoom(flags);
    if (room == 0) return 0;
    dVector3 lengths;
    dGeomBoxGetLengths(o1, lengths);  // any box geom: a body's, a twin or a query probe
    return collideHullCapsule(boxHull(0.5 * Vec3(lengths[0], lengths[1], lengths[2])), o1, o2, room, contact, skip);
}

}  // namespace anyphys::ode

// Spheres and boxes against boxes: closest point by clamping in the box frame, and the box-box
// separating-axis test on 15 axes (Gottschalk's OBB test) with reference-face clipping.
#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/clip.hpp"
#include "collision/feature_id.hpp"
#include "collision/manifold_builder.hpp"
#include "collision/narrow_phase.hpp"
#include "collision/segments.hpp"
#include "collision/tolerances.hpp"

namespace anyphys::native {
namespace {

double signOf(double x) { return x < 0 ? -1.0 : 1.0; }

Vec3 corner(const BoxGeom& box, int i) {
    const Vec3 local((i & 1) ? box.half.x() : -box.half.x(), (i & 2) ? box.half.y() : -box.half.y(),
                     (i & 4) ? box.half.z() : -box.half.z());
    return box.center + box.rotation * local;
}

// Clips the face of `inc` most opposed to the face of `ref` with normal sign x axis `refAxis`.
void boxFaceContact(const BoxGeom& ref, int refAxis, double sign, const BoxGeom& inc, feature::Kind kind, double speculative,
                    ManifoldBuilder& out) {
    const int refFace = 2 * refAxis + (sign > 0 ? 0 : 1);
    ReferenceFace face;
    face.normal = sign * ref.rotation.col(refAxis);
    face.offset = face.normal.dot(ref.center) + ref.half[refAxis];
    for (int v : boxFaces()[refFace]) face.corners.push_back(corner(ref, v));

    const Vec3 local = inc.rotation.transpose() * face.normal;
    int k = 0;
    local.cwiseAbs().maxCoeff(&k);
    const int incFace = 2 * k + (local[k] > 0 ? 1 : 0);  // its outward normal opposes face.normal
    std::vector<Vec3> corners(8);
    for (int i = 0; i < 8; ++i) corners[i] = corner(inc, i);

    const std::vector<ClipVertex> clipped = clipToFace(incidentPolygon(corners, boxFaces()[incFace]), face);
    const std::uint32_t seed = feature::id(kind, refFace, incFace);
    addFacePoints(clipped, face, 0.0, speculative, seed, out);
    // A deepest corner beside the reference face is clipped away: keep it all the same.
    int deepest = 0;
    for (int i = 1; i < 8; ++i)
        if (face.normal.dot(corners[i]) < face.normal.dot(corners[deepest])) deepest = i;
    const double depth = face.normal.dot(corners[deepest]) - face.offset;
    if (out.deepest() > depth + tolerance::kDistanceSwitch * std::min(ref.half.norm(), inc.half.norm()))
        addFacePoints({{corners[deepest], feature::vertexTag(static_cast<std::uint32_t>(deepest)), 0}}, face, 0.0, speculative,
                      seed, out);
}

struct BoxEdge {
    Vec3 p0, p1;
    int id;  // axis x 4 + which of the four parallel edges: its index in boxEdges(), so the
             // polyhedral routines (used while boxes are apart) give an edge pair the same id
};

// The edge of `box` along `axis` that is farthest in direction d.
BoxEdge supportEdge(const BoxGeom& box, int axis, const Vec3& d) {
    Vec3 offset = Vec3::Zero();
    int bits = 0, bit = 0;
    for (int k = 0; k < 3; ++k) {
        if (k == axis) continue;
        const double s = signOf(d.dot(box.rotation.col(k)));
        offset += s * box.half[k] * box.rotation.col(k);
        bits |= (s > 0 ? 1 : 0) << bit++;
    }
    const Vec3 along = box.half[axis] * box.rotation.col(axis);
    return {box.center + offset - along, box.center + offset + along, axis * 4 + bits};
}

}  // namespace

bool collideSphereBox(const SphereGeom& a, const BoxGeom& b, double speculative, Manifold& m) {
    const Vec3 c = b.rotation.transpose() * (a.center - b.center);
    const Vec3 q = c.cwiseMax(-b.half).cwiseMin(b.half);
    Vec3 n, onBox;
    double separation;
    int region = 0;
    if (c != q) {  // centre outside: the clamped point is the closest point
        const Vec3 d = c - q;
        const double distance = d.norm();
        separation = distance - a.radius;
        if (separation >= speculative) return false;
        n = -(b.rotation * d) / distance;
        onBox = b.center + b.rotation * q;
        for (int k = 2; k >= 0; --k) region = 3 * region + (c[k] < -b.half[k] ? 1 : c[k] > b.half[k] ? 2 : 0);
    } else {  // centre inside: leave through the nearest face
        int k = 0;
        (b.half - c.cwiseAbs()).minCoeff(&k);
        const double s = signOf(c[k]);
        separation = -(b.half[k] - std::abs(c[k])) - a.radius;
        if (separation >= speculative) return false;
        n = -s * b.rotation.col(k);
        Vec3 face = c;
        face[k] = s * b.half[k];
        onBox = b.center + b.rotation * face;
        region = 27 + 2 * k + (s > 0 ? 0 : 1);
    }
    ManifoldBuilder builder(n);
    builder.add(0.5 * (a.center + n * a.radius + onBox), separation, feature::id(feature::Kind::BoxRegion, region));
    return builder.finish(m);
}

bool collideBoxes(const BoxGeom& a, const BoxGeom& b, double speculative, Manifold& m) {
    // Everything in a's frame: R holds b's axes, t the centre offset.
    const Mat3 R = a.rotation.transpose() * b.rotation;
    const Vec3 t = a.rotation.transpose() * (b.center - a.center);
    // A small epsilon keeps near-parallel edge axes from claiming separation by rounding.
    const Mat3 absR = (R.cwiseAbs().array() + 1e-12).matrix();

    struct Axis {
        double separation = -std::numeric_limits<double>::infinity();
        int i = -1, j = -1;
        double sign = 1.0;  // of the axis oriented from a toward b
    };
    Axis faceA, faceB, edge;
    for (int i = 0; i < 3; ++i) {
        const double s = std::abs(t[i]) - (a.half[i] + absR.row(i).dot(b.half));
        if (s > speculative) return false;
        if (s > faceA.separation) faceA = {s, i, -1, signOf(t[i])};
    }
    for (int j = 0; j < 3; ++j) {
        const double tj = t.dot(R.col(j));
        const double s = std::abs(tj) - (absR.col(j).dot(a.half) + b.half[j]);
        if (s > speculative) return false;
        if (s > faceB.separation) faceB = {s, -1, j, signOf(tj)};
    }
    Vec3 edgeNormal = Vec3::Zero();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const Vec3 L = Vec3::Unit(i).cross(R.col(j));
            const double len = L.norm();
            if (len < tolerance::kParallelEdges) continue;
            const double rA = L.cwiseAbs().dot(a.half), rB = (R.transpose() * L).cwiseAbs().dot(b.half);
            const double tl = t.dot(L);
            const double s = (std::abs(tl) - rA - rB) / len;
            if (s > speculative) return false;
            if (s > edge.separation) {
                edge = {s, i, j, signOf(tl)};
                edgeNormal = signOf(tl) * (a.rotation * L) / len;
            }
        }

    // Apart: the axes only bound the distance from below; the polyhedral routine measures it
    // exactly (same face, corner and edge numbering, so ids carry over when the boxes meet).
    const double tol = tolerance::kDistanceSwitch * std::min(a.half.norm(), b.half.norm());
    if (std::max({faceA.separation, faceB.separation, edge.separation}) > tol)
        return collidePolytopes(makeBoxPolytope(a.half, a.center, a.rotation), makeBoxPolytope(b.half, b.center, b.rotation),
                                speculative, m);

    const double bias = tolerance::kAxisBias * std::min(a.half.maxCoeff(), b.half.maxCoeff());
    const bool useB = faceB.separation > faceA.separation + bias;
    const double faceSeparation = useB ? faceB.separation : faceA.separation;

    if (edge.i >= 0 && edge.separation > faceSeparation + bias) {
        const BoxEdge ea = supportEdge(a, edge.i, edgeNormal), eb = supportEdge(b, edge.j, -edgeNormal);
        const SegmentPair c = closestBetweenSegments(ea.p0, ea.p1, eb.p0, eb.p1);
        const double separation = (c.onSecond - c.onFirst).dot(edgeNormal);
        if (separation >= speculative) return false;
        ManifoldBuilder builder(edgeNormal);
        builder.add(0.5 * (c.onFirst + c.onSecond), separation, feature::id(feature::Kind::EdgeEdge, ea.id, eb.id));
        return builder.finish(m);
    }
    if (useB) {
        // The reference normal points from b toward a; the manifold's from a to b.
        ManifoldBuilder builder(faceB.sign * b.rotation.col(faceB.j));
        boxFaceContact(b, faceB.j, -faceB.sign, a, feature::Kind::FaceOfB, speculative, builder);
        return builder.finish(m);
    }
    ManifoldBuilder builder(faceA.sign * a.rotation.col(faceA.i));
    boxFaceContact(a, faceA.i, faceA.sign, b, feature::Kind::FaceOfA, speculative, builder);
    return builder.finish(m);
}

}  // namespace anyphys::native

// Spheres and boxes against boxes: closest point by clamping in the box frame, and the box-box
// separating-axis test on 15 axes (Gottschalk's OBB test, edge axes in closed form) with
// reference-face clipping done in the reference box's frame, where its side planes are the
// coordinate planes x_k = +-h_k.
#include <algorithm>
#include <array>
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

Vec3 cornerOffset(const Vec3& half, int i) {
    return Vec3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(), (i & 4) ? half.z() : -half.z());
}

// Feature tags of the corners (vertex, leaving edge) and of the side planes, made at compile time.
struct CornerTags {
    std::uint32_t vertex, edge;
};
constexpr std::array<CornerTags, 8> kCornerTags = [] {
    std::array<CornerTags, 8> t{};
    for (std::uint32_t v = 0; v < 8; ++v) t[v] = {feature::vertexTag(v), feature::edgeTag(v)};
    return t;
}();
constexpr std::array<std::uint32_t, 4> kPlaneTags{feature::planeTag(0), feature::planeTag(1), feature::planeTag(2),
                                                  feature::planeTag(3)};
// The two other axes of axis i, in cyclic order.
constexpr std::array<int, 3> kNext{1, 2, 0}, kPrev{2, 0, 1};

// Side plane k of a box face (through the face's corners k and k + 1) in the box's frame: the
// plane sign * x[axis] = half[axis], i.e. the neighbouring face across that edge.
struct BoxSidePlane {
    int axis;
    double sign;
};

// A box face as clipping sees it: its corners (boxFaces() order) and side planes.
struct BoxFace {
    std::array<int, 4> corners;
    std::array<BoxSidePlane, 4> sides;
};

const std::array<BoxFace, 6>& boxFaceTable() {
    static const std::array<BoxFace, 6> table = [] {
        std::array<BoxFace, 6> t{};
        for (std::size_t f = 0; f < 6; ++f) {
            const std::vector<int>& loop = boxFaces()[f];
            for (std::size_t k = 0; k < 4; ++k) {
                const int v = loop[k], w = loop[(k + 1) % 4];
                const int along = (v ^ w) == 1 ? 0 : (v ^ w) == 2 ? 1 : 2;         // the edge's direction
                const int axis = 3 - static_cast<int>(f / 2) - along;              // neither the face's nor the edge's
                t[f].corners[k] = v;
                t[f].sides[k] = {axis, (v >> axis) & 1 ? 1.0 : -1.0};
            }
        }
        return t;
    }();
    return table;
}

// The separating-axis test in a's frame: R holds b's axes, t the centre offset.
struct BoxPair {
    Mat3 R;
    Vec3 t;
    Mat3 absR;  // |R| plus a small epsilon: near-parallel edge axes never claim separation by rounding
};

BoxPair boxPair(const BoxGeom& a, const BoxGeom& b) {
    BoxPair p;
    p.R = a.rotation.transpose() * b.rotation;
    p.t = a.rotation.transpose() * (b.center - a.center);
    p.absR = (p.R.cwiseAbs().array() + 1e-12).matrix();
    return p;
}

double faceASeparation(const BoxGeom& a, const BoxGeom& b, const BoxPair& p, int i) {
    return std::abs(p.t[i]) - (a.half[i] + p.absR.row(i).dot(b.half));
}

double faceBSeparation(const BoxGeom& a, const BoxGeom& b, const BoxPair& p, int j) {
    return std::abs(p.t.dot(p.R.col(j))) - (p.absR.col(j).dot(a.half) + b.half[j]);
}

// Axis e_i x R_j in closed form: the centre offset along it and the projected radii, all scaled
// by its length (so the separation is (|tl| - rA - rB) / length).
struct EdgeTerms {
    double tl, rA, rB;
};

inline EdgeTerms edgeTerms(const BoxGeom& a, const BoxGeom& b, const BoxPair& p, int i, int j) {
    const int i1 = kNext[i], i2 = kPrev[i], j1 = kNext[j], j2 = kPrev[j];
    const Mat3 &R = p.R, &absR = p.absR;
    return {p.t[i2] * R(i1, j) - p.t[i1] * R(i2, j), a.half[i1] * absR(i2, j) + a.half[i2] * absR(i1, j),
            b.half[j1] * absR(i, j2) + b.half[j2] * absR(i, j1)};
}

double edgeLength(const BoxPair& p, int i, int j) {
    const double u = p.R(kNext[i], j), v = p.R(kPrev[i], j);
    return std::sqrt(u * u + v * v);
}

// The separation along the axis a cache remembers (-infinity if it names none).
double cachedSeparation(const BoxGeom& a, const BoxGeom& b, const BoxPair& p, const CollideCache& cache) {
    const auto fits = [](int index) { return index >= 0 && index < 3; };
    if (!cache.separating || !fits(cache.indexA) || !fits(cache.indexB)) return -std::numeric_limits<double>::infinity();
    switch (cache.axis) {
        case CollideCache::FaceOfA: return faceASeparation(a, b, p, cache.indexA);
        case CollideCache::FaceOfB: return faceBSeparation(a, b, p, cache.indexB);
        case CollideCache::EdgePair: {
            const double len = edgeLength(p, cache.indexA, cache.indexB);
            if (len < tolerance::kParallelEdges) break;
            const EdgeTerms e = edgeTerms(a, b, p, cache.indexA, cache.indexB);
            return (std::abs(e.tl) - e.rA - e.rB) / len;
        }
        default: break;
    }
    return -std::numeric_limits<double>::infinity();
}

// The face of `inc` most opposed to face (refAxis, sign) of `ref`, clipped to that face in ref's
// frame. turn and shift place inc in ref's frame (x_ref = turn x_inc + shift). Points go to `out`
// in ref's frame, with the manifold normal there. With keepDeepest, inc's deepest corner
// stands in when the clip leaves no point.
void boxFaceContact(const BoxGeom& ref, int refAxis, double sign, const BoxGeom& inc, const Mat3& turn, const Vec3& shift,
                    feature::Kind kind, double speculative, bool keepDeepest, ManifoldBuilder& out) {
    const int refFace = 2 * refAxis + (sign > 0 ? 0 : 1);
    // The reference normal in inc's frame.
    const Vec3 normalInInc = sign * turn.row(refAxis).transpose();
    int k = 0;
    normalInInc.cwiseAbs().maxCoeff(&k);
    const int incFace = 2 * k + (normalInInc[k] > 0 ? 1 : 0);  // its outward normal opposes the reference

    // Heights over the reference plane: sign * x[refAxis] - half[refAxis].
    auto height = [&](const Vec3& x) { return sign * x[refAxis] - ref.half[refAxis]; };
    auto place = [&](const Vec3& x, double h, std::uint32_t id) {
        // Midway between the reference plane (height 0) and the incident corner (height h).
        Vec3 point = x;
        point[refAxis] -= sign * 0.5 * h;
        if (h < speculative) out.add(point, h, id);
    };

    std::array<ClipVertex, 8> bufferA, bufferB;
    ClipVertex* in = bufferA.data();
    ClipVertex* cut = bufferB.data();
    int count = 0;
    const std::array<BoxFace, 6>& faces = boxFaceTable();
    for (int v : faces[static_cast<std::size_t>(incFace)].corners)
        in[count++] = {shift + turn * cornerOffset(inc.half, v), kCornerTags[static_cast<std::size_t>(v)].vertex,
                       kCornerTags[static_cast<std::size_t>(v)].edge};
    // Sutherland-Hodgman against the four side planes, in boxFaces() order (see clipToFace).
    const auto& sides = faces[static_cast<std::size_t>(refFace)].sides;
    for (std::size_t s = 0; s < 4 && count > 0; ++s) {
        const BoxSidePlane side = sides[s];
        const std::uint32_t tag = kPlaneTags[s];
        const double limit = ref.half[side.axis];
        int written = 0;
        for (int i = 0; i < count; ++i) {
            const ClipVertex& cur = in[i];
            const ClipVertex& next = in[i + 1 < count ? i + 1 : 0];
            const double dc = side.sign * cur.point[side.axis] - limit;
            const double dn = side.sign * next.point[side.axis] - limit;
            if (dc <= 0) cut[written++] = cur;
            if ((dc <= 0) != (dn <= 0)) {
                const Vec3 p = cur.point + (dc / (dc - dn)) * (next.point - cur.point);
                cut[written++] = {p, feature::combine(cur.edge, tag), dc <= 0 ? tag : cur.edge};
            }
        }
        count = written;
        std::swap(in, cut);
    }
    const std::uint32_t seed = feature::id(kind, refFace, incFace);
    for (int i = 0; i < count; ++i) place(in[i].point, height(in[i].point), feature::combine(seed, in[i].feature));
    if (!keepDeepest) return;

    // Only when the clip left nothing does inc's deepest corner stand in. A corner beside the
    // reference face is outside ref, whatever its height: kept beside a clipped patch, it held a
    // box of a pyramid row up by the neighbouring box's corner, off this box's face, and twisted
    // the box under it. The corner has the signs opposite to the normal in inc's frame (the
    // lowest index on exact ties).
    if (!out.empty()) return;
    const int deepest = (normalInInc.x() < 0 ? 1 : 0) | (normalInInc.y() < 0 ? 2 : 0) | (normalInInc.z() < 0 ? 4 : 0);
    const Vec3 corner = shift + turn * cornerOffset(inc.half, deepest);
    place(corner, height(corner), feature::combine(seed, kCornerTags[static_cast<std::size_t>(deepest)].vertex));
}

// Builds the face manifold in ref's frame and writes it in the world.
bool boxFaceManifold(const BoxGeom& ref, int refAxis, double refSign, const BoxGeom& inc, const Mat3& turn,
                     const Vec3& shift, feature::Kind kind, double manifoldSign, double speculative, bool keepDeepest,
                     Manifold& m) {
    ManifoldBuilder builder(manifoldSign * Vec3::Unit(refAxis));
    boxFaceContact(ref, refAxis, refSign, inc, turn, shift, kind, speculative, keepDeepest, builder);
    if (!builder.finish(m)) return false;
    m.normal = manifoldSign * ref.rotation.col(refAxis);
    for (int i = 0; i < m.pointCount; ++i) m.points[i].point = ref.center + ref.rotation * m.points[i].point;
    return true;
}

// Boxes apart with inc's lowest corner (against the normal of face (refAxis, sign) of ref) over
// that face's interior: the distance is then exactly the face's separation along its normal, so
// the distance routine would find what the face clip gives. Corners within a hair of a side are
// left to it.
bool cornerOverFace(const BoxGeom& ref, int refAxis, double sign, const BoxGeom& inc, const Mat3& turn, const Vec3& shift) {
    const Vec3 normalInInc = sign * turn.row(refAxis).transpose();
    const int lowest = (normalInInc.x() < 0 ? 1 : 0) | (normalInInc.y() < 0 ? 2 : 0) | (normalInInc.z() < 0 ? 4 : 0);
    const Vec3 corner = shift + turn * cornerOffset(inc.half, lowest);
    const double margin = 1e-9 * (ref.half.norm() + inc.half.norm());
    for (const int k : {kNext[refAxis], kPrev[refAxis]})
        if (!(std::abs(corner[k]) < ref.half[k] - margin)) return false;
    return true;
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
    m.normal = n;
    m.pointCount = 1;
    m.points[0] = {0.5 * (a.center + n * a.radius + onBox), separation, feature::id(feature::Kind::BoxRegion, region)};
    return true;
}

bool boxesStillApart(const Vec3& halfA, const Transform& xfA, const Vec3& halfB, const Transform& xfB,
                     const CollideCache& cache, double speculative) {
    if (!cache.separating || (cache.axis != CollideCache::FaceOfA && cache.axis != CollideCache::FaceOfB)) return false;
    const bool ofA = cache.axis == CollideCache::FaceOfA;
    const int k = ofA ? cache.indexA : cache.indexB;
    if (k < 0 || k > 2) return false;
    const Transform &own = ofA ? xfA : xfB, &other = ofA ? xfB : xfA;
    const Vec3 &ownHalf = ofA ? halfA : halfB, &otherHalf = ofA ? halfB : halfA;
    // The face normal, and the other box's reach along it (plus the epsilon collideBoxes adds).
    const Vec3 axis = own.orientation * Vec3::Unit(k);
    const Vec3 inOther = other.orientation.conjugate() * axis;
    const double reach = (inOther.cwiseAbs().array() + 1e-12).matrix().dot(otherHalf);
    return std::abs(axis.dot(other.position - own.position)) - (ownHalf[k] + reach) > speculative;
}

bool collideBoxes(const BoxGeom& a, const BoxGeom& b, double speculative, Manifold& m, CollideCache* cache) {
    const BoxPair p = boxPair(a, b);
    // Still apart along the axis that separated them last time: nothing else to do.
    if (cache && cachedSeparation(a, b, p, *cache) > speculative) return false;

    struct Axis {
        double separation = -std::numeric_limits<double>::infinity();
        int i = -1, j = -1;
        double sign = 1.0;  // of the axis oriented from a toward b
    };
    auto separated = [&](CollideCache::Axis kind, int i, int j) {
        if (cache) *cache = {kind, true, i, j};
        return false;
    };
    Axis faceA, faceB, edge;
    for (int i = 0; i < 3; ++i) {
        const double s = faceASeparation(a, b, p, i);
        if (s > speculative) return separated(CollideCache::FaceOfA, i, 0);
        if (s > faceA.separation) faceA = {s, i, -1, signOf(p.t[i])};
    }
    for (int j = 0; j < 3; ++j) {
        const double s = faceBSeparation(a, b, p, j);
        if (s > speculative) return separated(CollideCache::FaceOfB, 0, j);
        if (s > faceB.separation) faceB = {s, -1, j, signOf(p.t.dot(p.R.col(j)))};
    }
    const double tol = tolerance::kDistanceSwitch * std::min(a.half.norm(), b.half.norm());
    const double bias = tolerance::kAxisBias * std::min(a.half.maxCoeff(), b.half.maxCoeff());
    const bool useB = faceB.separation > faceA.separation + bias;
    const double faceSeparation = useB ? faceB.separation : faceA.separation;
    // An edge axis matters only if it separates by more than the speculative distance, shows the
    // boxes apart (beyond tol) or beats the faces by the bias. Lengths are at most 1, so an axis
    // whose scaled separation is already below all three (and not positive) is skipped before
    // its square root; the others are compared exactly, so the outcome is the full test's.
    const double skipBelow = std::min({speculative, tol, faceSeparation + bias, 0.0});
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const EdgeTerms e = edgeTerms(a, b, p, i, j);
            const double scaled = std::abs(e.tl) - e.rA - e.rB;
            if (scaled <= skipBelow) continue;
            const double len = edgeLength(p, i, j);
            if (len < tolerance::kParallelEdges) continue;
            const double s = scaled / len;
            if (s > speculative) return separated(CollideCache::EdgePair, i, j);
            if (s > edge.separation) edge = {s, i, j, signOf(e.tl)};
        }
    if (cache) *cache = {};

    // Apart: the axes only bound the distance from below. When a corner of one box lies over
    // the face of the other that bounds best, the face's separation is the distance and its clip
    // the manifold; otherwise the polyhedral routine measures the distance exactly (same face,
    // corner and edge numbering, so ids carry over when the boxes meet).
    if (std::max({faceA.separation, faceB.separation, edge.separation}) > tol) {
        const Mat3 turnB = p.R.transpose();  // a's frame in b's
        const Vec3 shiftB = -(turnB * p.t);
        if (faceA.separation >= faceB.separation && cornerOverFace(a, faceA.i, faceA.sign, b, p.R, p.t)) {
            return faceA.separation < speculative &&
                   boxFaceManifold(a, faceA.i, faceA.sign, b, p.R, p.t, feature::Kind::FaceOfA, faceA.sign, speculative,
                                   false, m);
        }
        // b's face is the reference only if no face of a is within 1e-9 as parallel to it (a's
        // face wins such ties in the polyhedral routine).
        if (faceB.separation > faceA.separation && p.absR.col(faceB.j).maxCoeff() < 1 - 2e-9 &&
            cornerOverFace(b, faceB.j, -faceB.sign, a, turnB, shiftB)) {
            return faceB.separation < speculative &&
                   boxFaceManifold(b, faceB.j, -faceB.sign, a, turnB, shiftB, feature::Kind::FaceOfB, faceB.sign,
                                   speculative, false, m);
        }
        const Polytope pa = makeBoxPolytope(a.half, a.rotation, a.center);
        const Polytope pb = makeBoxPolytope(b.half, b.rotation, b.center);
        bool apart = false;
        const bool hit = collideApartPolytopes(pa, pb, speculative, m, apart);
        if (apart) return hit;
    }

    if (edge.i >= 0 && edge.separation > faceSeparation + bias) {
        const Vec3 L = Vec3::Unit(edge.i).cross(p.R.col(edge.j));  // in a's frame
        const Vec3 edgeNormal = edge.sign * (a.rotation * L).normalized();
        const BoxEdge ea = supportEdge(a, edge.i, edgeNormal), eb = supportEdge(b, edge.j, -edgeNormal);
        const SegmentPair c = closestBetweenSegments(ea.p0, ea.p1, eb.p0, eb.p1);
        const double separation = (c.onSecond - c.onFirst).dot(edgeNormal);
        if (separation >= speculative) return false;
        m.normal = edgeNormal;
        m.pointCount = 1;
        m.points[0] = {0.5 * (c.onFirst + c.onSecond), separation, feature::id(feature::Kind::EdgeEdge, ea.id, eb.id)};
        return true;
    }
    if (useB) {
        // In b's frame: a placed by R^T and -R^T t. The reference normal points from b toward a;
        // the manifold's from a to b.
        const Mat3 turn = p.R.transpose();
        return boxFaceManifold(b, faceB.j, -faceB.sign, a, turn, -(turn * p.t), feature::Kind::FaceOfB, faceB.sign,
                               speculative, true, m);
    }
    return boxFaceManifold(a, faceA.i, faceA.sign, b, p.R, p.t, feature::Kind::FaceOfA, faceA.sign, speculative, true, m);
}

}  // namespace anyphys::native

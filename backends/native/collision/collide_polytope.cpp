// Convex polyhedra (hulls, boxes against hulls, mesh triangles) against spheres, capsules and
// each other. Round shapes: the distance routine while apart (exact closest features), the
// separating-axis test once their cores touch. Polyhedra: separating axes on face normals and
// edge-pair directions, then reference-face clipping or the closest points of the edge pair.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "collision/clip.hpp"
#include "collision/feature_id.hpp"
#include "collision/gjk.hpp"
#include "collision/manifold_builder.hpp"
#include "collision/narrow_phase.hpp"
#include "collision/segments.hpp"
#include "collision/tolerances.hpp"

namespace anyphys::native {
namespace {

// Shapes apart count as lying on a face (clipped, several points) when their closest-points
// direction is within about 2.6 degrees of the face normal; each point's separation is then its
// height over the face plane.
constexpr double kFaceAlignment = 0.999;
// Edge directions closer than this (1 - cosine) are one direction.
constexpr double kSameDirection = 1e-9;
// An edge within this fraction of the size of the extreme projection is at the extreme.
constexpr double kSupportTolerance = 1e-9;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::uint32_t featureCode(const CoreFeature& indices) {
    std::uint32_t h = static_cast<std::uint32_t>(indices.size());
    for (int i : indices) h = feature::combine(h, static_cast<std::uint32_t>(i));
    return h;
}

ReferenceFace referenceFace(const Polytope& p, int f) {
    ReferenceFace ref;
    for (int v : p.face(f)) ref.corners.push_back(p.vertices[v]);
    ref.normal = p.normals[f];
    ref.offset = p.offsets[f];
    return ref;
}

struct FaceAxis {
    double separation = -kInfinity;
    int face = -1;
};

// The face of `p` whose plane is farthest from `other` (its lowest vertex above the plane).
// With `oneSided`, only axes that push a shape out of a one-sided triangle's front count: its
// front face, and no face of the other shape facing the way that front does. (For deciding
// whether the shapes are apart every axis counts; the restriction only picks the contact normal.)
FaceAxis faceQuery(const Polytope& p, const Polytope& other, bool oneSided) {
    FaceAxis best;
    const int count = oneSided ? p.axisFaceCount() : p.faceCount();
    for (int f = 0; f < count; ++f) {
        if (oneSided && other.oneSided && p.normals[f].dot(other.normals[0]) > 1e-9) continue;
        if (const double s = other.project(p.normals[f])[0] - p.offsets[f]; s > best.separation) best = {s, f};
    }
    return best;
}

// The distinct edge directions of p (unit; a box has three).
std::vector<Vec3> edgeDirections(const Polytope& p) {
    std::vector<Vec3> dirs;
    for (const auto& [v, w] : p.edges()) {
        const Vec3 u = (p.vertices[w] - p.vertices[v]).normalized();
        if (std::none_of(dirs.begin(), dirs.end(), [&](const Vec3& d) { return std::abs(d.dot(u)) >= 1 - kSameDirection; }))
            dirs.push_back(u);
    }
    return dirs;
}

// The edge of `p` parallel to `dir` that is farthest along `toward`.
int supportEdge(const Polytope& p, const Vec3& dir, const Vec3& toward) {
    const auto& edges = p.edges();
    int best = -1;
    double bestValue = -kInfinity;
    for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
        const Vec3 a = p.vertices[edges[e][0]], b = p.vertices[edges[e][1]];
        if (std::abs((b - a).normalized().dot(dir)) < 1 - kSameDirection) continue;
        if (const double v = toward.dot(a + b); v > bestValue) {
            bestValue = v;
            best = e;
        }
    }
    return best;
}

struct EdgeAxis {
    double separation = -kInfinity;
    Vec3 normal = Vec3::Zero();  // from a toward b
    int edgeA = -1, edgeB = -1;  // the supporting edges along normal (a) and against it (b)
};

// True if edge e of p lies where p reaches farthest along n (both ends at the maximum). Only then
// is an edge-pair axis a face of the Minkowski difference and its edges the touching features;
// other edge pairs can tie with it (at a vertex touch) while their edges are far apart.
bool isSupportEdge(const Polytope& p, int e, const Vec3& n, double tolerance) {
    if (e < 0) return false;
    const double top = p.project(n)[1];
    const auto& ends = p.edges()[e];
    return n.dot(p.vertices[ends[0]]) >= top - tolerance && n.dot(p.vertices[ends[1]]) >= top - tolerance;
}

// Edge pairs of two closed polytopes that are faces of their Minkowski difference: the arcs the
// edges trace on the Gauss map (between their faces' normals; b's negated) cross. Only those can
// realise the separation, and for them it is one dot product (Gregorius, GDC 2013).
EdgeAxis minkowskiEdgeQuery(const Polytope& a, const Polytope& b) {
    // An edge's arc: its faces' normals (b's negated), the normal of their great circle, their
    // sum (pointing into the arc), and the edge itself. The arc lies in the cone of half angle h
    // around the unit `axis` (cosH, sinH): arcs whose cones miss each other cannot cross.
    struct Arc {
        Vec3 n1, n2, circle, middle, p, d, axis;
        double cosH, sinH;
    };
    auto arcs = [](const Polytope& q, double sign) {
        std::vector<Arc> out;
        out.reserve(q.edges().size());
        for (std::size_t e = 0; e < q.edges().size(); ++e) {
            const Vec3 n1 = sign * q.normals[q.edgeFaces()[e][0]], n2 = sign * q.normals[q.edgeFaces()[e][1]];
            const Vec3 p = q.vertices[q.edges()[e][0]];
            const Vec3 axis = (n1 + n2).normalized();
            const double c = std::clamp(axis.dot(n1), -1.0, 1.0);
            out.push_back({n1, n2, n1.cross(n2), n1 + n2, p, q.vertices[q.edges()[e][1]] - p, axis, c, std::sqrt(1 - c * c)});
        }
        return out;
    };
    const std::vector<Arc> arcsA = arcs(a, 1.0), arcsB = arcs(b, -1.0);

    EdgeAxis best;
    for (int i = 0; i < static_cast<int>(arcsA.size()); ++i) {
        const Arc& u = arcsA[i];
        for (int j = 0; j < static_cast<int>(arcsB.size()); ++j) {
            const Arc& w = arcsB[j];
            // Cones apart: the angle between axes exceeds the sum of half angles (with slack).
            if (u.axis.dot(w.axis) < u.cosH * w.cosH - u.sinH * w.sinH - 1e-9) continue;
            // The arcs cross: each one's ends lie on both sides of the other's great circle, and
            // the crossing is the same point of the sphere for both (not antipodal).
            if (w.n1.dot(u.circle) * w.n2.dot(u.circle) >= 0) continue;
            if (u.n1.dot(w.circle) * u.n2.dot(w.circle) >= 0) continue;
            const Vec3 crossing = u.circle.cross(w.circle);
            if (crossing.dot(u.middle) * crossing.dot(w.middle) <= 0) continue;

            Vec3 L = u.d.cross(w.d);
            const double len = L.norm();
            if (len < tolerance::kParallelEdges * u.d.norm() * w.d.norm()) continue;  // parallel: faces cover it
            L /= len;
            if (L.dot(u.middle) < 0) L = -L;  // outward from a at its edge
            if (const double s = L.dot(w.p - u.p); s > best.separation) best = {s, L, i, j};
        }
    }
    return best;
}

// Edge pairs by projecting both polytopes on every cross product of edge directions: for a flat
// triangle, whose Gauss map is degenerate. Only pairs whose edges are the touching features count.
// With `oneSided`, a one-sided b may only push a out of its front.
EdgeAxis edgeQuery(const Polytope& a, const Polytope& b, bool oneSided) {
    EdgeAxis best;
    const auto dirsB = edgeDirections(b);
    for (const Vec3& dirA : edgeDirections(a))
        for (const Vec3& dirB : dirsB) {
            Vec3 L = dirA.cross(dirB);
            const double len = L.norm();
            if (len < tolerance::kParallelEdges) continue;
            L /= len;
            const auto [loA, hiA] = a.project(L);
            const auto [loB, hiB] = b.project(L);
            double along = loB - hiA, against = loA - hiB;  // b beyond a along +L, or along -L
            if (oneSided && b.oneSided && L.dot(b.normals[0]) > 0) along = -kInfinity;
            if (oneSided && b.oneSided && L.dot(b.normals[0]) < 0) against = -kInfinity;
            const double s = std::max(along, against);
            if (s <= best.separation) continue;
            const Vec3 n = along >= against ? L : Vec3(-L);
            const int ea = supportEdge(a, dirA, n), eb = supportEdge(b, dirB, -n);
            const double tolerance = kSupportTolerance * (a.size + b.size);
            if (isSupportEdge(a, ea, n, tolerance) && isSupportEdge(b, eb, -n, tolerance)) best = {s, n, ea, eb};
        }
    return best;
}

// Clips the face of `inc` most opposed to face `refFace` of `ref`. With keepDeepest, inc's
// deepest vertex is added when the clip does not reach its depth (it lies beside the face).
void polytopeFaceContact(const Polytope& ref, int refFace, const Polytope& inc, feature::Kind kind, double speculative,
                         bool keepDeepest, ManifoldBuilder& out) {
    const ReferenceFace face = referenceFace(ref, refFace);
    int incFace = 0;
    double lowest = kInfinity;
    for (int f = 0; f < inc.faceCount(); ++f)
        if (const double d = inc.normals[f].dot(face.normal); d < lowest) {
            lowest = d;
            incFace = f;
        }
    const std::vector<ClipVertex> clipped = clipToFace(incidentPolygon(inc.vertices, inc.face(incFace)), face);
    const std::uint32_t seed = feature::id(kind, refFace, incFace);
    addFacePoints(clipped, face, 0.0, speculative, seed, out);
    if (!keepDeepest) return;
    const int v = inc.support(-face.normal);
    const double depth = face.normal.dot(inc.vertices[v]) - face.offset;
    if (out.deepest() > depth + tolerance::kDistanceSwitch * std::min(ref.size, inc.size))
        addFacePoints({{inc.vertices[v], feature::vertexTag(static_cast<std::uint32_t>(v)), 0}}, face, 0.0, speculative, seed,
                      out);
}

// Index of the edge joining vertices v and w, or -1.
int edgeIndex(const Polytope& p, int v, int w) {
    const auto& edges = p.edges();
    for (int e = 0; e < static_cast<int>(edges.size()); ++e)
        if ((edges[e][0] == v && edges[e][1] == w) || (edges[e][0] == w && edges[e][1] == v)) return e;
    return -1;
}

// Polytopes apart by g.distance (> 0): the closest points are exact. If their direction is the
// normal of a face (a face's interior is closest), that face is the reference and the other's
// face is clipped to it; otherwise (edges or vertices closest) the closest points are the contact.
bool separatedPolytopes(const Polytope& a, const Polytope& b, const GjkResult& g, double speculative, Manifold& m) {
    const Vec3 n = (g.pointB - g.pointA) / g.distance;
    int faceA = 0, faceB = 0;
    double alignA = -kInfinity, alignB = -kInfinity;
    for (int f = 0; f < a.faceCount(); ++f)
        if (const double d = a.normals[f].dot(n); d > alignA) {
            alignA = d;
            faceA = f;
        }
    for (int f = 0; f < b.axisFaceCount(); ++f)
        if (const double d = -b.normals[f].dot(n); d > alignB) {
            alignB = d;
            faceB = f;
        }
    if (std::max(alignA, alignB) >= kFaceAlignment) {
        // As in the overlapping case, a's face wins ties, so ids carry over when they meet.
        const bool useB = alignB > alignA + 1e-9;
        ManifoldBuilder builder(useB ? Vec3(-b.normals[faceB]) : a.normals[faceA]);
        if (useB) polytopeFaceContact(b, faceB, a, feature::Kind::FaceOfB, speculative, false, builder);
        else polytopeFaceContact(a, faceA, b, feature::Kind::FaceOfA, speculative, false, builder);
        // Only if the closest points lie over the face: heights over its plane then never
        // exceed the true distances (else the other shape hangs over an edge of the face).
        if (builder.deepest() <= g.distance + tolerance::kDistanceSwitch * std::min(a.size, b.size))
            return builder.finish(m);
    }
    // Edge against edge gets the id the overlapping case gives that edge pair.
    std::uint32_t id = feature::id(feature::Kind::Closest, featureCode(g.featureA), featureCode(g.featureB));
    if (g.featureA.size() == 2 && g.featureB.size() == 2) {
        const int ea = edgeIndex(a, g.featureA[0], g.featureA[1]), eb = edgeIndex(b, g.featureB[0], g.featureB[1]);
        if (ea >= 0 && eb >= 0) id = feature::id(feature::Kind::EdgeEdge, ea, eb);
    }
    ManifoldBuilder builder(n);
    builder.add(0.5 * (g.pointA + g.pointB), g.distance, id);
    return builder.finish(m);
}

}  // namespace

bool collideSpherePolytope(const SphereGeom& a, const Polytope& b, double speculative, Manifold& m) {
    // Face planes bound the distance from below: a cheap rejection before the distance routine.
    FaceAxis deepest;
    for (int f = 0; f < b.axisFaceCount(); ++f)
        if (const double s = b.normals[f].dot(a.center) - b.offsets[f]; s > deepest.separation) deepest = {s, f};
    if (deepest.separation - a.radius >= speculative) return false;

    const double tol = tolerance::kDistanceSwitch * b.size;
    const GjkResult g = gjkFromFirstVertices(ConvexCore::points({&a.center, 1}), ConvexCore::points(b.vertices), tol);
    if (g.distance > tol) {
        const double separation = g.distance - a.radius;
        if (separation >= speculative) return false;
        const Vec3 n = (g.pointB - a.center) / g.distance;
        ManifoldBuilder builder(n);
        builder.add(0.5 * (a.center + n * a.radius + g.pointB), separation,
                    feature::id(feature::Kind::Closest, featureCode(g.featureB)));
        return builder.finish(m);
    }
    // Centre inside (or on the surface): out through the face whose plane is nearest.
    const Vec3& n = b.normals[deepest.face];
    const double separation = deepest.separation - a.radius;
    ManifoldBuilder builder(-n);
    // Surfaces at a.center - n deepest.separation (the plane) and a.center - n radius.
    builder.add(a.center - n * (0.5 * (deepest.separation + a.radius)), separation,
                feature::id(feature::Kind::FaceOfB, deepest.face));
    return builder.finish(m);
}

bool collideCapsulePolytope(const CapsuleGeom& a, const Polytope& b, double speculative, Manifold& m) {
    const std::array<Vec3, 2> segment{a.p0, a.p1};
    const double r = a.radius;
    for (int f = 0; f < b.axisFaceCount(); ++f)  // lower bounds of the distance, as for the sphere
        if (std::min(b.normals[f].dot(a.p0), b.normals[f].dot(a.p1)) - b.offsets[f] - r >= speculative) return false;

    const double tol = tolerance::kDistanceSwitch * b.size;
    const GjkResult g = gjkFromFirstVertices(ConvexCore::points(segment), ConvexCore::points(b.vertices), tol);
    if (g.distance > tol) {
        if (g.distance - r >= speculative) return false;
        const Vec3 n = (g.pointB - g.pointA) / g.distance;  // from the capsule to the polytope
        int face = 0;
        double alignment = -kInfinity;
        for (int f = 0; f < b.axisFaceCount(); ++f)
            if (const double d = -b.normals[f].dot(n); d > alignment) {
                alignment = d;
                face = f;
            }
        if (alignment >= kFaceAlignment) {  // lying on a face: the part of the segment over it
            const ReferenceFace ref = referenceFace(b, face);
            ManifoldBuilder builder(-ref.normal);
            addFacePoints(clipSegmentToFace(a.p0, a.p1, ref), ref, r, speculative,
                          feature::id(feature::Kind::FaceOfB, face), builder);
            // Only if the closest points lie over the face (see separatedPolytopes).
            if (builder.deepest() <= g.distance - r + tol) return builder.finish(m);
        }
        ManifoldBuilder builder(n);
        builder.add(0.5 * (g.pointA + n * r + g.pointB), g.distance - r,
                    feature::id(feature::Kind::Closest, featureCode(g.featureA), featureCode(g.featureB)));
        return builder.finish(m);
    }

    // Cores touch: separating axes are b's face normals and b's edges crossed with the segment.
    FaceAxis face;
    for (int f = 0; f < b.axisFaceCount(); ++f) {
        const double s = std::min(b.normals[f].dot(a.p0), b.normals[f].dot(a.p1)) - b.offsets[f] - r;
        if (s > face.separation) face = {s, f};
    }
    const Vec3 axis = a.p1 - a.p0;
    const double length = axis.norm();
    EdgeAxis edge;  // normal here points from b toward the capsule
    if (length > 0) {
        const Vec3 u = axis / length;
        for (const Vec3& dir : edgeDirections(b)) {
            Vec3 L = dir.cross(u);
            const double len = L.norm();
            if (len < tolerance::kParallelEdges) continue;
            L /= len;
            const auto [lo, hi] = b.project(L);
            const double segLo = std::min(L.dot(a.p0), L.dot(a.p1)), segHi = std::max(L.dot(a.p0), L.dot(a.p1));
            double above = segLo - hi - r, below = lo - segHi - r;
            // A one-sided b (a triangle) may only push the capsule out of its front.
            if (b.oneSided && L.dot(b.normals[0]) < 0) above = -kInfinity;
            if (b.oneSided && L.dot(b.normals[0]) > 0) below = -kInfinity;
            const double s = std::max(above, below);
            if (s >= speculative) return false;
            if (s > edge.separation) {
                const Vec3 n = above >= below ? L : Vec3(-L);
                const int e = supportEdge(b, dir, n);
                if (isSupportEdge(b, e, n, kSupportTolerance * b.size)) edge = {s, n, e, -1};
            }
        }
    }
    const double bias = tolerance::kAxisBias * std::min(b.size, r + 0.5 * length);
    if (edge.separation > face.separation + bias) {
        const int e = edge.edgeA;
        const auto& ends = b.edges()[e];
        const SegmentPair c = closestBetweenSegments(a.p0, a.p1, b.vertices[ends[0]], b.vertices[ends[1]]);
        ManifoldBuilder builder(-edge.normal);
        builder.add(0.5 * (c.onFirst - edge.normal * r + c.onSecond), edge.separation,
                    feature::id(feature::Kind::EdgeEdge, e));
        return builder.finish(m);
    }
    const ReferenceFace ref = referenceFace(b, face.face);
    ManifoldBuilder builder(-ref.normal);
    addFacePoints(clipSegmentToFace(a.p0, a.p1, ref), ref, r, speculative, feature::id(feature::Kind::FaceOfB, face.face),
                  builder);
    if (builder.empty() && face.separation < speculative) {
        // The segment passes beside the face's prism: its deepest end still touches the face plane.
        const int end = ref.normal.dot(a.p0) <= ref.normal.dot(a.p1) ? 0 : 1;
        addFacePoints({{segment[end], feature::vertexTag(end), 0}}, ref, r, speculative,
                      feature::id(feature::Kind::FaceOfB, face.face), builder);
    }
    return builder.finish(m);
}

bool collidePolytopes(const Polytope& a, const Polytope& b, double speculative, Manifold& m) {
    FaceAxis faceA = faceQuery(a, b, false);
    if (faceA.separation > speculative) return false;
    FaceAxis faceB = faceQuery(b, a, false);
    if (faceB.separation > speculative) return false;
    EdgeAxis edge = a.closed() && b.closed() ? minkowskiEdgeQuery(a, b) : edgeQuery(a, b, false);
    if (edge.separation > speculative) return false;

    // Apart: the axes only bound the distance from below; the distance routine is exact.
    const double tol = tolerance::kDistanceSwitch * std::min(a.size, b.size);
    if (std::max({faceA.separation, faceB.separation, edge.separation}) > tol) {
        const GjkResult g = gjkFromFirstVertices(ConvexCore::points(a.vertices), ConvexCore::points(b.vertices), tol);
        if (g.distance > tol) return g.distance < speculative && separatedPolytopes(a, b, g, speculative, m);
    }
    // Overlapping a one-sided triangle: the way out is through its front only.
    if (b.oneSided) {
        faceA = faceQuery(a, b, true);
        faceB = faceQuery(b, a, true);
        edge = edgeQuery(a, b, true);
    }

    const double bias = tolerance::kAxisBias * std::min(a.size, b.size);
    const bool useB = faceB.separation > faceA.separation + bias;
    const double faceSeparation = useB ? faceB.separation : faceA.separation;

    if (edge.separation > faceSeparation + bias) {
        const int ea = edge.edgeA, eb = edge.edgeB;
        const auto &endsA = a.edges()[ea], &endsB = b.edges()[eb];
        const SegmentPair c = closestBetweenSegments(a.vertices[endsA[0]], a.vertices[endsA[1]], b.vertices[endsB[0]],
                                                     b.vertices[endsB[1]]);
        const double separation = (c.onSecond - c.onFirst).dot(edge.normal);
        if (separation >= speculative) return false;
        ManifoldBuilder builder(edge.normal);
        builder.add(0.5 * (c.onFirst + c.onSecond), separation, feature::id(feature::Kind::EdgeEdge, ea, eb));
        return builder.finish(m);
    }
    if (useB) {
        ManifoldBuilder builder(-b.normals[faceB.face]);
        polytopeFaceContact(b, faceB.face, a, feature::Kind::FaceOfB, speculative, true, builder);
        return builder.finish(m);
    }
    ManifoldBuilder builder(a.normals[faceA.face]);
    polytopeFaceContact(a, faceA.face, b, feature::Kind::FaceOfA, speculative, true, builder);
    return builder.finish(m);
}

bool collideSphereFace(const SphereGeom& a, const Polytope& b, int face, double speculative, Manifold& m) {
    const ReferenceFace ref = referenceFace(b, face);
    ManifoldBuilder builder(-ref.normal);
    addFacePoints(clipToFace({{a.center, feature::vertexTag(0), feature::edgeTag(0)}}, ref), ref, a.radius, speculative,
                  feature::id(feature::Kind::FaceOfB, face), builder);
    return builder.finish(m);
}

bool collideCapsuleFace(const CapsuleGeom& a, const Polytope& b, int face, double speculative, Manifold& m) {
    const ReferenceFace ref = referenceFace(b, face);
    ManifoldBuilder builder(-ref.normal);
    addFacePoints(clipSegmentToFace(a.p0, a.p1, ref), ref, a.radius, speculative, feature::id(feature::Kind::FaceOfB, face),
                  builder);
    return builder.finish(m);
}

bool collidePolytopeFace(const Polytope& a, const Polytope& b, int face, double speculative, Manifold& m) {
    ManifoldBuilder builder(-b.normals[face]);
    polytopeFaceContact(b, face, a, feature::Kind::FaceOfB, speculative, false, builder);
    return builder.finish(m);
}

}  // namespace anyphys::native

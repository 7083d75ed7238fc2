// Convex polyhedra (hulls, boxes against hulls, mesh triangles) against spheres, capsules and
// each other. Round shapes: the distance routine while apart (exact closest features), the
// separating-axis test once their cores touch. Polyhedra: separating axes on face normals and
// edge-pair directions, then reference-face clipping or the closest points of the edge pair.
//
// Polytopes keep their geometry in their own frames; each test turns the few directions it needs
// into the frame of the shape it scans rather than moving every vertex into the world. Buffers
// whose size follows a hull's come from a per-thread scratch set (no allocation once warm).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "collision/clip.hpp"
#include "collision/feature_id.hpp"
#include "collision/gjk.hpp"
#include "collision/manifold_builder.hpp"
#include "collision/narrow_phase.hpp"
#include "collision/scratch.hpp"
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
// Corners of an incident patch count when at most this fraction of the incident shape's size
// above the deepest clipped point: noise on a flat face, not a facet the shape does not rest on.
// (At 1e-4 a cube hull with noise of 1e-4 to 1e-3 of its size rested on too few corners and
// rocked in 5 of 120 cases, at 0.08 to 0.22 m/s; the builder keeps the deepest point whatever
// else it keeps.)
constexpr double kPatchBand = 2e-3;
// An edge within this fraction of the size of the extreme projection is at the extreme.
constexpr double kSupportTolerance = 1e-9;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// An edge's arc on the Gauss map: its faces' normals (b's negated), the normal of their great
// circle and their sum (pointing into the arc). The arc lies in the cone of half angle h around
// the unit `axis` (cosH, sinH): arcs whose cones miss each other cannot cross.
struct Arc {
    Vec3 n1, n2, circle, middle, axis;
    double cosH, sinH;
};

// The arc of an edge between faces with normals n1 and n2 (in whatever frame they are).
Arc makeArc(const Vec3& n1, const Vec3& n2) {
    const Vec3 middle = n1 + n2;
    const Vec3 axis = middle.normalized();
    const double c = std::clamp(axis.dot(n1), -1.0, 1.0);
    return {n1, n2, n1.cross(n2), middle, axis, c, std::sqrt(1 - c * c)};
}

// An edge in some frame: its start, its direction (to its end), its index and its arc.
struct EdgeInFrame {
    Vec3 start, direction;
    int index;
    Arc arc;
};

struct Scratch {
    std::vector<Vec3> corners;  // a reference face's corners
    std::vector<ClipVertex> polygon, spare;
    std::vector<ManifoldBuilder::Candidate> candidates;
    std::vector<Vec3> directionsA, directionsB;  // distinct edge directions
    std::vector<Vec3> normalsB;                  // b's face normals in a's frame, negated
    std::vector<EdgeInFrame> keptA, keptB;       // edges whose pairs may matter
    std::vector<int> patchCorners;               // corners of faces beside the incident face
};

Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

std::uint32_t featureCode(const CoreFeature& indices) {
    std::uint32_t h = static_cast<std::uint32_t>(indices.size());
    for (int i : indices) h = feature::combine(h, static_cast<std::uint32_t>(i));
    return h;
}

ConvexCore coreOf(const Polytope& p) { return ConvexCore::posedPoints(p.vertices, p.rotation, p.position); }

// Face f of p in the world, its corners written to `corners` (room for the face's loop).
ReferenceFace referenceFace(const Polytope& p, int f, std::span<Vec3> corners) {
    const std::vector<int>& loop = p.face(f);
    for (std::size_t i = 0; i < loop.size(); ++i) corners[i] = p.vertex(loop[i]);
    ReferenceFace ref;
    ref.corners = corners.first(loop.size());
    ref.normal = p.normal(f);
    ref.offset = p.offset(f, ref.normal);
    return ref;
}

// Most faces have few corners; larger ones go to the scratch set.
using SmallCorners = std::array<Vec3, 8>;
std::span<Vec3> cornerRoom(SmallCorners& small, const Polytope& p, int f) {
    return room(small, scratch().corners, p.face(f).size());
}

// A builder with room for clipping a face of `inc` to face `refFace` of `ref`, plus inc's
// deepest vertex (a face has at most all of inc's vertices).
ManifoldBuilder faceContactBuilder(const Vec3& normal, const Polytope& ref, int refFace, const Polytope& inc) {
    const std::size_t needed = ref.face(refFace).size() + inc.vertices.size() + 1;
    if (needed <= static_cast<std::size_t>(ManifoldBuilder::kInlineCapacity)) return ManifoldBuilder(normal);
    return ManifoldBuilder(normal, firstOf(scratch().candidates, needed));
}

struct FaceAxis {
    double separation = -kInfinity;
    int face = -1;
};

// p's faces seen from other's frame: p's normals turned by `turn`, p's position shifted.
struct FacesInFrame {
    Mat3 turn;
    Vec3 shift;

    FacesInFrame(const Polytope& p, const Polytope& other)
        : turn(other.rotation.transpose() * p.rotation), shift(other.rotation.transpose() * (other.position - p.position)) {}

    // Height of other's lowest vertex over the plane of p's face f (n: its normal in other's frame).
    double separation(const Polytope& p, int f, const Polytope& other, const Vec3& n) const {
        return other.localLowest(n) + n.dot(shift) - p.offsets[static_cast<std::size_t>(f)];
    }
    double separation(const Polytope& p, int f, const Polytope& other) const {
        return separation(p, f, other, turn * p.normals[static_cast<std::size_t>(f)]);
    }
};

// The face of `p` whose plane is farthest from `other` (its lowest vertex above the plane), or
// the first found farther than `stopAbove`. With `oneSided`, only axes that push a shape out of
// a one-sided triangle's front count: its front face, and no face of the other shape facing the
// way that front does. (For deciding whether the shapes are apart every axis counts; the
// restriction only picks the contact normal.)
FaceAxis faceQuery(const Polytope& p, const Polytope& other, bool oneSided, double stopAbove = kInfinity) {
    const FacesInFrame frame(p, other);
    const bool skipFacing = oneSided && other.oneSided;
    const Vec3 otherFront = skipFacing ? Vec3(other.normal(0)) : Vec3::Zero();
    FaceAxis best;
    const int count = oneSided ? p.axisFaceCount() : p.faceCount();
    for (int f = 0; f < count; ++f) {
        if (skipFacing && p.normal(f).dot(otherFront) > 1e-9) continue;
        if (const double s = frame.separation(p, f, other); s > best.separation) {
            best = {s, f};
            if (s > stopAbove) break;
        }
    }
    return best;
}

// Rounding allowance on the upper bounds below (they only skip work; a generous one costs little).
double boundSlack(const Polytope& a, const Polytope& b) { return 1e-9 * (a.size() + b.size()); }

// faceQuery (two-sided) without measuring every face. A face's separation is at most the height
// of other's centre over it, so a face whose bound is below the best so far cannot win, and one
// whose bound is at most `irrelevantAtOrBelow` cannot matter (see collidePolytopes): both are
// skipped. `seed` (a face, or -1) is measured first: the last contact's reference face, else the
// face turned most toward other, bounds the rest tightly. Ties go to the lowest index, as there.
FaceAxis prunedFaceQuery(const Polytope& p, const Polytope& other, int seed, double irrelevantAtOrBelow, double stopAbove) {
    const FacesInFrame frame(p, other);
    const Vec3 centre = other.localCenter() + frame.shift;  // other's centre seen from p, in other's frame
    const double slack = boundSlack(p, other);
    if (seed < 0 || seed >= p.faceCount()) {
        const Vec3 toward = p.rotation.transpose() * (other.center - p.center);
        double most = -kInfinity;
        for (int f = 0; f < p.faceCount(); ++f)
            if (const double d = p.normals[static_cast<std::size_t>(f)].dot(toward); d > most) {
                most = d;
                seed = f;
            }
    }
    FaceAxis best{frame.separation(p, seed, other), seed};
    if (best.separation > stopAbove) return best;
    for (int f = 0; f < p.faceCount(); ++f) {
        if (f == seed) continue;
        const Vec3 n = frame.turn * p.normals[static_cast<std::size_t>(f)];
        const double bound = n.dot(centre) - p.offsets[static_cast<std::size_t>(f)] + slack;
        if (bound < best.separation || bound <= irrelevantAtOrBelow) continue;
        const double s = frame.separation(p, f, other, n);
        if (s > best.separation || (s == best.separation && f < best.face)) {
            best = {s, f};
            if (s > stopAbove) break;
        }
    }
    return best;
}

// The distinct edge directions of p (world, unit; a box has its three axes), kept in `out`.
std::span<const Vec3> edgeDirections(const Polytope& p, std::vector<Vec3>& out) {
    out.clear();
    if (p.isBox) {
        for (int k = 0; k < 3; ++k) out.push_back(p.rotation.col(k));
        return out;
    }
    for (const auto& [v, w] : p.edges) {
        const Vec3 u = (p.vertices[static_cast<std::size_t>(w)] - p.vertices[static_cast<std::size_t>(v)]).normalized();
        if (std::none_of(out.begin(), out.end(), [&](const Vec3& d) { return std::abs(d.dot(u)) >= 1 - kSameDirection; }))
            out.push_back(u);
    }
    for (Vec3& d : out) d = p.rotation * d;
    return out;
}

// The edge of `p` parallel to `dir` that is farthest along `toward` (both world).
int supportEdge(const Polytope& p, const Vec3& dir, const Vec3& toward) {
    const Vec3 d = p.rotation.transpose() * dir, t = p.rotation.transpose() * toward;
    int best = -1;
    double bestValue = -kInfinity;
    for (int e = 0; e < static_cast<int>(p.edges.size()); ++e) {
        const auto& ends = p.edges[static_cast<std::size_t>(e)];
        const Vec3& a = p.vertices[static_cast<std::size_t>(ends[0])];
        const Vec3& b = p.vertices[static_cast<std::size_t>(ends[1])];
        if (std::abs((b - a).normalized().dot(d)) < 1 - kSameDirection) continue;
        if (const double v = t.dot(a + b); v > bestValue) {
            bestValue = v;
            best = e;
        }
    }
    return best;
}

struct EdgeAxis {
    double separation = -kInfinity;
    Vec3 normal = Vec3::Zero();  // world, from a toward b
    int edgeA = -1, edgeB = -1;  // the supporting edges along normal (a) and against it (b)
};

// True if edge e of p lies where p reaches farthest along n (both ends at the maximum). Only then
// is an edge-pair axis a face of the Minkowski difference and its edges the touching features;
// other edge pairs can tie with it (at a vertex touch) while their edges are far apart.
bool isSupportEdge(const Polytope& p, int e, const Vec3& n, double tolerance) {
    if (e < 0) return false;
    const Vec3 local = p.rotation.transpose() * n;
    const double top = p.localProject(local)[1];
    const auto& ends = p.edges[static_cast<std::size_t>(e)];
    return local.dot(p.vertices[static_cast<std::size_t>(ends[0])]) >= top - tolerance &&
           local.dot(p.vertices[static_cast<std::size_t>(ends[1])]) >= top - tolerance;
}

// An upper bound of L.w over the unit vectors L of the arc from n1 to n2 (less than a half
// circle). L = (s n1 + t n2) / |s n1 + t n2| with s, t >= 0, and |s n1 + t n2| lies between
// (s + t) |n1 + n2| / 2 and s + t, so L.w <= m / (|n1 + n2| / 2) if m = max(n1.w, n2.w) >= 0,
// else L.w <= m.
double arcMax(const Vec3& n1, const Vec3& n2, const Vec3& w) {
    const double m = std::max(n1.dot(w), n2.dot(w));
    return m < 0 ? m : 2 * m / (n1 + n2).norm();
}

// Edge pairs of two closed polytopes that are faces of their Minkowski difference: the arcs the
// edges trace on the Gauss map (between their faces' normals; b's negated) cross. Only those can
// realise the separation, and for them it is one dot product (Gregorius, GDC 2013). Worked in
// a's frame; stops at the first pair farther apart than `stopAbove`.
//
// Only separations above `relevant` matter (see collidePolytopes). Along any normal L of a's arc
// the separation is at most L.(b's centre - the edge), and along b's at most L.(the edge - a's
// centre): an edge whose arc keeps that bound at or below `relevant` is skipped with all its
// pairs. Separations are compared exactly, so the outcome is the full query's.
EdgeAxis minkowskiEdgeQuery(const Polytope& a, const Polytope& b, double relevant, double stopAbove) {
    Scratch& s = scratch();
    const Mat3 turn = a.rotation.transpose() * b.rotation;  // b's frame -> a's
    const Vec3 shift = a.rotation.transpose() * (b.position - a.position);
    const std::span<Vec3> normalsB = firstOf(s.normalsB, b.normals.size());
    for (std::size_t f = 0; f < normalsB.size(); ++f) normalsB[f] = -(turn * b.normals[f]);

    // The edges that may matter, with their start, direction and arc in a's frame.
    const double threshold = relevant - boundSlack(a, b);
    const Vec3 centreA = a.localCenter(), centreB = a.rotation.transpose() * (b.center - a.position);
    const auto keep = [threshold](const Polytope& p, std::span<const Vec3> normals, int e, const Vec3& start,
                                  const Vec3& toCentre, std::vector<EdgeInFrame>& kept) {
        const Vec3& n1 = normals[static_cast<std::size_t>(p.edgeFaces[static_cast<std::size_t>(e)][0])];
        const Vec3& n2 = normals[static_cast<std::size_t>(p.edgeFaces[static_cast<std::size_t>(e)][1])];
        if (arcMax(n1, n2, toCentre) <= threshold) return false;
        kept.push_back({start, Vec3::Zero(), e, makeArc(n1, n2)});
        return true;
    };
    std::vector<EdgeInFrame>& keptA = s.keptA;
    std::vector<EdgeInFrame>& keptB = s.keptB;
    keptA.clear();
    keptB.clear();
    for (int i = 0; i < static_cast<int>(a.edges.size()); ++i) {
        const auto& ends = a.edges[static_cast<std::size_t>(i)];
        const Vec3& p = a.vertices[static_cast<std::size_t>(ends[0])];
        if (keep(a, a.normals, i, p, centreB - p, keptA))
            keptA.back().direction = a.vertices[static_cast<std::size_t>(ends[1])] - p;
    }
    for (int j = 0; j < static_cast<int>(b.edges.size()); ++j) {
        const auto& ends = b.edges[static_cast<std::size_t>(j)];
        const Vec3& v0 = b.vertices[static_cast<std::size_t>(ends[0])];
        const Vec3 p = turn * v0 + shift;
        // Along L, b reaches down to L.p at this edge, a up to at least L.(a's centre).
        if (keep(b, normalsB, j, p, p - centreA, keptB))
            keptB.back().direction = turn * (b.vertices[static_cast<std::size_t>(ends[1])] - v0);
    }

    EdgeAxis best;
    Vec3 bestNormal = Vec3::Zero();
    const auto scan = [&] {
        for (const EdgeInFrame& ea : keptA) {
            const Arc& u = ea.arc;
            for (const EdgeInFrame& eb : keptB) {
                const Arc& w = eb.arc;
                // Cones apart: the angle between axes exceeds the sum of half angles (with slack).
                if (u.axis.dot(w.axis) < u.cosH * w.cosH - u.sinH * w.sinH - 1e-9) continue;
                // The arcs cross: each one's ends lie on both sides of the other's great circle, and
                // the crossing is the same point of the sphere for both (not antipodal).
                if (w.n1.dot(u.circle) * w.n2.dot(u.circle) >= 0) continue;
                if (u.n1.dot(w.circle) * u.n2.dot(w.circle) >= 0) continue;
                const Vec3 crossing = u.circle.cross(w.circle);
                if (crossing.dot(u.middle) * crossing.dot(w.middle) <= 0) continue;

                Vec3 L = ea.direction.cross(eb.direction);
                const double len = L.norm();
                // Parallel: the faces cover it.
                if (len < tolerance::kParallelEdges * ea.direction.norm() * eb.direction.norm()) continue;
                L /= len;
                if (L.dot(u.middle) < 0) L = -L;  // outward from a at its edge
                if (const double sep = L.dot(eb.start - ea.start); sep > best.separation) {
                    best = {sep, Vec3::Zero(), ea.index, eb.index};
                    bestNormal = L;
                    if (sep > stopAbove) return;
                }
            }
        }
    };
    scan();
    best.normal = a.rotation * bestNormal;
    return best;
}

// Edge pairs by projecting both polytopes on every cross product of edge directions: for a flat
// triangle, whose Gauss map is degenerate. Only pairs whose edges are the touching features count.
// With `oneSided`, a one-sided b may only push a out of its front.
EdgeAxis edgeQuery(const Polytope& a, const Polytope& b, bool oneSided) {
    Scratch& s = scratch();
    EdgeAxis best;
    const std::span<const Vec3> dirsA = edgeDirections(a, s.directionsA), dirsB = edgeDirections(b, s.directionsB);
    const Vec3 frontB = b.oneSided ? Vec3(b.normal(0)) : Vec3::Zero();
    for (const Vec3& dirA : dirsA)
        for (const Vec3& dirB : dirsB) {
            Vec3 L = dirA.cross(dirB);
            const double len = L.norm();
            if (len < tolerance::kParallelEdges) continue;
            L /= len;
            const auto [loA, hiA] = a.project(L);
            const auto [loB, hiB] = b.project(L);
            double along = loB - hiA, against = loA - hiB;  // b beyond a along +L, or along -L
            if (oneSided && b.oneSided && L.dot(frontB) > 0) along = -kInfinity;
            if (oneSided && b.oneSided && L.dot(frontB) < 0) against = -kInfinity;
            const double sep = std::max(along, against);
            if (sep <= best.separation) continue;
            const Vec3 n = along >= against ? L : Vec3(-L);
            const int ea = supportEdge(a, dirA, n), eb = supportEdge(b, dirB, -n);
            const double tolerance = kSupportTolerance * (a.size() + b.size());
            if (isSupportEdge(a, ea, n, tolerance) && isSupportEdge(b, eb, -n, tolerance)) best = {sep, n, ea, eb};
        }
    return best;
}

// Whether `p` lies over the reference face: inside every side plane (corners counter-clockwise
// about the normal).
bool overFace(const Vec3& p, const ReferenceFace& face) {
    const std::size_t n = face.corners.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& c = face.corners[i];
        const Vec3 outward = (face.corners[(i + 1) % n] - c).cross(face.normal);
        if ((p - c).dot(outward) > 0) return false;
    }
    return true;
}

// A hull whose points carry a little noise (a scan, rounding) has its bottom split into facets
// tilted by less than a thousandth of a radian against each other. Clipping only the facet most
// opposed to the reference face, the manifold held one facet, the next step another, and such a
// cube rocked on the ground for ever (0.03 to 0.12 m/s with points jittered by 1e-5 to 1e-4 of its
// size). The corners of inc's other faces turned as far toward the reference face (within
// kFaceAlignment) are contact points too, where they lie over it and within the speculative
// distance; the builder keeps the four that span the most. A box's or a clean hull's face has
// no such neighbour, so this adds nothing there.
void addPatchCorners(const ReferenceFace& face, const Polytope& inc, int incFace, const Vec3& against, double speculative,
                     std::uint32_t seed, ManifoldBuilder& out) {
    std::vector<int>& corners = scratch().patchCorners;
    corners.clear();
    for (int f = 0; f < inc.faceCount(); ++f)
        if (f != incFace && inc.normals[static_cast<std::size_t>(f)].dot(against) <= -kFaceAlignment)
            corners.insert(corners.end(), inc.face(f).begin(), inc.face(f).end());
    if (corners.empty()) return;
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    const std::vector<int>& clippedLoop = inc.face(incFace);  // its corners are in the clip already
    const double deepestAllowed = out.deepest() + kPatchBand * inc.size();
    for (const int v : corners) {
        if (std::find(clippedLoop.begin(), clippedLoop.end(), v) != clippedLoop.end()) continue;
        const Vec3 corner = inc.vertex(v);
        if (face.normal.dot(corner) - face.offset > deepestAllowed || !overFace(corner, face)) continue;
        const ClipVertex point{corner, feature::vertexTag(static_cast<std::uint32_t>(v)), 0};
        addFacePoints({&point, 1}, face, 0.0, speculative, seed, out);
    }
}

// Whether world point x lies within the closed polytope p (behind every face plane).
bool contains(const Polytope& p, const Vec3& x) {
    for (int f = 0; f < p.faceCount(); ++f) {
        const Vec3 n = p.normal(f);
        if (n.dot(x) > p.offset(f, n)) return false;
    }
    return true;
}

// Clips the face of `inc` most opposed to face `refFace` of `ref`. With keepDeepest, inc's
// deepest vertex is added when the clip does not reach its depth and the vertex lies inside
// ref, or when the clip leaves no point.
void polytopeFaceContact(const Polytope& ref, int refFace, const Polytope& inc, feature::Kind kind, double speculative,
                         bool keepDeepest, ManifoldBuilder& out) {
    Scratch& s = scratch();
    SmallCorners small;
    const ReferenceFace face = referenceFace(ref, refFace, cornerRoom(small, ref, refFace));
    const Vec3 against = inc.rotation.transpose() * face.normal;
    int incFace = 0, turnedToRef = 0;  // turnedToRef: faces within kFaceAlignment of facing it
    double lowest = kInfinity;
    for (int f = 0; f < inc.faceCount(); ++f) {
        const double d = inc.normals[static_cast<std::size_t>(f)].dot(against);
        if (d <= -kFaceAlignment) ++turnedToRef;
        if (d < lowest) {
            lowest = d;
            incFace = f;
        }
    }
    const std::vector<int>& loop = inc.face(incFace);
    const std::size_t capacity = loop.size() + face.corners.size();
    std::array<ClipVertex, 16> smallPolygon, smallSpare;
    const std::span<ClipVertex> polygon = room(smallPolygon, s.polygon, capacity);
    const std::span<ClipVertex> spare = room(smallSpare, s.spare, capacity);
    for (std::size_t i = 0; i < loop.size(); ++i) polygon[i] = incidentVertex(inc.vertex(loop[i]), loop[i]);
    const std::span<const ClipVertex> clipped = clipToFace(polygon, static_cast<int>(loop.size()), spare, face);
    const std::uint32_t seed = feature::id(kind, refFace, incFace);
    addFacePoints(clipped, face, 0.0, speculative, seed, out);
    if (turnedToRef > 1) addPatchCorners(face, inc, incFace, against, speculative, seed, out);
    if (!keepDeepest) return;
    // inc's deepest vertex, if the clip did not reach its depth, lies beside the face. It is a
    // contact only inside ref (a hull may widen below the face; a box never does, see
    // collide_box.cpp), or as a stand-in when the clip left nothing. Outside ref it would hold inc
    // up by the face's plane extended (a box over a table's edge stayed on the table).
    const int v = inc.support(-face.normal);
    const Vec3 deepest = inc.vertex(v);
    const double depth = face.normal.dot(deepest) - face.offset;
    if (!(out.deepest() > depth + tolerance::kDistanceSwitch * std::min(ref.size(), inc.size()))) return;
    if (!out.empty() && !(ref.closed() && contains(ref, deepest))) return;
    const ClipVertex corner{deepest, feature::vertexTag(static_cast<std::uint32_t>(v)), 0};
    addFacePoints({&corner, 1}, face, 0.0, speculative, seed, out);
}

// Index of the edge joining vertices v and w, or -1.
int edgeIndex(const Polytope& p, int v, int w) {
    for (int e = 0; e < static_cast<int>(p.edges.size()); ++e) {
        const auto& ends = p.edges[static_cast<std::size_t>(e)];
        if ((ends[0] == v && ends[1] == w) || (ends[0] == w && ends[1] == v)) return e;
    }
    return -1;
}

// The face of p whose normal is closest to the world direction n, and that alignment (cosine).
FaceAxis alignedFace(const Polytope& p, int count, const Vec3& n) {
    const Vec3 local = p.rotation.transpose() * n;
    FaceAxis best;
    for (int f = 0; f < count; ++f)
        if (const double d = p.normals[static_cast<std::size_t>(f)].dot(local); d > best.separation) best = {d, f};
    return best;
}

// Polytopes apart by g.distance (> 0): the closest points are exact. If their direction is the
// normal of a face (a face's interior is closest), that face is the reference and the other's
// face is clipped to it; otherwise (edges or vertices closest) the closest points are the contact.
bool separatedPolytopes(const Polytope& a, const Polytope& b, const GjkResult& g, double speculative, Manifold& m) {
    const Vec3 n = (g.pointB - g.pointA) / g.distance;
    const FaceAxis alignA = alignedFace(a, a.faceCount(), n), alignB = alignedFace(b, b.axisFaceCount(), -n);
    if (std::max(alignA.separation, alignB.separation) >= kFaceAlignment) {
        // As in the overlapping case, a's face wins ties, so ids carry over when they meet.
        const bool useB = alignB.separation > alignA.separation + 1e-9;
        const Vec3 normal = useB ? Vec3(-b.normal(alignB.face)) : a.normal(alignA.face);
        ManifoldBuilder builder =
            useB ? faceContactBuilder(normal, b, alignB.face, a) : faceContactBuilder(normal, a, alignA.face, b);
        if (useB) polytopeFaceContact(b, alignB.face, a, feature::Kind::FaceOfB, speculative, false, builder);
        else polytopeFaceContact(a, alignA.face, b, feature::Kind::FaceOfA, speculative, false, builder);
        // Only if the closest points lie over the face: heights over its plane then never
        // exceed the true distances (else the other shape hangs over an edge of the face).
        if (builder.deepest() <= g.distance + tolerance::kDistanceSwitch * std::min(a.size(), b.size()))
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

// The separation along the axis a cache remembers (-infinity if it names none of these shapes').
double cachedSeparation(const Polytope& a, const Polytope& b, const CollideCache& cache) {
    if (!cache.separating) return -kInfinity;
    const auto fits = [](int index, std::size_t count) { return index >= 0 && static_cast<std::size_t>(index) < count; };
    switch (cache.axis) {
        case CollideCache::FaceOfA:
            if (fits(cache.indexA, a.faces.size())) return FacesInFrame(a, b).separation(a, cache.indexA, b);
            break;
        case CollideCache::FaceOfB:
            if (fits(cache.indexB, b.faces.size())) return FacesInFrame(b, a).separation(b, cache.indexB, a);
            break;
        case CollideCache::EdgePair: {
            if (!fits(cache.indexA, a.edges.size()) || !fits(cache.indexB, b.edges.size())) break;
            const auto& ea = a.edges[static_cast<std::size_t>(cache.indexA)];
            const auto& eb = b.edges[static_cast<std::size_t>(cache.indexB)];
            const Vec3 da = a.vertex(ea[1]) - a.vertex(ea[0]), db = b.vertex(eb[1]) - b.vertex(eb[0]);
            Vec3 L = da.cross(db);
            const double len = L.norm();
            if (len < tolerance::kParallelEdges * da.norm() * db.norm()) break;
            L /= len;
            // Any direction bounds the distance from below by the gap of the projections.
            const auto [loA, hiA] = a.project(L);
            const auto [loB, hiB] = b.project(L);
            return std::max(loB - hiA, loA - hiB);
        }
        default:
            break;
    }
    return -kInfinity;
}

}  // namespace

bool collideSpherePolytope(const SphereGeom& a, const Polytope& b, double speculative, Manifold& m) {
    // Face planes bound the distance from below: a cheap rejection before the distance routine.
    const Vec3 local = b.rotation.transpose() * (a.center - b.position);
    FaceAxis deepest;
    for (int f = 0; f < b.axisFaceCount(); ++f)
        if (const double s = b.normals[static_cast<std::size_t>(f)].dot(local) - b.offsets[static_cast<std::size_t>(f)];
            s > deepest.separation)
            deepest = {s, f};
    if (deepest.separation - a.radius >= speculative) return false;

    const double tol = tolerance::kDistanceSwitch * b.size();
    const GjkResult g = gjkFromFirstVertices(ConvexCore::points({&a.center, 1}), coreOf(b), tol);
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
    const Vec3 n = b.normal(deepest.face);
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
    const Vec3 q0 = b.rotation.transpose() * (a.p0 - b.position), q1 = b.rotation.transpose() * (a.p1 - b.position);
    // Per face of b: the lower end's height over its plane, less the radius.
    auto faceSeparation = [&](int f) {
        const Vec3& n = b.normals[static_cast<std::size_t>(f)];
        return std::min(n.dot(q0), n.dot(q1)) - b.offsets[static_cast<std::size_t>(f)] - r;
    };
    for (int f = 0; f < b.axisFaceCount(); ++f)  // lower bounds of the distance, as for the sphere
        if (faceSeparation(f) >= speculative) return false;

    const double tol = tolerance::kDistanceSwitch * b.size();
    const GjkResult g = gjkFromFirstVertices(ConvexCore::points(segment), coreOf(b), tol);
    if (g.distance > tol) {
        if (g.distance - r >= speculative) return false;
        const Vec3 n = (g.pointB - g.pointA) / g.distance;  // from the capsule to the polytope
        const FaceAxis aligned = alignedFace(b, b.axisFaceCount(), -n);
        if (aligned.separation >= kFaceAlignment) {  // lying on a face: the part of the segment over it
            SmallCorners small;
            const ReferenceFace ref = referenceFace(b, aligned.face, cornerRoom(small, b, aligned.face));
            ManifoldBuilder builder(-ref.normal);
            addFacePoints(clipSegmentToFace(a.p0, a.p1, ref).view(), ref, r, speculative,
                          feature::id(feature::Kind::FaceOfB, aligned.face), builder);
            // Only if the closest points lie over the face (see separatedPolytopes).
            if (builder.deepest() <= g.distance - r + tol) return builder.finish(m);
            // They lie beside it: the capsule's low end hangs over an edge of the face while part
            // of it lies over the face, nearly parallel (within kFaceAlignment). On a mesh triangle
            // that edge is usually shared, and the part over this face is then the only support
            // there: the closest point alone let a capsule lying along an internal edge, tilted by
            // 3e-5 rad, fall for a step at its raised end. Both hold it up. (A closed polytope's edge
            // is a real edge: the closest point alone lets the capsule pivot on it.)
            if (b.oneSided && !builder.empty()) {
                builder.add(0.5 * (g.pointA + n * r + g.pointB), g.distance - r,
                            feature::id(feature::Kind::Closest, featureCode(g.featureA), featureCode(g.featureB)));
                return builder.finish(m);
            }
        }
        ManifoldBuilder builder(n);
        builder.add(0.5 * (g.pointA + n * r + g.pointB), g.distance - r,
                    feature::id(feature::Kind::Closest, featureCode(g.featureA), featureCode(g.featureB)));
        return builder.finish(m);
    }

    // Cores touch: separating axes are b's face normals and b's edges crossed with the segment.
    FaceAxis face;
    for (int f = 0; f < b.axisFaceCount(); ++f)
        if (const double s = faceSeparation(f); s > face.separation) face = {s, f};
    const Vec3 axis = a.p1 - a.p0;
    const double length = axis.norm();
    EdgeAxis edge;  // normal here points from b toward the capsule
    if (length > 0) {
        const Vec3 u = axis / length;
        const Vec3 frontB = b.oneSided ? Vec3(b.normal(0)) : Vec3::Zero();
        for (const Vec3& dir : edgeDirections(b, scratch().directionsB)) {
            Vec3 L = dir.cross(u);
            const double len = L.norm();
            if (len < tolerance::kParallelEdges) continue;
            L /= len;
            const auto [lo, hi] = b.project(L);
            const double segLo = std::min(L.dot(a.p0), L.dot(a.p1)), segHi = std::max(L.dot(a.p0), L.dot(a.p1));
            double above = segLo - hi - r, below = lo - segHi - r;
            // A one-sided b (a triangle) may only push the capsule out of its front.
            if (b.oneSided && L.dot(frontB) < 0) above = -kInfinity;
            if (b.oneSided && L.dot(frontB) > 0) below = -kInfinity;
            const double s = std::max(above, below);
            if (s >= speculative) return false;
            if (s > edge.separation) {
                const Vec3 n = above >= below ? L : Vec3(-L);
                const int e = supportEdge(b, dir, n);
                if (isSupportEdge(b, e, n, kSupportTolerance * b.size())) edge = {s, n, e, -1};
            }
        }
    }
    const double bias = tolerance::kAxisBias * std::min(b.size(), r + 0.5 * length);
    if (edge.separation > face.separation + bias) {
        const auto& ends = b.edges[static_cast<std::size_t>(edge.edgeA)];
        const SegmentPair c = closestBetweenSegments(a.p0, a.p1, b.vertex(ends[0]), b.vertex(ends[1]));
        ManifoldBuilder builder(-edge.normal);
        builder.add(0.5 * (c.onFirst - edge.normal * r + c.onSecond), edge.separation,
                    feature::id(feature::Kind::EdgeEdge, edge.edgeA));
        return builder.finish(m);
    }
    SmallCorners small;
    const ReferenceFace ref = referenceFace(b, face.face, cornerRoom(small, b, face.face));
    ManifoldBuilder builder(-ref.normal);
    addFacePoints(clipSegmentToFace(a.p0, a.p1, ref).view(), ref, r, speculative,
                  feature::id(feature::Kind::FaceOfB, face.face), builder);
    if (builder.empty() && face.separation < speculative) {
        // The segment passes beside the face's prism: its deepest end still touches the face plane.
        const int end = ref.normal.dot(a.p0) <= ref.normal.dot(a.p1) ? 0 : 1;
        const ClipVertex v{segment[static_cast<std::size_t>(end)], feature::vertexTag(static_cast<std::uint32_t>(end)), 0};
        addFacePoints({&v, 1}, ref, r, speculative, feature::id(feature::Kind::FaceOfB, face.face), builder);
    }
    return builder.finish(m);
}

bool collidePolytopes(const Polytope& a, const Polytope& b, double speculative, Manifold& m, CollideCache* cache) {
    // Still apart along the axis that separated them last time: nothing else to do.
    if (cache && cachedSeparation(a, b, *cache) > speculative) return false;
    auto separated = [&](CollideCache::Axis axis, int indexA, int indexB) {
        if (cache) *cache = {axis, true, indexA, indexB};
        return false;
    };
    const double tol = tolerance::kDistanceSwitch * std::min(a.size(), b.size());
    const double bias = tolerance::kAxisBias * std::min(a.size(), b.size());
    const bool closed = a.closed() && b.closed();
    FaceAxis faceA, faceB;
    EdgeAxis edge;
    if (closed) {
        // Exact maxima, skipping what cannot matter: a's faces are all compared; b's face matters
        // only if it ends the test, shows the shapes apart or beats a's face by the bias; an edge
        // pair only if it ends the test, shows them apart or beats the chosen face.
        const int seedA = cache && !cache->separating && cache->axis == CollideCache::FaceOfA ? cache->indexA : -1;
        const int seedB = cache && !cache->separating && cache->axis == CollideCache::FaceOfB ? cache->indexB : -1;
        faceA = prunedFaceQuery(a, b, seedA, -kInfinity, speculative);
        if (faceA.separation > speculative) return separated(CollideCache::FaceOfA, faceA.face, 0);
        faceB = prunedFaceQuery(b, a, seedB, std::min({speculative, tol, faceA.separation + bias}), speculative);
        if (faceB.separation > speculative) return separated(CollideCache::FaceOfB, 0, faceB.face);
        const double faceSeparation = faceB.separation > faceA.separation + bias ? faceB.separation : faceA.separation;
        edge = minkowskiEdgeQuery(a, b, std::min({speculative, tol, faceSeparation + bias}), speculative);
    } else {
        faceA = faceQuery(a, b, false, speculative);
        if (faceA.separation > speculative) return separated(CollideCache::FaceOfA, faceA.face, 0);
        faceB = faceQuery(b, a, false, speculative);
        if (faceB.separation > speculative) return separated(CollideCache::FaceOfB, 0, faceB.face);
        edge = edgeQuery(a, b, false);
    }
    if (edge.separation > speculative) return separated(CollideCache::EdgePair, edge.edgeA, edge.edgeB);
    if (cache) *cache = {};

    // Apart: the axes only bound the distance from below; the distance routine is exact.
    if (std::max({faceA.separation, faceB.separation, edge.separation}) > tol) {
        bool apart = false;
        const bool hit = collideApartPolytopes(a, b, speculative, m, apart);
        if (apart) return hit;
    }
    // Overlapping a one-sided triangle: the way out is through its front only.
    if (b.oneSided) {
        faceA = faceQuery(a, b, true);
        faceB = faceQuery(b, a, true);
        edge = edgeQuery(a, b, true);
    }

    const bool useB = faceB.separation > faceA.separation + bias;
    const double faceSeparation = useB ? faceB.separation : faceA.separation;

    if (edge.separation > faceSeparation + bias) {
        const int ea = edge.edgeA, eb = edge.edgeB;
        const auto &endsA = a.edges[static_cast<std::size_t>(ea)], &endsB = b.edges[static_cast<std::size_t>(eb)];
        const SegmentPair c = closestBetweenSegments(a.vertex(endsA[0]), a.vertex(endsA[1]), b.vertex(endsB[0]),
                                                     b.vertex(endsB[1]));
        const double separation = (c.onSecond - c.onFirst).dot(edge.normal);
        if (separation >= speculative) return false;
        ManifoldBuilder builder(edge.normal);
        builder.add(0.5 * (c.onFirst + c.onSecond), separation, feature::id(feature::Kind::EdgeEdge, ea, eb));
        return builder.finish(m);
    }
    if (useB) {
        if (cache) *cache = {CollideCache::FaceOfB, false, 0, faceB.face};
        ManifoldBuilder builder = faceContactBuilder(-b.normal(faceB.face), b, faceB.face, a);
        polytopeFaceContact(b, faceB.face, a, feature::Kind::FaceOfB, speculative, true, builder);
        return builder.finish(m);
    }
    if (cache) *cache = {CollideCache::FaceOfA, false, faceA.face, 0};
    ManifoldBuilder builder = faceContactBuilder(a.normal(faceA.face), a, faceA.face, b);
    polytopeFaceContact(a, faceA.face, b, feature::Kind::FaceOfA, speculative, true, builder);
    return builder.finish(m);
}

bool collideApartPolytopes(const Polytope& a, const Polytope& b, double speculative, Manifold& m, bool& apart) {
    const double tol = tolerance::kDistanceSwitch * std::min(a.size(), b.size());
    const GjkResult g = gjkFromFirstVertices(coreOf(a), coreOf(b), tol);
    apart = g.distance > tol;
    return apart && g.distance < speculative && separatedPolytopes(a, b, g, speculative, m);
}

bool collideSphereFace(const SphereGeom& a, const Polytope& b, int face, double speculative, Manifold& m) {
    SmallCorners small;
    const ReferenceFace ref = referenceFace(b, face, cornerRoom(small, b, face));
    ManifoldBuilder builder(-ref.normal);
    // A one-vertex polygon: kept if the centre is over the face.
    std::array<ClipVertex, 16> smallPolygon, smallSpare;
    const std::size_t capacity = 1 + ref.corners.size();
    const std::span<ClipVertex> polygon = room(smallPolygon, scratch().polygon, capacity);
    const std::span<ClipVertex> spare = room(smallSpare, scratch().spare, capacity);
    polygon[0] = {a.center, feature::vertexTag(0), feature::edgeTag(0)};
    addFacePoints(clipToFace(polygon, 1, spare, ref), ref, a.radius, speculative, feature::id(feature::Kind::FaceOfB, face),
                  builder);
    return builder.finish(m);
}

bool collideCapsuleFace(const CapsuleGeom& a, const Polytope& b, int face, double speculative, Manifold& m) {
    SmallCorners small;
    const ReferenceFace ref = referenceFace(b, face, cornerRoom(small, b, face));
    ManifoldBuilder builder(-ref.normal);
    addFacePoints(clipSegmentToFace(a.p0, a.p1, ref).view(), ref, a.radius, speculative,
                  feature::id(feature::Kind::FaceOfB, face), builder);
    return builder.finish(m);
}

bool collidePolytopeFace(const Polytope& a, const Polytope& b, int face, double speculative, Manifold& m) {
    ManifoldBuilder builder = faceContactBuilder(-b.normal(face), b, face, a);
    polytopeFaceContact(b, face, a, feature::Kind::FaceOfB, speculative, false, builder);
    return builder.finish(m);
}

}  // namespace anyphys::native

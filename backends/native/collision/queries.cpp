// Per-shape geometric queries: bounds, ray casts, GJK distance, conservative-advancement time of
// impact and overlap.
#include "collision/queries.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "collision/mesh_data.hpp"

namespace anyphys::native {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Half size of the box standing in for an infinite plane: large, but finite so that tree
// arithmetic (perimeters, merges) stays finite.
constexpr double kPlaneExtent = 1e6;

bool isConvex(ShapeType t) {
    return t == ShapeType::Sphere || t == ShapeType::Capsule || t == ShapeType::Box || t == ShapeType::Convex;
}

Transform inverse(const Transform& xf) {
    const Quat qInv = xf.orientation.conjugate();
    return {qInv * (-xf.position), qInv};
}

Transform compose(const Transform& a, const Transform& b) {
    return {a.position + a.orientation * b.position, a.orientation * b.orientation};
}

Vec3 apply(const Transform& xf, const Vec3& p) { return xf.position + xf.orientation * p; }

// ---------------------------------------------------------------------------------------------
// Bounds

Aabb pointsAabb(const std::vector<Vec3>& points, const Transform& xf) {
    const Mat3 r = xf.orientation.toRotationMatrix();
    Aabb box{Vec3::Constant(kInf), Vec3::Constant(-kInf)};
    for (const Vec3& p : points) {
        const Vec3 w = r * p;
        box.min = box.min.cwiseMin(w);
        box.max = box.max.cwiseMax(w);
    }
    box.min += xf.position;
    box.max += xf.position;
    return box;
}

// Exact bounds of the solid half-space n.p <= offset within the cube |p_i| <= kPlaneExtent: along
// axis i the half-space reaches at most (offset + L * sum_{j != i} |n_j|) / n_i.
Aabb planeAabb(const Vec3& n, double offset) {
    const double l = kPlaneExtent;
    Aabb box{Vec3::Constant(-l), Vec3::Constant(l)};
    const double sumAbs = n.cwiseAbs().sum();
    for (int i = 0; i < 3; ++i) {
        if (std::abs(n[i]) < 1e-12) continue;
        const double reach = (offset + l * (sumAbs - std::abs(n[i]))) / n[i];
        if (n[i] > 0.0) {
            box.max[i] = std::clamp(reach, -l, l);
        } else {
            box.min[i] = std::clamp(reach, -l, l);
        }
    }
    return box;
}

// ---------------------------------------------------------------------------------------------
// Ray casts, each in the shape's local frame (dir unit). Results are local too.

std::optional<RayHit> raySphere(const Vec3& center, double radius, const Vec3& o, const Vec3& d, double maxT) {
    const Vec3 m = o - center;
    const double b = m.dot(d);
    const double c = m.squaredNorm() - radius * radius;
    if (c < 0.0 || b > 0.0) return std::nullopt;  // starts inside, or outside and leaving
    const double disc = b * b - c;
    if (disc < 0.0) return std::nullopt;
    const double t = std::max(0.0, -b - std::sqrt(disc));
    if (t > maxT) return std::nullopt;
    RayHit hit;
    hit.distance = t;
    hit.point = o + t * d;
    hit.normal = (hit.point - center) / radius;
    return hit;
}

double segmentPointDistance(const Vec3& a, const Vec3& b, const Vec3& p) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).norm();
}

// The capsule is the union of a cylinder and two end spheres: its first hit is the earliest of
// theirs (the origin is outside all of them), the cylinder counting only within the segment.
std::optional<RayHit> rayCapsule(double r, double h, const Vec3& o, const Vec3& d, double maxT) {
    const Vec3 top(0, h, 0);
    const Vec3 bottom(0, -h, 0);
    if (segmentPointDistance(bottom, top, o) < r) return std::nullopt;
    std::optional<RayHit> best;
    auto consider = [&](const std::optional<RayHit>& hit) {
        if (hit && (!best || hit->distance < best->distance)) best = hit;
    };
    const double a = d.x() * d.x() + d.z() * d.z();
    if (a > 1e-300) {
        const double b = o.x() * d.x() + o.z() * d.z();
        const double c = o.x() * o.x() + o.z() * o.z() - r * r;
        const double disc = b * b - a * c;
        if (disc >= 0.0) {
            const double t = std::max(0.0, (-b - std::sqrt(disc)) / a);
            const Vec3 p = o + t * d;
            if (t <= maxT && std::abs(p.y()) <= h && b <= 0.0) {
                RayHit hit;
                hit.distance = t;
                hit.point = p;
                hit.normal = Vec3(p.x(), 0.0, p.z()) / r;
                consider(hit);
            }
        }
    }
    consider(raySphere(top, r, o, d, maxT));
    consider(raySphere(bottom, r, o, d, maxT));
    return best;
}

// Slab test; the entering slab gives the normal.
std::optional<RayHit> rayBox(const Vec3& half, const Vec3& o, const Vec3& d, double maxT) {
    double tEnter = -kInf;
    double tExit = kInf;
    Vec3 normal = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
        if (std::abs(d[i]) < 1e-300) {
            if (o[i] < -half[i] || o[i] > half[i]) return std::nullopt;
            continue;
        }
        const double t1 = (-half[i] - o[i]) / d[i];
        const double t2 = (half[i] - o[i]) / d[i];
        const double tNear = std::min(t1, t2);
        if (tNear > tEnter) {
            tEnter = tNear;
            normal = Vec3::Zero();
            normal[i] = d[i] > 0.0 ? -1.0 : 1.0;
        }
        tExit = std::min(tExit, std::max(t1, t2));
        if (tEnter > tExit) return std::nullopt;
    }
    // tEnter < 0: the origin is inside (or the box is behind it).
    if (tEnter < 0.0 || tEnter > maxT) return std::nullopt;
    return RayHit{tEnter, o + tEnter * d, normal};
}

// Clip the ray by every face plane n.x <= offset; the last plane entered gives the normal.
std::optional<RayHit> rayHull(const HullData& hull, const Vec3& o, const Vec3& d, double maxT) {
    double tEnter = -kInf;
    double tExit = kInf;
    Vec3 normal = Vec3::Zero();
    for (std::size_t f = 0; f < hull.faceNormals.size(); ++f) {
        const Vec3& n = hull.faceNormals[f];
        const double numer = hull.faceOffsets[f] - n.dot(o);  // > 0: origin inside this plane
        const double denom = n.dot(d);
        if (denom == 0.0) {
            if (numer < 0.0) return std::nullopt;
            continue;
        }
        const double t = numer / denom;
        if (denom < 0.0) {
            if (t > tEnter) {
                tEnter = t;
                normal = n;
            }
        } else {
            tExit = std::min(tExit, t);
        }
        if (tEnter > tExit) return std::nullopt;
    }
    if (tEnter < 0.0 || tEnter > maxT) return std::nullopt;
    return RayHit{tEnter, o + tEnter * d, normal};
}

// Möller-Trumbore, two-sided (a mesh is a surface).
std::optional<double> rayTriangle(const std::array<Vec3, 3>& v, const Vec3& o, const Vec3& d, double maxT) {
    const Vec3 e1 = v[1] - v[0];
    const Vec3 e2 = v[2] - v[0];
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-14 * e1.norm() * e2.norm()) return std::nullopt;  // parallel
    const double inv = 1.0 / det;
    const Vec3 s = o - v[0];
    const double u = s.dot(p) * inv;
    if (u < 0.0 || u > 1.0) return std::nullopt;
    const Vec3 q = s.cross(e1);
    const double w = d.dot(q) * inv;
    if (w < 0.0 || u + w > 1.0) return std::nullopt;
    const double t = e2.dot(q) * inv;
    if (t < 0.0 || t > maxT) return std::nullopt;
    return t;
}

std::optional<RayHit> rayMesh(const MeshData& mesh, const Vec3& o, const Vec3& d, double maxT) {
    std::optional<RayHit> best;
    mesh.rayCastTriangles(o, d, maxT, [&](int tri, double clip) {
        const auto t = rayTriangle(mesh.triangleVertices(tri), o, d, clip);
        if (!t) return clip;
        const Vec3& n = mesh.normals[static_cast<std::size_t>(tri)];
        best = RayHit{*t, o + *t * d, n.dot(d) > 0.0 ? Vec3(-n) : n};
        return *t > 0.0 ? *t : 0.0;  // a hit at 0 cannot be beaten: stop
    });
    return best;
}

// ---------------------------------------------------------------------------------------------
// GJK on "cores" (point, segment, box, hull, triangle) with radii added afterwards, as in Box2D's
// b2Distance: spheres and capsules stay exact and every support is a numbered vertex, which
// gives GJK a sure termination test (a repeated vertex).

class Core {
public:
    static Core of(const Shape& s, const Transform& xf) {
        Core c;
        c.rotation_ = xf.orientation.toRotationMatrix();
        c.position_ = xf.position;
        switch (s.type) {
            case ShapeType::Sphere:
                c.local_[0] = Vec3::Zero();
                c.count_ = 1;
                c.radius_ = s.radius;
                break;
            case ShapeType::Capsule:
                c.local_[0] = Vec3(0, -s.halfHeight, 0);
                c.local_[1] = Vec3(0, s.halfHeight, 0);
                c.count_ = 2;
                c.radius_ = s.radius;
                break;
            case ShapeType::Box:
                for (int i = 0; i < 8; ++i)
                    c.local_[static_cast<std::size_t>(i)] =
                        Vec3(i & 1 ? s.halfExtents.x() : -s.halfExtents.x(), i & 2 ? s.halfExtents.y() : -s.halfExtents.y(),
                             i & 4 ? s.halfExtents.z() : -s.halfExtents.z());
                c.count_ = 8;
                c.isBox_ = true;
                break;
            case ShapeType::Convex:
                if (!s.hull || s.hull->vertices.empty()) throw std::invalid_argument("convex shape without hull");
                c.hull_ = &s.hull->vertices;
                c.count_ = static_cast<int>(s.hull->vertices.size());
                break;
            default:
                throw std::invalid_argument("Core::of: not a convex shape");
        }
        return c;
    }

    static Core triangle(const std::array<Vec3, 3>& world) {
        Core c;
        for (std::size_t i = 0; i < 3; ++i) c.local_[i] = world[i];
        c.count_ = 3;
        return c;
    }

    /// Index of a vertex furthest along `dir` (world).
    int support(const Vec3& dir) const {
        const Vec3 d = rotation_.transpose() * dir;
        if (isBox_) return (d.x() >= 0.0 ? 1 : 0) | (d.y() >= 0.0 ? 2 : 0) | (d.z() >= 0.0 ? 4 : 0);
        int best = 0;
        double bestDot = -kInf;
        for (int i = 0; i < count_; ++i) {
            const double dot = localVertex(i).dot(d);
            if (dot > bestDot) {
                bestDot = dot;
                best = i;
            }
        }
        return best;
    }

    Vec3 vertex(int i) const { return position_ + rotation_ * localVertex(i); }
    double radius() const { return radius_; }

private:
    const Vec3& localVertex(int i) const {
        return hull_ ? (*hull_)[static_cast<std::size_t>(i)] : local_[static_cast<std::size_t>(i)];
    }

    Mat3 rotation_ = Mat3::Identity();
    Vec3 position_ = Vec3::Zero();
    std::array<Vec3, 8> local_{};
    const std::vector<Vec3>* hull_ = nullptr;  // convex: the hull's own vertices, not copied
    int count_ = 0;
    double radius_ = 0.0;
    bool isBox_ = false;
};

struct SimplexVertex {
    Vec3 wA = Vec3::Zero();  // support point on A
    Vec3 wB = Vec3::Zero();  // support point on B
    Vec3 w = Vec3::Zero();   // wB - wA: a point of the Minkowski difference B - A
    int iA = 0;
    int iB = 0;
    double bary = 1.0;
};

struct Simplex {
    std::array<SimplexVertex, 4> v;
    int count = 0;
};

/// Closest point to the origin of a sub-simplex: which vertices (indices into the simplex) and
/// their barycentric weights.
struct Closest {
    std::array<int, 3> index{};
    std::array<double, 3> bary{};
    int count = 0;
    Vec3 point = Vec3::Zero();
};

Closest closestOnSegment(const Simplex& s, int ia, int ib) {
    const Vec3& a = s.v[static_cast<std::size_t>(ia)].w;
    const Vec3& b = s.v[static_cast<std::size_t>(ib)].w;
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? -a.dot(ab) / len2 : 0.0;
    if (t <= 0.0) return {{ia, 0, 0}, {1.0, 0, 0}, 1, a};
    if (t >= 1.0) return {{ib, 0, 0}, {1.0, 0, 0}, 1, b};
    return {{ia, ib, 0}, {1.0 - t, t, 0}, 2, a + t * ab};
}

// Voronoi-region walk (Ericson, Real-Time Collision Detection 5.1.5) with the query point at
// the origin; a degenerate (flat) triangle falls back to its best edge.
Closest closestOnTriangle(const Simplex& s, int ia, int ib, int ic) {
    const Vec3& a = s.v[static_cast<std::size_t>(ia)].w;
    const Vec3& b = s.v[static_cast<std::size_t>(ib)].w;
    const Vec3& c = s.v[static_cast<std::size_t>(ic)].w;
    const Vec3 ab = b - a;
    const Vec3 ac = c - a;
    const double d1 = -ab.dot(a);
    const double d2 = -ac.dot(a);
    if (d1 <= 0.0 && d2 <= 0.0) return {{ia, 0, 0}, {1.0, 0, 0}, 1, a};
    const double d3 = -ab.dot(b);
    const double d4 = -ac.dot(b);
    if (d3 >= 0.0 && d4 <= d3) return {{ib, 0, 0}, {1.0, 0, 0}, 1, b};
    const double d5 = -ab.dot(c);
    const double d6 = -ac.dot(c);
    if (d6 >= 0.0 && d5 <= d6) return {{ic, 0, 0}, {1.0, 0, 0}, 1, c};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) return closestOnSegment(s, ia, ib);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) return closestOnSegment(s, ia, ic);
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) return closestOnSegment(s, ib, ic);
    const double denom = va + vb + vc;
    if (!(denom > 1e-300)) {
        Closest best = closestOnSegment(s, ia, ib);
        for (const Closest& e : {closestOnSegment(s, ia, ic), closestOnSegment(s, ib, ic)})
            if (e.point.squaredNorm() < best.point.squaredNorm()) best = e;
        return best;
    }
    const double v = vb / denom;
    const double w = vc / denom;
    return {{ia, ib, ic}, {1.0 - v - w, v, w}, 3, a + v * ab + w * ac};
}

/// Closest point of a tetrahedron's boundary faces that the origin lies beyond (each tested
/// against the opposite vertex; a flat tetrahedron puts every face under test); nullopt when the
/// origin is inside.
std::optional<Closest> closestOnTetrahedron(const Simplex& s) {
    constexpr int faces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
    std::optional<Closest> best;
    for (const auto& f : faces) {
        const Vec3& p = s.v[static_cast<std::size_t>(f[0])].w;
        const Vec3 n = (s.v[static_cast<std::size_t>(f[1])].w - p).cross(s.v[static_cast<std::size_t>(f[2])].w - p);
        const double sideOrigin = -n.dot(p);
        const double sideOpposite = n.dot(s.v[static_cast<std::size_t>(f[3])].w - p);
        if (sideOrigin * sideOpposite > 0.0) continue;
        const Closest c = closestOnTriangle(s, f[0], f[1], f[2]);
        if (!best || c.point.squaredNorm() < best->point.squaredNorm()) best = c;
    }
    return best;
}

/// Reduces the simplex to the vertices supporting its closest point to the origin; returns
/// false when the origin is inside the tetrahedron (the shapes overlap).
bool solveSimplex(Simplex& s, Vec3& closest) {
    std::optional<Closest> c;
    switch (s.count) {
        case 1: c = Closest{{0, 0, 0}, {1.0, 0, 0}, 1, s.v[0].w}; break;
        case 2: c = closestOnSegment(s, 0, 1); break;
        case 3: c = closestOnTriangle(s, 0, 1, 2); break;
        default: c = closestOnTetrahedron(s); break;
    }
    if (!c) return false;
    std::array<SimplexVertex, 3> kept;
    for (std::size_t i = 0; i < static_cast<std::size_t>(c->count); ++i) {
        kept[i] = s.v[static_cast<std::size_t>(c->index[i])];
        kept[i].bary = c->bary[i];
    }
    std::copy(kept.begin(), kept.begin() + c->count, s.v.begin());
    s.count = c->count;
    closest = c->point;
    return true;
}

struct CoreDistance {
    Vec3 pointA = Vec3::Zero();  // closest points of the cores (radii not included)
    Vec3 pointB = Vec3::Zero();
    double distance = 0.0;
    bool overlap = false;
};

CoreDistance gjk(const Core& a, const Core& b, const Vec3& initialDir) {
    Simplex s;
    auto makeVertex = [&](const Vec3& dir) {  // minimises dir . (wB - wA)
        SimplexVertex v;
        v.iA = a.support(dir);
        v.iB = b.support(-dir);
        v.wA = a.vertex(v.iA);
        v.wB = b.vertex(v.iB);
        v.w = v.wB - v.wA;
        return v;
    };
    s.v[0] = makeVertex(initialDir.squaredNorm() > 0.0 ? initialDir : Vec3::UnitX());
    s.count = 1;

    CoreDistance out;
    constexpr int kMaxIterations = 64;
    for (int iter = 0;; ++iter) {
        // The vertices before reduction: a support point among them means no progress is
        // possible (the main termination test, as in Box2D; it also stops cycling).
        const Simplex before = s;
        Vec3 v;
        if (!solveSimplex(s, v)) {
            // Origin inside the tetrahedron: report its centroid as the (meaningless) witness.
            for (SimplexVertex& sv : s.v) sv.bary = 0.25;
            out.overlap = true;
            break;
        }
        const double vv = v.squaredNorm();
        if (vv < 1e-24) {  // touching to 1e-12 m: call it overlap
            out.overlap = true;
            break;
        }
        if (iter == kMaxIterations) break;
        const SimplexVertex next = makeVertex(v);
        bool repeated = false;
        double scale = next.w.squaredNorm();
        for (int i = 0; i < before.count; ++i) {
            const SimplexVertex& sv = before.v[static_cast<std::size_t>(i)];
            repeated = repeated || (sv.iA == next.iA && sv.iB == next.iB);
            scale = std::max(scale, sv.w.squaredNorm());
        }
        // No new vertex, or no progress toward the origin beyond rounding (v carries an error
        // of about 1e-16 times the simplex's size, so v.w does too): v is the answer.
        if (repeated || vv - v.dot(next.w) <= 1e-12 * vv + 1e-14 * scale) break;
        s.v[static_cast<std::size_t>(s.count++)] = next;
    }
    for (int i = 0; i < s.count; ++i) {
        const SimplexVertex& sv = s.v[static_cast<std::size_t>(i)];
        out.pointA += sv.bary * sv.wA;
        out.pointB += sv.bary * sv.wB;
    }
    out.distance = out.overlap ? 0.0 : (out.pointB - out.pointA).norm();
    return out;
}

// Closest points of two convex shapes: GJK on the cores, then the radii. When the cores are
// closer than the radii, the points are the two deepest surface points (they have crossed).
DistanceResult convexDistance(const Core& a, const Core& b, const Vec3& initialDir) {
    const CoreDistance g = gjk(a, b, initialDir);
    DistanceResult r;
    if (g.overlap || g.distance <= 0.0) {
        r.pointA = r.pointB = 0.5 * (g.pointA + g.pointB);
        return r;
    }
    const Vec3 n = (g.pointB - g.pointA) / g.distance;
    r.normal = n;
    r.pointA = g.pointA + a.radius() * n;
    r.pointB = g.pointB - b.radius() * n;
    r.distance = std::max(0.0, g.distance - a.radius() - b.radius());
    return r;
}

// Closed form: the deepest point of A along -n decides.
DistanceResult planeDistance(const Core& a, const Shape& plane) {
    const Vec3& n = plane.normal;
    const Vec3 deepest = a.vertex(a.support(-n)) - a.radius() * n;
    const double separation = n.dot(deepest) - plane.offset;
    DistanceResult r;
    r.distance = std::max(0.0, separation);
    r.pointA = deepest;
    r.pointB = deepest - separation * n;  // its projection on the plane
    r.normal = -n;
    return r;
}

// Min over triangles near A. The search box grows until it holds a triangle at most as far as
// its margin (then no unseen triangle can be closer).
DistanceResult meshDistance(const Shape& a, const Transform& xfA, const Shape& meshShape, const Transform& xfB) {
    const MeshData& mesh = *meshShape.mesh;
    const Core core = Core::of(a, xfA);
    const Aabb local = computeAabb(a, compose(inverse(xfB), xfA));
    const Aabb meshBox = mesh.tree.rootAabb();
    DistanceResult best;
    best.distance = kInf;
    double margin = std::max(1e-3, 0.5 * local.extents().maxCoeff());
    while (true) {
        bool found = false;
        const Aabb searchBox = local.fattened(margin);
        mesh.queryTriangles(searchBox, [&](int tri) {
            found = true;
            std::array<Vec3, 3> v = mesh.triangleVertices(tri);
            for (Vec3& p : v) p = apply(xfB, p);
            const DistanceResult r = convexDistance(core, Core::triangle(v), v[0] - xfA.position);
            if (r.distance < best.distance) best = r;
            return best.distance > 0.0;
        });
        if (found && best.distance <= margin) return best;
        if (found) {
            // The next pass sees every triangle that could be closer (a hair more for rounding).
            margin = best.distance * (1.0 + 1e-9) + 1e-12;
        } else if (searchBox.contains(meshBox)) {
            return best;  // an empty mesh: nothing to be near
        } else {
            margin *= 4.0;
        }
    }
}

/// How far any surface point of a convex shape lies from its frame origin: bounds the motion a
/// rotation causes. A sphere is unchanged by rotation about its centre, hence 0.
double maxRadius(const Shape& s) {
    switch (s.type) {
        case ShapeType::Sphere: return 0.0;
        case ShapeType::Capsule: return s.halfHeight + s.radius;
        case ShapeType::Box: return s.halfExtents.norm();
        case ShapeType::Convex: {
            double r = 0.0;
            for (const Vec3& v : s.hull->vertices) r = std::max(r, v.norm());
            return r;
        }
        default: return 0.0;
    }
}

/// Conservative advancement of a over [0, tEnd] against a convex b given by its distance
/// function. With n the separating normal at t, no point of a approaches b faster than
/// n.dx + angle * rMax (per unit t), so advancing by (d - target) / that bound never passes
/// the target distance.
template <class DistanceFn>
double advance(const Transform& start, const Transform& end, double rMax, double target, double tEnd,
               const DistanceFn& distanceAt) {
    constexpr int kMaxIterations = 30;
    const double tolerance = 0.05 * target;  // accept distances in [target, 1.05 target]
    const Vec3 dx = end.position - start.position;
    const double angle = start.orientation.angularDistance(end.orientation);
    double t = 0.0;
    for (int iter = 0; iter < kMaxIterations; ++iter) {
        const Transform xf{start.position + t * dx, start.orientation.slerp(t, end.orientation)};
        const DistanceResult d = distanceAt(xf);
        if (d.distance <= target + tolerance) return t;
        const double approach = d.normal.dot(dx) + angle * rMax;
        if (approach <= 0.0) return tEnd;  // moving apart
        t += (d.distance - target) / approach;
        if (t >= tEnd) return tEnd;
    }
    return t;  // out of iterations: t is still safe (never past the target)
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public queries

Aabb computeAabb(const Shape& s, const Transform& xf) {
    switch (s.type) {
        case ShapeType::Sphere: return {xf.position.array() - s.radius, xf.position.array() + s.radius};
        case ShapeType::Capsule: {
            const Vec3 axis = (xf.orientation * Vec3(0, s.halfHeight, 0)).cwiseAbs();
            return {xf.position - axis - Vec3::Constant(s.radius), xf.position + axis + Vec3::Constant(s.radius)};
        }
        case ShapeType::Box: {
            const Vec3 e = xf.orientation.toRotationMatrix().cwiseAbs() * s.halfExtents;
            return {xf.position - e, xf.position + e};
        }
        case ShapeType::Plane: return planeAabb(s.normal, s.offset);
        case ShapeType::Convex: return pointsAabb(s.hull->vertices, xf);
        case ShapeType::Mesh: return pointsAabb(s.mesh->vertices, xf);
        case ShapeType::Compound: break;
    }
    throw std::invalid_argument("computeAabb: compound shapes are flattened before they reach the backend");
}

std::optional<RayHit> raycast(const Shape& s, const Transform& xf, const Vec3& origin, const Vec3& dir, double maxDistance) {
    if (s.type == ShapeType::Plane) {  // world frame
        const double height = s.normal.dot(origin) - s.offset;
        const double denom = s.normal.dot(dir);
        if (height < 0.0 || denom >= 0.0) return std::nullopt;  // inside, or not heading down to it
        const double t = -height / denom;
        if (t > maxDistance) return std::nullopt;
        return RayHit{t, origin + t * dir, s.normal};
    }
    const Quat qInv = xf.orientation.conjugate();
    const Vec3 o = qInv * (origin - xf.position);
    const Vec3 d = qInv * dir;
    std::optional<RayHit> hit;
    switch (s.type) {
        case ShapeType::Sphere: hit = raySphere(Vec3::Zero(), s.radius, o, d, maxDistance); break;
        case ShapeType::Capsule: hit = rayCapsule(s.radius, s.halfHeight, o, d, maxDistance); break;
        case ShapeType::Box: hit = rayBox(s.halfExtents, o, d, maxDistance); break;
        case ShapeType::Convex: hit = rayHull(*s.hull, o, d, maxDistance); break;
        case ShapeType::Mesh: hit = rayMesh(*s.mesh, o, d, maxDistance); break;
        default: break;
    }
    if (hit) {
        hit->point = apply(xf, hit->point);
        hit->normal = xf.orientation * hit->normal;
    }
    return hit;
}

DistanceResult distance(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
    const bool convexA = isConvex(a.type);
    const bool convexB = isConvex(b.type);
    if (convexA && convexB) return convexDistance(Core::of(a, xfA), Core::of(b, xfB), xfB.position - xfA.position);
    if (convexA && b.type == ShapeType::Plane) return planeDistance(Core::of(a, xfA), b);
    if (convexA && b.type == ShapeType::Mesh) return meshDistance(a, xfA, b, xfB);
    if (convexB) {  // plane or mesh first: answer the swapped question, swap back
        DistanceResult r = distance(b, xfB, a, xfA);
        std::swap(r.pointA, r.pointB);
        r.normal = -r.normal;
        return r;
    }
    // Two static shapes: never asked by the pipeline; they are "infinitely" apart.
    DistanceResult r;
    r.distance = kInf;
    return r;
}

double timeOfImpact(const Shape& a, const Transform& startA, const Transform& endA, const Shape& b, const Transform& xfB,
                    double target) {
    if (!isConvex(a.type)) throw std::invalid_argument("timeOfImpact: the moving shape must be convex");
    const double rMax = maxRadius(a);
    if (b.type != ShapeType::Mesh)
        return advance(startA, endA, rMax, target, 1.0, [&](const Transform& xf) { return distance(a, xf, b, xfB); });

    // A mesh is not convex: its nearest triangle's normal does not bound the approach to the
    // others. Advance against each triangle the sweep can reach and keep the earliest.
    const MeshData& mesh = *b.mesh;
    const Transform toMesh = inverse(xfB);
    const double angle = startA.orientation.angularDistance(endA.orientation);
    // Any point strays at most 2 angle rMax from the union of its start and end boxes.
    const Aabb sweep = computeAabb(a, compose(toMesh, startA))
                           .merged(computeAabb(a, compose(toMesh, endA)))
                           .fattened(2.0 * angle * rMax + target);
    double earliest = 1.0;
    mesh.queryTriangles(sweep, [&](int tri) {
        std::array<Vec3, 3> v = mesh.triangleVertices(tri);
        for (Vec3& p : v) p = apply(xfB, p);
        const Core triangle = Core::triangle(v);
        earliest = advance(startA, endA, rMax, target, earliest, [&](const Transform& xf) {
            return convexDistance(Core::of(a, xf), triangle, v[0] - xf.position);
        });
        return earliest > 0.0;
    });
    return earliest;
}

bool overlap(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
    return distance(a, xfA, b, xfB).distance <= 0.0;
}

}  // namespace anyphys::native

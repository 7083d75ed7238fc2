#include "box2d_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "anyphys/limits.hpp"
#include "anyphys/error.hpp"
#include "box2d_convert.hpp"

namespace anyphys::box2d {
namespace {

using Vec2 = Eigen::Vector2d;

// Box2D welds polygon vertices closer than this (b2PolygonShape::Set); our outlines weld the
// same way so the vertex count we check is the count Box2D would use.
constexpr double kWeld = 0.5 * b2_linearSlop;

// A vertex this close to the line through its neighbours is left out of an outline. Box2D clips
// contacts against one edge at a time, so a face split into facets a hair apart (a scanned or
// noisy hull) rests on one short facet and rocks; a step this small is well inside the slop that
// Box2D's contacts rest within anyway. (Found by the noisy-cube contract test on other random
// draws: 34 of 120 rocked, at 0.04 to 0.52 m/s, with noise of 1e-5 to 1e-3 of the cube's size.)
constexpr double kFlatVertex = 0.25 * b2_linearSlop;

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Counter-clockwise convex outline of points in the plane (Andrew's monotone chain), with
// near-coincident and collinear vertices removed.
std::vector<Vec2> convexOutline(std::vector<Vec2> p) {
    if (p.size() < 3) return p;
    std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
    double extent = 0.0;
    for (const Vec2& q : p) extent = std::max(extent, (q - p.front()).norm());
    const double flat = 1e-12 * std::max(extent * extent, 1e-12);
    std::vector<Vec2> hull(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {  // lower chain
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= flat) --k;
        hull[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
        while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= flat) --k;
        hull[k++] = p[i];
    }
    hull.resize(k > 1 ? k - 1 : k);
    // Weld as Box2D does, then drop the flattest vertex while one lies within kFlatVertex of the
    // chord of its neighbours (flattest first, so a gentle arc loses no more than it must). The
    // outline moves by less than that (a right-angle corner with edges past kWeld stands 1.8 mm off).
    const double flatVertex = std::min(kFlatVertex, 0.02 * extent);
    while (hull.size() > 3) {
        std::size_t flattest = hull.size();
        double least = flatVertex;
        for (std::size_t i = 0; i < hull.size(); ++i) {
            const Vec2& prev = hull[(i + hull.size() - 1) % hull.size()];
            const Vec2& next = hull[(i + 1) % hull.size()];
            if ((hull[i] - next).norm() < kWeld) {
                least = 0.0, flattest = i;
                break;
            }
            const double height = cross(prev, hull[i], next) / (next - prev).norm();
            if (height < least) least = height, flattest = i;
        }
        if (flattest == hull.size()) break;
        hull.erase(hull.begin() + static_cast<std::ptrdiff_t>(flattest));
    }
    return hull;
}

double area(const std::vector<Vec2>& v) {
    double a = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) a += cross(Vec2::Zero(), v[i], v[(i + 1) % v.size()]);
    return 0.5 * a;
}

// The outline moved inward by `inset` (each edge's line shifted along its normal), or nothing if
// an edge would vanish or come closer to Box2D's weld distance.
std::optional<std::vector<Vec2>> inset(const std::vector<Vec2>& v, double by) {
    const std::size_t n = v.size();
    std::vector<Vec2> normal(n);
    std::vector<double> offset(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 e = (v[(i + 1) % n] - v[i]).normalized();
        normal[i] = Vec2(e.y(), -e.x());
        offset[i] = normal[i].dot(v[i]) - by;
    }
    std::vector<Vec2> out(n);
    for (std::size_t i = 0; i < n; ++i) {  // vertex i: lines of edges i-1 and i
        const Vec2& n1 = normal[(i + n - 1) % n];
        const Vec2& n2 = normal[i];
        const double c1 = offset[(i + n - 1) % n], c2 = offset[i];
        const double det = n1.x() * n2.y() - n1.y() * n2.x();
        out[i] = Vec2((c1 * n2.y() - c2 * n1.y()) / det, (n1.x() * c2 - n2.x() * c1) / det);
    }
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 e = out[(i + 1) % n] - out[i];
        if (e.dot(v[(i + 1) % n] - v[i]) <= 0 || e.norm() < 1.5 * kWeld) return std::nullopt;
    }
    return out;
}

float cross(const b2Vec2& o, const b2Vec2& a, const b2Vec2& b) { return b2Cross(a - o, b - o); }

// Whether Box2D 2.4.1's b2PolygonShape::Set takes these float vertices without tripping one of
// its assertions. It welds vertices closer than kWeld, wraps the rest in a hull with float cross
// products (gift wrapping from the rightmost vertex, the farther of two collinear candidates),
// and needs three hull vertices, edges longer than b2_epsilon and an area above b2_epsilon. An
// outline that passes the checks in double can still fail them in float: a sliver 1e7 m long
// whose far vertex rounds the near ones onto one line (the API fuzzer found one).
bool box2dAcceptsPolygon(const std::vector<b2Vec2>& vertices) {
    constexpr float weld = 0.5f * b2_linearSlop;  // in float, as Box2D computes it
    std::vector<b2Vec2> p;
    for (const b2Vec2& v : vertices)
        if (std::none_of(p.begin(), p.end(), [&](const b2Vec2& q) { return b2DistanceSquared(v, q) < weld * weld; }))
            p.push_back(v);
    if (p.size() < 3) return false;
    std::size_t start = 0;
    for (std::size_t i = 1; i < p.size(); ++i)
        if (p[i].x > p[start].x || (p[i].x == p[start].x && p[i].y < p[start].y)) start = i;
    std::vector<b2Vec2> hull;
    for (std::size_t at = start;;) {
        if (hull.size() == b2_maxPolygonVertices) return false;
        hull.push_back(p[at]);
        std::size_t best = at == 0 ? 1 : 0;
        for (std::size_t j = 0; j < p.size(); ++j) {
            if (j == at || j == best) continue;
            const float c = cross(p[at], p[best], p[j]);
            if (c < 0.0f || (c == 0.0f && (p[j] - p[at]).LengthSquared() > (p[best] - p[at]).LengthSquared())) best = j;
        }
        at = best;
        if (at == start) break;
    }
    if (hull.size() < 3) return false;
    float area = 0.0f;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const b2Vec2 edge = hull[(i + 1) % hull.size()] - hull[i];
        if (edge.LengthSquared() <= b2_epsilon * b2_epsilon) return false;
        area += 0.5f * cross(hull[0], hull[i], hull[(i + 1) % hull.size()]);
    }
    return area > b2_epsilon;
}

// Box2D's polygon of these vertices, or nullptr where Box2D would refuse it in float.
std::unique_ptr<b2PolygonShape> polygon(const std::vector<Vec2>& v, double radius) {
    std::vector<b2Vec2> points;
    for (const Vec2& q : v) points.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()));
    if (v.size() > b2_maxPolygonVertices || !box2dAcceptsPolygon(points)) return nullptr;
    auto shape = std::make_unique<b2PolygonShape>();
    shape->Set(points.data(), static_cast<int32>(points.size()));
    shape->m_radius = static_cast<float>(radius);
    return shape;
}

// A polygon piece from its true outline (counter-clockwise, convex, at most 8 vertices); `path`
// and `what` name the shape in the error if Box2D cannot hold the outline in float.
Piece polygonPiece(const std::vector<Vec2>& outline, const std::string& path, const char* what) {
    Piece piece;
    piece.exact = polygon(outline, 0.0);
    if (!piece.exact)
        throw Error::invalid(path, std::to_string(outline.size()) + " vertices",
                             std::string("the outline of a ") + what +
                                 " in the XY plane is too thin for its size in Box2D's float coordinates (it rounds "
                                 "to fewer than 3 vertices on a hull, or no area)",
                             ErrorKind::Unsupported);
    // Box2D's rounding radius stays (its time of impact aims for a separation inside it); the core
    // shrinks so core + radius = outline + kSkin. Small polygons get a smaller radius: at most a
    // quarter of their inner radius, so the core keeps its shape.
    Vec2 centre = Vec2::Zero();
    for (const Vec2& p : outline) centre += p;
    centre /= static_cast<double>(outline.size());
    double inner = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < outline.size(); ++i) {
        const Vec2 e = (outline[(i + 1) % outline.size()] - outline[i]).normalized();
        inner = std::min(inner, Vec2(e.y(), -e.x()).dot(outline[i] - centre));
    }
    double shrink = std::min<double>(b2_polygonRadius - kSkin, 0.25 * inner);
    for (int attempt = 0; attempt < 8 && !piece.collision; ++attempt, shrink *= 0.5)
        if (const std::optional<std::vector<Vec2>> core = inset(outline, shrink)) piece.collision = polygon(*core, shrink + kSkin);
    if (!piece.collision) piece.collision = polygon(outline, kSkin);  // no core: the outline itself, with the skin
    return piece;
}

Piece circlePiece(const Vec2& centre, double radius) {
    auto collision = std::make_unique<b2CircleShape>();
    collision->m_p.Set(static_cast<float>(centre.x()), static_cast<float>(centre.y()));
    collision->m_radius = static_cast<float>(radius + kSkin);
    auto exact = std::make_unique<b2CircleShape>(*collision);
    exact->m_radius = static_cast<float>(radius);
    Piece piece;
    piece.collision = std::move(collision);
    piece.exact = std::move(exact);
    return piece;
}

// A polygon outline from 3D points (already in the body frame), projected onto XY.
std::vector<Vec2> projectedOutline(const std::vector<Vec3>& points, const std::string& path, const char* what) {
    std::vector<Vec2> flat;
    flat.reserve(points.size());
    for (const Vec3& p : points) flat.emplace_back(p.x(), p.y());
    std::vector<Vec2> outline = convexOutline(std::move(flat));
    if (outline.size() > b2_maxPolygonVertices)
        throw Error::invalid(path, std::to_string(outline.size()) + " vertices",
                             std::string("the outline of a ") + what + " in the XY plane must have at most " +
                                 std::to_string(b2_maxPolygonVertices) +
                                 " vertices on backend \"box2d\" (b2_maxPolygonVertices, capabilities.maxConvexVertices)",
                             ErrorKind::Unsupported);
    if (outline.size() < 3 || area(outline) < 4.0 * kWeld * kWeld)
        throw Error::invalid(path, std::to_string(outline.size()) + " distinct vertices",
                             std::string("the outline of a ") + what +
                                 " in the XY plane is too thin for a Box2D polygon (needs 3 vertices " +
                                 std::to_string(kWeld) + " m apart)",
                             ErrorKind::Unsupported);
    return outline;
}

// Where a plane's edges begin and end along its line, from the point nearest the origin:
// -R ... -2L, -L, L, 2L ... R for the middle half length L, doubling until R passes twice the
// largest coordinate a world admits (a body may stand anywhere within it).
std::vector<double> planeStops() {
    std::vector<double> ends{kPlaneMiddleHalfLength};
    while (ends.back() < 2.0 * kMaxCoordinate) ends.push_back(2.0 * ends.back());
    std::vector<double> stops;
    for (auto it = ends.rbegin(); it != ends.rend(); ++it) stops.push_back(-*it);
    stops.insert(stops.end(), ends.begin(), ends.end());
    return stops;
}

// The plane of unit normal n through `centre` (body frame), as HalfPlane keeps it.
HalfPlane halfPlane(const Vec2& n, const Vec2& centre) {
    return HalfPlane{b2Vec2(static_cast<float>(n.x()), static_cast<float>(n.y())), static_cast<float>(n.dot(centre))};
}

// Edge i of a plane, from stops[i] to stops[i + 1] along t. Its ghost vertices are its
// neighbours' far ends, so a body sliding across a joint meets one smooth surface; the run's
// outer ends look past themselves.
Piece planeEdge(const Vec2& sunk, const Vec2& centre, const Vec2& t, const Vec2& n, const std::vector<double>& stops,
                std::size_t i) {
    const auto point = [](const Vec2& p) { return b2Vec2(static_cast<float>(p.x()), static_cast<float>(p.y())); };
    const double before = i > 0 ? stops[i - 1] : stops[i] - 1.0;
    const double after = i + 2 < stops.size() ? stops[i + 2] : stops[i + 1] + 1.0;
    auto collision = std::make_unique<b2EdgeShape>();
    collision->SetOneSided(point(sunk + before * t), point(sunk + stops[i] * t), point(sunk + stops[i + 1] * t),
                           point(sunk + after * t));  // one-sided: a half-plane's surface
    auto exact = std::make_unique<b2EdgeShape>();
    exact->SetTwoSided(point(centre + stops[i] * t), point(centre + stops[i + 1] * t));
    exact->m_radius = 0.0f;
    Piece piece;
    piece.collision = std::move(collision);
    piece.exact = std::move(exact);
    piece.plane = halfPlane(n, centre);
    return piece;
}

// The polygon under edge i: its top is the plane between the edge's ends, and it reaches as deep
// as the edge is long (2 km under the middle one). Its coordinates stay as large as the edge's.
Piece planeBasement(const Vec2& centre, const Vec2& t, const Vec2& n, const std::vector<double>& stops, std::size_t i,
                    const std::string& path) {
    const double depth = stops[i + 1] - stops[i];
    const Vec2 a = centre + stops[i] * t, b = centre + stops[i + 1] * t;
    Piece piece = polygonPiece(convexOutline({a, b, b - depth * n, a - depth * n}), path, "plane");
    piece.plane = halfPlane(n, centre);
    piece.basement = true;
    return piece;
}

}  // namespace

std::vector<Piece> makePieces(const PeerShape& shape, const Transform& pose, const b2Vec2& originInBody,
                              const std::string& path) {
    const ShapeDef& s = shape.def;
    const Mat3 r = pose.orientation.toRotationMatrix();
    const auto at = [&](const Vec3& local) -> Vec3 { return pose.position + r * local; };
    std::vector<Piece> pieces;
    switch (s.type) {
        case ShapeType::Sphere:
            pieces.push_back(circlePiece(Vec2(pose.position.x(), pose.position.y()), s.radius));
            break;
        case ShapeType::Box: {
            std::vector<Vec3> corners;
            for (int i = 0; i < 8; ++i)
                corners.push_back(at(Vec3((i & 1 ? 1 : -1) * s.halfExtents.x(), (i & 2 ? 1 : -1) * s.halfExtents.y(),
                                          (i & 4 ? 1 : -1) * s.halfExtents.z())));
            pieces.push_back(polygonPiece(projectedOutline(corners, path, "box"), path, "box"));
            break;
        }
        case ShapeType::Convex: {
            std::vector<Vec3> points;
            for (const Vec3& v : shape.hull->vertices) points.push_back(at(v));
            pieces.push_back(polygonPiece(projectedOutline(points, path + ".points", "convex hull"), path + ".points", "convex hull"));
            break;
        }
        case ShapeType::Capsule: {
            // Box2D 2.4 has no capsule: the exact stadium is a rectangle between the two end
            // circles, all three on the same body (they never collide with each other).
            const Vec3 a3 = at(Vec3(0, s.halfHeight, 0)), b3 = at(Vec3(0, -s.halfHeight, 0));
            const Vec2 a(a3.x(), a3.y()), b(b3.x(), b3.y());
            pieces.push_back(circlePiece(a, s.radius));
            if ((a - b).norm() < kWeld) break;  // seen end on, or a sphere: one circle is the shape
            pieces.push_back(circlePiece(b, s.radius));
            const Vec2 side = Vec2(b.y() - a.y(), a.x() - b.x()).normalized() * s.radius;
            pieces.push_back(polygonPiece(convexOutline({a + side, a - side, b + side, b - side}), path, "capsule"));
            break;
        }
        case ShapeType::Plane: {
            const Vec3 n3 = r * s.normal.normalized();
            const double d = s.offset / s.normal.norm() + n3.dot(pose.position);
            const Vec2 n = Vec2(n3.x(), n3.y()).normalized();
            const Vec2 o(originInBody.x, originInBody.y);
            const Vec2 centre = o - (n.dot(o) - d) * n;
            const Vec2 t(-n.y(), n.x());  // Box2D's edge normal is the right-hand side of v1 -> v2
            // The edge keeps Box2D's radius and sits that much minus the skin below the plane, so
            // its surface is kSkin above the plane like every other piece's.
            const Vec2 sunk = centre - (b2_polygonRadius - kSkin) * n;
            const std::vector<double> stops = planeStops();
            for (std::size_t i = 0; i + 1 < stops.size(); ++i)
                pieces.push_back(planeEdge(sunk, centre, t, n, stops, i));
            // A trigger plane's overlaps are the world's to find (TriggerPlanes): no basement.
            if (!shape.isTrigger)
                for (std::size_t i = 0; i + 1 < stops.size(); ++i) pieces.push_back(planeBasement(centre, t, n, stops, i, path));
            break;
        }
        case ShapeType::Mesh:
        case ShapeType::Compound:
            throw Error::invalid(path + ".type", toString(s.type), "has no Box2D form (sphere, box, capsule, convex, plane)",
                                 ErrorKind::Unsupported);
    }
    return pieces;
}

float lowest(const b2Shape& exact, const b2Transform& xf, const b2Vec2& normal) {
    if (exact.GetType() == b2Shape::e_circle)
        return b2Dot(normal, b2Mul(xf, static_cast<const b2CircleShape&>(exact).m_p)) - exact.m_radius;
    const auto& p = static_cast<const b2PolygonShape&>(exact);
    float low = b2Dot(normal, b2Mul(xf, p.m_vertices[0]));
    for (int32 i = 1; i < p.m_count; ++i) low = std::min(low, b2Dot(normal, b2Mul(xf, p.m_vertices[i])));
    return low;
}

double innerRadius(const Piece& piece) {
    const b2Shape& s = *piece.exact;
    if (s.GetType() == b2Shape::e_circle) return s.m_radius;
    if (s.GetType() != b2Shape::e_polygon) return std::numeric_limits<double>::infinity();
    const auto& p = static_cast<const b2PolygonShape&>(s);
    double inner = std::numeric_limits<double>::infinity();
    for (int32 i = 0; i < p.m_count; ++i) inner = std::min<double>(inner, b2Dot(p.m_normals[i], p.m_vertices[i] - p.m_centroid));
    return inner;
}

}  // namespace anyphys::box2d

#include "batch.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace anyphys::testbed {
namespace {

constexpr double kPi = 3.141592653589793;

void put(std::vector<Vertex>& out, const Vec3& p, const Vec3& n, const DebugColor& c) {
    out.push_back(Vertex{{float(p.x()), float(p.y()), float(p.z())},
                         {float(n.x()), float(n.y()), float(n.z())},
                         {c.r, c.g, c.b}});
}

// One flat triangle (normal from its winding; shading is two-sided, so winding does not matter).
void flat(std::vector<Vertex>& out, const Vec3& a, const Vec3& b, const Vec3& c, const DebugColor& color) {
    Vec3 n = (b - a).cross(c - a);
    const double length = n.norm();
    n = length > 0 ? Vec3(n / length) : Vec3(Vec3::UnitY());
    put(out, a, n, color);
    put(out, b, n, color);
    put(out, c, n, color);
}

// A sphere or capsule (radius r, core half length hh along local Y) as latitude rings: the upper
// cap's rings raised by hh, the lower cap's lowered, the equator in both (the band between them is
// the capsule's cylinder; empty for a sphere).
void roundShape(std::vector<Vertex>& out, const Transform& pose, double r, double hh, const DebugColor& color) {
    constexpr int kRings = 12, kSegments = 20;
    struct RingPoint {
        Vec3 p, n;
    };
    std::vector<std::vector<RingPoint>> rings;
    for (int half = 0; half < 2; ++half)
        for (int ring = half ? kRings / 2 : 0; ring <= (half ? kRings : kRings / 2); ++ring) {
            const double theta = kPi * ring / kRings;  // 0 at the top
            std::vector<RingPoint> points;
            for (int seg = 0; seg <= kSegments; ++seg) {
                const double phi = 2.0 * kPi * seg / kSegments;
                const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
                const Vec3 local = r * n + Vec3(0, half ? -hh : hh, 0);
                points.push_back({pose.position + pose.orientation * local, pose.orientation * n});
            }
            rings.push_back(std::move(points));
        }
    for (std::size_t i = 0; i + 1 < rings.size(); ++i)
        for (int seg = 0; seg < kSegments; ++seg) {
            const RingPoint& a = rings[i][seg];
            const RingPoint& b = rings[i][seg + 1];
            const RingPoint& c = rings[i + 1][seg];
            const RingPoint& d = rings[i + 1][seg + 1];
            for (const RingPoint* q : {&a, &c, &d, &a, &d, &b}) put(out, q->p, q->n, color);
        }
}

void box(std::vector<Vertex>& out, const Transform& pose, const Vec3& h, const DebugColor& color) {
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign = -1; sign <= 1; sign += 2) {
            Vec3 n = Vec3::Zero();
            n[axis] = sign;
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            Vec3 corner[4];
            const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
            for (int k = 0; k < 4; ++k) {
                Vec3 p = Vec3::Zero();
                p[axis] = sign * h[axis];
                p[u] = su[k] * h[u];
                p[v] = sv[k] * h[v];
                corner[k] = pose.position + pose.orientation * p;
            }
            const Vec3 wn = pose.orientation * n;
            for (int k : {0, 1, 2, 0, 2, 3}) put(out, corner[k], wn, color);
        }
    }
}

DebugColor shade(const DebugColor& c, float f) { return DebugColor{c.r * f, c.g * f, c.b * f}; }

std::uint64_t hashPoints(const std::vector<Vec3>& points) {
    std::uint64_t h = 1469598103934665603ull;
    for (const Vec3& p : points)
        for (int i = 0; i < 3; ++i) {
            std::uint64_t bits;
            const double d = p[i];
            std::memcpy(&bits, &d, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
    return h ^ points.size();
}

}  // namespace

void Batch::clear(const Vec3& planeCentre, double planeReach) {
    planeReach_ = planeReach;
    triangles.clear();
    lines.clear();
    overlayLines.clear();
    bodies.clear();
    planeCentre_ = planeCentre;
}

void Batch::draw(const World& world, const DrawToggles& toggles) {
    DebugDrawOptions options;
    options.shapes = true;
    options.bounds = true;  // always: the bodies' bounds feed the projections and the framing
    options.contacts = toggles.contacts;
    options.joints = toggles.joints;
    options.jointLimits = false;
    if (!toggles.sleep) options.palette.sleepingBody = options.palette.awakeBody;
    showBounds_ = toggles.bounds;
    world.debugDraw(*this, options);
}

void Batch::line(std::vector<LineVertex>& out, const Vec3& a, const Vec3& b, const DebugColor& c) {
    out.push_back(LineVertex{{float(a.x()), float(a.y()), float(a.z())}, {c.r, c.g, c.b}});
    out.push_back(LineVertex{{float(b.x()), float(b.y()), float(b.z())}, {c.r, c.g, c.b}});
}

const std::vector<Vec3>& Batch::hullTriangles(const std::vector<Vec3>& points) {
    const std::uint64_t key = hashPoints(points);
    if (auto it = hulls_.find(key); it != hulls_.end()) return it->second;
    // Every triple of points with all others on one side is a face (exact for the small hulls of
    // games and scenes; coplanar faces come out as overlapping triangles of the same colour).
    std::vector<Vec3> tris;
    double scale = 0.0;
    for (const Vec3& p : points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
    const double eps = 1e-9 * std::max(scale, 1.0);
    const std::size_t n = points.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                const Vec3 normal = (points[j] - points[i]).cross(points[k] - points[i]);
                if (normal.norm() <= eps * eps) continue;
                int above = 0, below = 0;
                for (std::size_t m = 0; m < n && !(above && below); ++m) {
                    const double d = normal.dot(points[m] - points[i]);
                    if (d > eps) ++above;
                    if (d < -eps) ++below;
                }
                if (above && below) continue;
                tris.push_back(points[i]);
                tris.push_back(points[j]);
                tris.push_back(points[k]);
            }
    return hulls_.emplace(key, std::move(tris)).first->second;
}

void Batch::drawShape(BodyId body, const ShapeDef& shape, const Transform& pose, DebugColor color, bool awake) {
    BodyInfo& info = bodies[body.index];
    info.id = body;
    info.color = color;
    info.awake = awake;
    const auto world = [&pose](const Vec3& p) { return Vec3(pose.position + pose.orientation * p); };
    switch (shape.type) {
        case ShapeType::Sphere: roundShape(triangles, pose, shape.radius, 0.0, color); break;
        case ShapeType::Capsule: roundShape(triangles, pose, shape.radius, shape.halfHeight, color); break;
        case ShapeType::Box: {
            box(triangles, pose, shape.halfExtents, color);
            // Dark edges, so stacked boxes of one colour read as separate boxes.
            const Vec3& h = shape.halfExtents;
            for (int axis = 0; axis < 3; ++axis)
                for (int k = 0; k < 4; ++k) {
                    Vec3 a = -h;
                    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                    if (k & 1) a[u] = h[u];
                    if (k & 2) a[v] = h[v];
                    Vec3 b = a;
                    b[axis] = h[axis];
                    line(lines, world(a), world(b), shade(color, 0.45f));
                }
            break;
        }
        case ShapeType::Plane: {
            // A checkered square of 30 x 30 tiles about the point of the plane nearest the centre the
            // view asked for, snapped to the tiles so the checks do not swim. Tiles are 2 m, doubled
            // until the square reaches planeReach_.
            const Vec3 n = shape.normal.normalized();
            const Vec3 u = (std::abs(n.y()) < 0.9 ? n.cross(Vec3::UnitY()) : n.cross(Vec3::UnitX())).normalized();
            const Vec3 v = n.cross(u);
            constexpr int kHalf = 15;
            double tile = 2.0;
            while (tile * kHalf < planeReach_ && tile < 1e6) tile *= 2.0;
            const Vec3 onPlane = planeCentre_ - (n.dot(planeCentre_) - shape.offset) * n;
            const double cu = std::floor(u.dot(onPlane) / tile), cv = std::floor(v.dot(onPlane) / tile);
            const Vec3 base = shape.offset * n;
            for (int i = -kHalf; i < kHalf; ++i)
                for (int j = -kHalf; j < kHalf; ++j) {
                    const double a = (cu + i) * tile, b = (cv + j) * tile;
                    // Darker than the body colour, so the ground does not outshine what stands on it.
                    const DebugColor c = shade(color, (static_cast<long long>(cu + i + cv + j) & 1) ? 0.62f : 0.72f);
                    const Vec3 p0 = base + a * u + b * v, p1 = p0 + tile * u, p2 = p1 + tile * v, p3 = p0 + tile * v;
                    for (const Vec3& p : {p0, p1, p2, p0, p2, p3}) put(triangles, p, n, c);
                }
            break;
        }
        case ShapeType::Convex: {
            const std::vector<Vec3>& tris = hullTriangles(shape.points);
            for (std::size_t i = 0; i + 2 < tris.size(); i += 3) flat(triangles, world(tris[i]), world(tris[i + 1]), world(tris[i + 2]), color);
            break;
        }
        case ShapeType::Mesh:
            for (std::size_t i = 0; i + 2 < shape.indices.size(); i += 3)
                flat(triangles, world(shape.vertices[shape.indices[i]]), world(shape.vertices[shape.indices[i + 1]]),
                     world(shape.vertices[shape.indices[i + 2]]), color);
            break;
        case ShapeType::Compound: break;  // never handed over: children come one by one
    }
}

void Batch::drawContact(const DebugContact& contact) {
    const DebugColor red{1.0f, 0.2f, 0.2f}, yellow{1.0f, 0.9f, 0.2f};
    constexpr double s = 0.04;
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 d = Vec3::Zero();
        d[axis] = s;
        line(overlayLines, contact.point - d, contact.point + d, red);
    }
    line(overlayLines, contact.point, contact.normalEnd, yellow);
}

void Batch::drawJoint(JointId, JointType, const Transform& frameA, const Transform& frameB) {
    const DebugColor axes[3] = {{1.0f, 0.3f, 0.3f}, {0.3f, 1.0f, 0.3f}, {0.3f, 0.5f, 1.0f}};
    constexpr double length = 0.12;
    for (const Transform* f : {&frameA, &frameB})
        for (int axis = 0; axis < 3; ++axis)
            line(overlayLines, f->position, f->position + length * (f->orientation * Vec3::Unit(axis)), axes[axis]);
    line(overlayLines, frameA.position, frameB.position, DebugColor{1.0f, 1.0f, 1.0f});
}

void Batch::drawBounds(BodyId body, const Vec3& min, const Vec3& max) {
    BodyInfo& info = bodies[body.index];
    if (info.hasBounds) {
        info.lo = info.lo.cwiseMin(min);
        info.hi = info.hi.cwiseMax(max);
    } else {
        info.lo = min;
        info.hi = max;
        info.hasBounds = true;
    }
    if (!showBounds_) return;
    const DebugColor c{0.9f, 0.8f, 0.2f};
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int k = 0; k < 4; ++k) {
            Vec3 a = min;
            if (k & 1) a[u] = max[u];
            if (k & 2) a[v] = max[v];
            Vec3 b = a;
            b[axis] = max[axis];
            line(lines, a, b, c);
        }
    }
}

}  // namespace anyphys::testbed

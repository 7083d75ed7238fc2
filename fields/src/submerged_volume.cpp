#include "anyphys/fields/submerged_volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace anyphys {

SubmergedVolume& SubmergedVolume::operator+=(const SubmergedVolume& other) {
    const double total = volume + other.volume;
    if (total > 0.0) centroid = (centroid * volume + other.centroid * other.volume) / total;
    volume = total;
    return *this;
}

SubmergedVolume submergedSphere(double r, const Vec3& center, const FluidPlane& fluid) {
    // The cap below the plane has height h (0..2r); V = pi h^2 (3r - h) / 3, its centroid lies
    // 3 (2r - h)^2 / (4 (3r - h)) from the sphere's centre, into the fluid.
    const double h = std::clamp(r - fluid.height(center), 0.0, 2.0 * r);
    if (h <= 0.0) return {0.0, center};
    const double volume = std::numbers::pi * h * h * (3.0 * r - h) / 3.0;
    const double depth = 3.0 * (2.0 * r - h) * (2.0 * r - h) / (4.0 * (3.0 * r - h));
    return {volume, center - fluid.normal * depth};
}

namespace {

// The polyhedron's part below the plane, by the divergence theorem over its clipped faces: each
// face polygon is clipped to the fluid side (Sutherland-Hodgman against one plane) and fanned into
// tetrahedra with an apex on the surface plane. The cap that closes the cut lies in that plane, so
// its tetrahedra have no volume and it need not be built.
SubmergedVolume clippedPolyhedron(const std::vector<Vec3>& v, const std::vector<std::vector<int>>& faces,
                                  const FluidPlane& fluid) {
    double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : v) {
        const double s = fluid.height(p);
        lowest = std::min(lowest, s);
        highest = std::max(highest, s);
        mean += p;
    }
    mean /= static_cast<double>(v.size());
    if (lowest >= 0.0) return {0.0, mean};
    const Vec3 apex = mean - fluid.normal * fluid.height(mean);  // on the surface plane
    const bool whole = highest <= 0.0;
    double volume = 0.0;
    Vec3 moment = Vec3::Zero();
    std::array<Vec3, 64> buffer;
    std::vector<Vec3> large;
    for (const auto& face : faces) {
        const std::size_t n = face.size();
        Vec3* out = buffer.data();
        if (2 * n > buffer.size()) {
            large.resize(2 * n);
            out = large.data();
        }
        std::size_t count = 0;
        if (whole) {
            for (int i : face) out[count++] = v[i];
        } else {
            for (std::size_t i = 0; i < n; ++i) {
                const Vec3& a = v[face[i]];
                const Vec3& b = v[face[(i + 1) % n]];
                const double sa = fluid.height(a), sb = fluid.height(b);
                if (sa <= 0.0) out[count++] = a;
                if ((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0)) out[count++] = a + (b - a) * (sa / (sa - sb));
            }
        }
        for (std::size_t i = 1; i + 1 < count; ++i) {
            const Vec3 &p0 = out[0], &p1 = out[i], &p2 = out[i + 1];
            const double tet = (p0 - apex).dot((p1 - apex).cross(p2 - apex)) / 6.0;
            volume += tet;
            moment += tet * (apex + p0 + p1 + p2) / 4.0;
        }
    }
    if (volume <= 0.0) return {0.0, mean};
    return {volume, moment / volume};
}

// Gauss-Legendre nodes and weights on [-1, 1], 8 points (exact for polynomials of degree 15).
constexpr std::array<double, 4> kNodes = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> kWeights = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

// The disc of radius rho whose centre has height s above the surface, cut by the plane's trace:
// with the in-slice slope q = |n_perp| (height grows by q per metre across the slice), the wet
// part is the circular segment u < u0 = -s / q. Adds its area and first moments (along the axis
// coordinate t and across, in the direction of n_perp) into the integrand.
struct Slice {
    double area = 0.0;
    double across = 0.0;  // integral of u over the wet part (u along n_perp / |n_perp|)
};

Slice wetDisc(double rho, double s, double q) {
    if (rho <= 0.0) return {};
    if (q < 1e-12) return s < 0.0 ? Slice{std::numbers::pi * rho * rho, 0.0} : Slice{};
    const double u0 = -s / q;
    if (u0 <= -rho) return {};
    if (u0 >= rho) return {std::numbers::pi * rho * rho, 0.0};
    const double root = std::sqrt(std::max(0.0, rho * rho - u0 * u0));
    const double area = rho * rho * std::acos(-u0 / rho) + u0 * root;
    // The segment u < u0 has its centroid at u = -2 (rho^2 - u0^2)^(3/2) / (3 area).
    return {area, -2.0 * root * root * root / 3.0};
}

}  // namespace

SubmergedVolume submergedBox(const Vec3& half, const Transform& pose, const FluidPlane& fluid) {
    // Quick exits: the box's extent along the normal is sum |n . axis_k| h_k.
    const Mat3 R = pose.orientation.toRotationMatrix();
    const Vec3 nl = R.transpose() * fluid.normal;
    const double reach = std::abs(nl.x()) * half.x() + std::abs(nl.y()) * half.y() + std::abs(nl.z()) * half.z();
    const double s = fluid.height(pose.position);
    if (s >= reach) return {0.0, pose.position};
    if (s <= -reach) return {8.0 * half.x() * half.y() * half.z(), pose.position};
    ConvexFaces box = boxFaces(half);
    for (Vec3& p : box.vertices) p = pose.position + R * p;
    return clippedPolyhedron(box.vertices, box.faces, fluid);
}

SubmergedVolume submergedConvex(const ConvexFaces& hull, const Transform& pose, const FluidPlane& fluid) {
    std::vector<Vec3> placed(hull.vertices.size());
    const Mat3 R = pose.orientation.toRotationMatrix();
    for (std::size_t i = 0; i < placed.size(); ++i) placed[i] = pose.position + R * hull.vertices[i];
    return clippedPolyhedron(placed, hull.faces, fluid);
}

SubmergedVolume submergedCapsule(double r, double h, const Transform& pose, const FluidPlane& fluid) {
    const Vec3 axis = pose.orientation * Vec3::UnitY();
    const Vec3 c = pose.position;
    const double s0 = fluid.height(c);
    const double along = fluid.normal.dot(axis);  // height gained per metre along the axis
    const double reach = std::abs(along) * h + r;
    const double full = std::numbers::pi * r * r * (2.0 * h + 4.0 * r / 3.0);
    if (s0 >= reach) return {0.0, c};
    if (s0 <= -reach) return {full, c};
    const Vec3 across = fluid.normal - along * axis;  // n_perp: the slope inside a slice
    const double q = across.norm();
    const Vec3 m = q > 1e-12 ? Vec3(across / q) : Vec3::Zero();
    // Integrate the slices over t in [-h - r, h + r] (the axis coordinate) between the points
    // where the integrand has a kink or a step: the ends of the cylinder, where a disc starts or
    // stops being cut by the surface's trace (|u0(t)| = rho(t)), and where a slice's centre
    // crosses the surface. Between them it is smooth but for square-root behaviour at the ends,
    // which the map t = a + (b - a)(1 - cos(pi x)) / 2 smooths; then 2 x 8-point Gauss-Legendre.
    std::array<double, 12> breaks{};
    std::size_t count = 0;
    const auto addBreak = [&](double t) {
        if (t > -h - r && t < h + r) breaks[count++] = t;
    };
    breaks[count++] = -h - r;
    breaks[count++] = h + r;
    if (h > 0.0) {
        breaks[count++] = -h;
        breaks[count++] = h;
    }
    if (std::abs(along) > 1e-15) {
        addBreak(-s0 / along);
        if (q > 1e-12)
            for (double u : {-r, r}) {  // the cylinder: -(s0 + along t) / q = u
                const double t = (-u * q - s0) / along;
                if (t > -h && t < h) addBreak(t);
            }
    }
    if (q > 1e-12)
        for (double centre : {-h, h}) {
            // A cap's disc (radius^2 = r^2 - (t - centre)^2) touches the trace where
            // (s0 + along t)^2 = q^2 (r^2 - (t - centre)^2); with along^2 + q^2 = 1 that is
            // t^2 + 2 (along s0 - q^2 centre) t + s0^2 + q^2 (centre^2 - r^2) = 0.
            const double b = along * s0 - q * q * centre;
            const double disc = b * b - (s0 * s0 + q * q * (centre * centre - r * r));
            if (disc < 0.0) continue;
            for (double t : {-b - std::sqrt(disc), -b + std::sqrt(disc)})
                if (std::abs(t - centre) < r && (centre > 0 ? t > h : t < -h)) addBreak(t);
        }
    std::sort(breaks.begin(), breaks.begin() + count);
    double volume = 0.0, momentT = 0.0, momentU = 0.0;
    const double pi = std::numbers::pi;
    for (std::size_t i = 0; i + 1 < count; ++i) {
        const double a = breaks[i], b = breaks[i + 1];
        if (b - a <= 0.0) continue;
        for (int half = 0; half < 2; ++half)
            for (std::size_t k = 0; k < 2 * kNodes.size(); ++k) {
                const double node = (k % 2 == 0 ? 1.0 : -1.0) * kNodes[k / 2];
                const double x = 0.25 + 0.5 * half + 0.25 * node;  // in [0, 1]
                const double t = a + (b - a) * 0.5 * (1.0 - std::cos(pi * x));
                const double w = kWeights[k / 2] * 0.25 * (b - a) * 0.5 * pi * std::sin(pi * x);
                const double e = std::abs(t) - h;
                const double rho = e <= 0.0 ? r : std::sqrt(std::max(0.0, r * r - e * e));
                const Slice slice = wetDisc(rho, s0 + along * t, q);
                volume += w * slice.area;
                momentT += w * slice.area * t;
                momentU += w * slice.across;
            }
    }
    if (volume <= 0.0) return {0.0, c};
    return {volume, c + axis * (momentT / volume) + m * (momentU / volume)};
}

SubmergedVolume submergedShape(const FieldShape& shape, const Transform& bodyPose, const FluidPlane& fluid) {
    const Transform pose{bodyPose.position + bodyPose.orientation * shape.local.position,
                         bodyPose.orientation * shape.local.orientation};
    switch (shape.type) {
        case ShapeType::Sphere: return submergedSphere(shape.radius, pose.position, fluid);
        case ShapeType::Box: return submergedBox(shape.halfExtents, pose, fluid);
        case ShapeType::Capsule: return submergedCapsule(shape.radius, shape.halfHeight, pose, fluid);
        case ShapeType::Convex: return shape.hull ? submergedConvex(*shape.hull, pose, fluid) : SubmergedVolume{};
        default: return {};
    }
}

SubmergedVolume submergedShapes(const std::vector<FieldShape>& shapes, const Transform& bodyPose, const FluidPlane& fluid) {
    SubmergedVolume total;
    for (const FieldShape& s : shapes) total += submergedShape(s, bodyPose, fluid);
    return total;
}

}  // namespace anyphys

#pragma once
// The native backend's one GJK (Gilbert, Johnson, Keerthi 1988), built as Box2D's b2Distance:
// shapes enter as "cores" (point, segment, box, hull, triangle or any point set) whose radius is
// added by the caller afterwards, so spheres and capsules stay exact; every support point is a
// numbered core vertex, which gives a sure termination test (a vertex met again); and nothing is
// allocated.
#include <array>
#include <limits>
#include <span>

#include "collision/shape.hpp"

namespace anyphys::native {

/// A convex shape as GJK sees it: a support mapping over numbered vertices plus a radius.
class ConvexCore {
public:
    /// Sphere (its centre), capsule (its segment), box or convex hull at world pose xf; the
    /// radius is the sphere's or capsule's. A hull's vertices are referenced, not copied.
    static ConvexCore of(const Shape& s, const Transform& xf);
    /// A triangle given in world space (copied).
    static ConvexCore triangle(const std::array<Vec3, 3>& world);
    /// The convex hull of world-space points (non-empty; referenced, not copied: they must
    /// outlive the core).
    static ConvexCore points(std::span<const Vec3> world);
    /// The convex hull of points given in a frame placed at (rotation, position) in the world
    /// (non-empty; referenced, not copied).
    static ConvexCore posedPoints(std::span<const Vec3> local, const Mat3& rotation, const Vec3& position);

    /// Index of a vertex furthest along `dir` (world); the first such one on ties.
    int support(const Vec3& dir) const {
        const Vec3 d = posed_ ? Vec3(rotation_.transpose() * dir) : dir;
        // A box's corner i has coordinate k positive when bit k of i is set: O(1).
        if (isBox_) return (d.x() >= 0.0 ? 1 : 0) | (d.y() >= 0.0 ? 2 : 0) | (d.z() >= 0.0 ? 4 : 0);
        int best = 0;
        double bestDot = -std::numeric_limits<double>::infinity();
        for (int i = 0; i < count_; ++i) {
            const double dot = localVertex(i).dot(d);
            if (dot > bestDot) {
                bestDot = dot;
                best = i;
            }
        }
        return best;
    }

    /// Vertex i in world space.
    Vec3 vertex(int i) const { return posed_ ? Vec3(position_ + rotation_ * localVertex(i)) : localVertex(i); }
    double radius() const { return radius_; }

private:
    const Vec3& localVertex(int i) const {
        const auto k = static_cast<std::size_t>(i);
        return shared_.empty() ? local_[k] : shared_[k];
    }

    Mat3 rotation_ = Mat3::Identity();  // shape frame -> world, when posed_
    Vec3 position_ = Vec3::Zero();
    std::array<Vec3, 8> local_{};       // sphere, capsule, box, triangle
    std::span<const Vec3> shared_;      // hull vertices or caller's points, not copied
    int count_ = 0;
    double radius_ = 0.0;
    bool isBox_ = false;
    bool posed_ = false;  // vertices in a shape frame (else already in world space)
};

/// Indices of one core's vertices spanning the closest feature (1: a vertex, 2: an edge, 3: a
/// face; 4 when the cores overlap), distinct and increasing.
struct CoreFeature {
    std::array<int, 4> index{};
    int count = 0;

    int size() const { return count; }
    int operator[](int i) const { return index[static_cast<std::size_t>(i)]; }
    const int* begin() const { return index.data(); }
    const int* end() const { return index.data() + count; }
};

struct GjkResult {
    Vec3 pointA = Vec3::Zero();  // closest points of the cores (radii not included)
    Vec3 pointB = Vec3::Zero();
    double distance = 0.0;       // between the cores; 0 when they overlap
    bool overlap = false;        // cores overlap or lie within the overlap tolerance
    CoreFeature featureA;        // vertices of a spanning its closest feature
    CoreFeature featureB;        // same for b
};

/// Below this distance (m) cores count as touching: overlap.
inline constexpr double kGjkTouching = 1e-12;

/// Closest points of the cores of a and b (radii not included). The iteration starts from the
/// support pair along `initialDir` (from a toward b; a good guess saves iterations, zero means
/// +x). Cores closer than `overlapTolerance` count as overlapping; then the points are only an
/// interior witness and the caller needs another method for a normal.
GjkResult gjk(const ConvexCore& a, const ConvexCore& b, const Vec3& initialDir, double overlapTolerance = kGjkTouching);

/// The same, started from vertex 0 of each core (b2Distance's start without a cache).
GjkResult gjkFromFirstVertices(const ConvexCore& a, const ConvexCore& b, double overlapTolerance = kGjkTouching);

}  // namespace anyphys::native

#pragma once
// The orbit camera every view shares: it turns about a target point (yaw about +Y, pitch above the
// horizon), so the same body appears at the same pixel of each view when the engines agree.
#include <Eigen/Core>
#include <optional>

#include "anyphys/math.hpp"

namespace anyphys::testbed {

struct Ray {
    Vec3 origin = Vec3::Zero();
    Vec3 direction = Vec3::UnitZ();  ///< unit
};

/// A point projected into a view: pixels from the view's top-left corner, and its depth.
struct Projected {
    double x = 0.0;
    double y = 0.0;
    double depth = 0.0;  ///< normalised device depth in [-1, 1]
};

class Camera {
public:
    Vec3 target = Vec3(0, 1, 0);  ///< m, the point turned about and looked at
    double yaw = 0.6;             ///< rad about +Y; 0 looks along -Z (the side view of planar scenes)
    double pitch = 0.3;           ///< rad above the horizon
    double distance = 10.0;       ///< m from the target
    double fovY = 0.7853981633974483;  ///< rad, vertical field of view (45 degrees)

    Vec3 eye() const;
    Vec3 forward() const;  ///< unit, from the eye to the target
    Vec3 right() const;    ///< unit
    Vec3 up() const;       ///< unit

    /// Looks at the box [lo, hi] so it fills most of the view; planar scenes from the side.
    void frame(const Vec3& lo, const Vec3& hi, bool planar);
    /// Mouse motions in pixels: orbit (drag), pan (in a view `viewHeight` pixels high), zoom (wheel).
    void orbit(double dx, double dy);
    void pan(double dx, double dy, double viewHeight);
    void zoom(double wheel);

    Eigen::Matrix4f viewMatrix() const;
    Eigen::Matrix4f projectionMatrix(double aspect) const;
    /// The ray through pixel (x, y) of a w x h view (pixels from the top-left).
    Ray ray(double x, double y, double w, double h) const;
    /// Where `p` appears in a w x h view; nothing when it is behind the eye.
    std::optional<Projected> project(const Vec3& p, double w, double h) const;

private:
    double nearPlane() const;
    double farPlane() const;
};

}  // namespace anyphys::testbed

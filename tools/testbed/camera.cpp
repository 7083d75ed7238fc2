#include "camera.hpp"

#include <algorithm>
#include <cmath>

namespace anyphys::testbed {

Vec3 Camera::eye() const {
    const Vec3 offset(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
    return target + distance * offset;
}

Vec3 Camera::forward() const { return (target - eye()).normalized(); }

Vec3 Camera::right() const {
    // Pitch stays inside (-pi/2, pi/2), so forward is never parallel to +Y.
    return forward().cross(Vec3::UnitY()).normalized();
}

Vec3 Camera::up() const { return right().cross(forward()); }

void Camera::frame(const Vec3& lo, const Vec3& hi, bool planar) {
    target = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * (hi - lo).norm(), 1.0);
    distance = 1.3 * radius / std::sin(0.5 * fovY);
    yaw = planar ? 0.0 : 0.6;
    pitch = planar ? 0.0 : 0.3;
}

void Camera::orbit(double dx, double dy) {
    yaw -= 0.005 * dx;
    pitch = std::clamp(pitch + 0.005 * dy, -1.5, 1.5);
}

void Camera::pan(double dx, double dy, double viewHeight) {
    const double metresPerPixel = 2.0 * distance * std::tan(0.5 * fovY) / std::max(viewHeight, 1.0);
    target += metresPerPixel * (-dx * right() + dy * up());
}

void Camera::zoom(double wheel) { distance = std::clamp(distance * std::pow(0.9, wheel), 0.1, 1e5); }

double Camera::nearPlane() const { return std::max(0.01, distance * 0.01); }
double Camera::farPlane() const { return distance * 100.0 + 100.0; }

Eigen::Matrix4f Camera::viewMatrix() const {
    const Vec3 f = forward(), r = right(), u = up(), e = eye();
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.block<1, 3>(0, 0) = r.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -r.dot(e);
    m(1, 3) = -u.dot(e);
    m(2, 3) = f.dot(e);
    return m.cast<float>();
}

Eigen::Matrix4f Camera::projectionMatrix(double aspect) const {
    const double n = nearPlane(), f = farPlane();
    const double t = 1.0 / std::tan(0.5 * fovY);
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    m(0, 0) = t / aspect;
    m(1, 1) = t;
    m(2, 2) = (f + n) / (n - f);
    m(2, 3) = 2.0 * f * n / (n - f);
    m(3, 2) = -1.0;
    return m.cast<float>();
}

Ray Camera::ray(double x, double y, double w, double h) const {
    const double t = std::tan(0.5 * fovY);
    const double ndcX = 2.0 * x / w - 1.0, ndcY = 1.0 - 2.0 * y / h;
    Ray r;
    r.origin = eye();
    r.direction = (forward() + ndcX * t * (w / h) * right() + ndcY * t * up()).normalized();
    return r;
}

std::optional<Projected> Camera::project(const Vec3& p, double w, double h) const {
    const Eigen::Matrix4d mvp = (projectionMatrix(w / h) * viewMatrix()).cast<double>();
    const Eigen::Vector4d clip = mvp * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (clip.w() <= 1e-9) return std::nullopt;
    const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
    return Projected{(ndc.x() + 1.0) * 0.5 * w, (1.0 - ndc.y()) * 0.5 * h, ndc.z()};
}

}  // namespace anyphys::testbed

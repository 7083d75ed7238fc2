#include "picking.hpp"

#include <cmath>

namespace anyphys::testbed {

bool Picker::begin(Views& views, std::size_t viewIndex, const Ray& ray, const Camera& camera) {
    body_.reset();
    if (viewIndex >= views.views().size()) return false;
    View& v = views.views()[viewIndex];
    if (!v.world) return false;
    const std::optional<RayHit> hit = v.world->raycast(ray.origin, ray.direction, 1e4);
    if (!hit || hit->body.type() != BodyType::Dynamic) return false;
    for (std::size_t i = 0; i < v.bodies.size(); ++i)
        if (v.bodies[i] == hit->body) {
            body_ = i;
            local_ = hit->body.orientation().conjugate() * (hit->point - hit->body.position());
            target_ = hit->point;
            planeNormal_ = camera.forward();
            return true;
        }
    return false;
}

void Picker::move(const Ray& ray) {
    if (!body_) return;
    const double denom = planeNormal_.dot(ray.direction);
    if (std::abs(denom) < 1e-9) return;
    const double t = planeNormal_.dot(target_ - ray.origin) / denom;
    if (t > 0) target_ = ray.origin + t * ray.direction;
}

void Picker::pull(View& view) const {
    if (!body_ || *body_ >= view.bodies.size()) return;
    Body& b = view.bodies[*body_];
    if (b.type() != BodyType::Dynamic) return;
    const double m = b.massProperties().mass;
    const double omega = 2.0 * 3.141592653589793 * frequency;
    const Vec3 anchor = b.position() + b.orientation() * local_;
    const Vec3 velocity = b.linearVelocity() + b.angularVelocity().cross(anchor - b.centerOfMass());
    Vec3 target = target_;
    if (view.world->settings().planar) target.z() = 0.0;
    Vec3 force = m * (omega * omega * (target - anchor) - 2.0 * dampingRatio * omega * velocity);
    // At most 50 g, so a grab far off the screen does not throw the body through the floor.
    const double limit = 50.0 * 9.81 * m;
    if (force.norm() > limit) force *= limit / force.norm();
    b.applyForceAtPoint(force, anchor);
}

}  // namespace anyphys::testbed

#pragma once
// Dragging a body with the mouse. The pick is a ray cast (World::raycast) in the view under the
// cursor; the same body (by scene order) is then pulled in every view, by a spring-damper force
// at the grabbed point toward the cursor (Body::applyForceAtPoint before each step), so the views
// stay comparable. A force works on every backend; a joint to a moving anchor is not in the API.
#include <cstddef>
#include <optional>

#include "camera.hpp"
#include "views.hpp"

namespace anyphys::testbed {

class Picker {
public:
    /// Casts `ray` in view `viewIndex`; grabs the dynamic body hit. Returns whether one was.
    bool begin(Views& views, std::size_t viewIndex, const Ray& ray, const Camera& camera);
    /// Moves the cursor's target along the grab plane (through the grabbed point, facing the camera).
    void move(const Ray& ray);
    void end() { body_.reset(); }
    bool active() const { return body_.has_value(); }
    const Vec3& target() const { return target_; }

    /// Adds the pull to the grabbed body of `view` (call just before it steps).
    void pull(View& view) const;

    double frequency = 4.0;     ///< Hz, of the spring with the body's mass
    double dampingRatio = 0.7;

private:
    std::optional<std::size_t> body_;  ///< index in View::bodies
    Vec3 local_ = Vec3::Zero();        ///< grabbed point in the body frame (from the body origin)
    Vec3 target_ = Vec3::Zero();
    Vec3 planeNormal_ = Vec3::UnitZ();
};

}  // namespace anyphys::testbed

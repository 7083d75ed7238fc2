#pragma once
// ODE's colliders find only shapes that overlap. The layer keeps a touching pair until its
// shapes are twice linearSlop apart, so that a resting contact whose gap wanders about zero (an
// unloaded side contact in a row of boxes) does not blink in and out. NearProbe answers the layer's
// question about such a pair (WorldPeer::reportNearPair): it collides the two shapes with one of
// them grown by the reach, and reports the contacts against the true surfaces.
#include <ode/ode.h>

#include "anyphys/defs.hpp"
#include "ode_shapes.hpp"

namespace anyphys::ode {

class NearProbe {
public:
    NearProbe() = default;
    ~NearProbe();
    NearProbe(const NearProbe&) = delete;
    NearProbe& operator=(const NearProbe&) = delete;

    /// Contacts of `first` and `second` as they are placed now, one of them grown by `reach` all
    /// round: depths less `reach` (negative: apart), normals into `first` (ODE's convention for
    /// the first geom). 0 when neither shape can grow (hulls and meshes: a hull against a mesh)
    /// or the grown shapes do not meet.
    int collide(const OdeShape& first, const OdeShape& second, double reach, dContactGeom* out, int most);
    /// Whether `moving`, grown by `reach`, meets `other` once moved by `move` and turned by `turn`
    /// about `pivot` (its body's centre) from where it is. A shape that cannot grow never meets.
    bool meetsAfter(const OdeShape& moving, const Vec3& pivot, const Vec3& move, const Quat& turn, const OdeShape& other,
                    double reach);
    /// Whether grown() can grow shapes of this type.
    static bool growable(ShapeType type) {
        return type == ShapeType::Box || type == ShapeType::Sphere || type == ShapeType::Capsule || type == ShapeType::Plane;
    }

private:
    /// A scratch geom of the shape's kind, `reach` larger, at the shape's pose; null for shapes
    /// that do not grow simply (a hull's offset surface is not a hull; a mesh has no inside).
    /// Valid until the next call.
    dGeomID grown(const OdeShape& shape, double reach);
    dGeomID box_ = nullptr, sphere_ = nullptr, capsule_ = nullptr, plane_ = nullptr;
};

}  // namespace anyphys::ode

#pragma once
// One world's picture for one frame: a DebugDraw that turns what World::debugDraw hands it into
// shaded triangles and lines (world coordinates, ready for one GL buffer each), and remembers
// each body's colour and bounds (for the projections sidecar and the camera's framing).
#include <cstdint>
#include <map>
#include <unordered_map>
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::testbed {

struct Vertex {
    float position[3];
    float normal[3];
    float color[3];
};

struct LineVertex {
    float position[3];
    float color[3];
};

/// What the batch learnt about one body while drawing.
struct BodyInfo {
    BodyId id;
    DebugColor color;
    bool awake = false;
    bool hasBounds = false;  ///< false for bodies whose only shape is a plane
    Vec3 lo = Vec3::Zero();  ///< m, world AABB of its primitives
    Vec3 hi = Vec3::Zero();
};

/// Which kinds the view shows (the world is always asked for shapes and bounds).
struct DrawToggles {
    bool contacts = false;
    bool joints = true;
    bool bounds = false;
    bool sleep = true;  ///< sleeping bodies in their own colour; off: in the awake colour
};

class Batch : public DebugDraw {
public:
    /// Empties the batch; planes are drawn as a checkered square about `planeCentre`, reaching at
    /// least `planeReach` m from it (the ground must look endless from the camera).
    void clear(const Vec3& planeCentre, double planeReach = 30.0);
    /// Draws `world` into the batch.
    void draw(const World& world, const DrawToggles& toggles);

    std::vector<Vertex> triangles;
    std::vector<LineVertex> lines;         ///< depth-tested (bounds)
    std::vector<LineVertex> overlayLines;  ///< drawn over the shapes (contacts, joints)
    std::map<std::uint32_t, BodyInfo> bodies;  ///< by body slot index

    void drawShape(BodyId body, const ShapeDef& shape, const Transform& pose, DebugColor color, bool awake) override;
    void drawContact(const DebugContact& contact) override;
    void drawJoint(JointId joint, JointType type, const Transform& frameA, const Transform& frameB) override;
    void drawBounds(BodyId body, const Vec3& min, const Vec3& max) override;

private:
    void line(std::vector<LineVertex>& out, const Vec3& a, const Vec3& b, const DebugColor& color);
    const std::vector<Vec3>& hullTriangles(const std::vector<Vec3>& points);

    Vec3 planeCentre_ = Vec3::Zero();
    double planeReach_ = 30.0;
    bool showBounds_ = false;
    std::unordered_map<std::uint64_t, std::vector<Vec3>> hulls_;  ///< convex shapes' triangles by point hash
};

}  // namespace anyphys::testbed

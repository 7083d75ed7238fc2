#pragma once
// A DebugDraw that keeps every call, so tests can count and check what World::debugDraw drew.
#include <vector>

#include "anyphys/anyphys.hpp"

namespace anyphys::test {

class RecordingDrawer : public DebugDraw {
public:
    struct Shape {
        BodyId body;
        ShapeDef shape;
        Transform pose;
        DebugColor color;
        bool awake = false;
    };
    struct Joint {
        JointId joint;
        JointType type;
        Transform frameA;
        Transform frameB;
    };
    struct Limit {
        JointId joint;
        DebugJointLimit limit;
    };
    struct Bounds {
        BodyId body;
        Vec3 min;
        Vec3 max;
    };

    void drawShape(BodyId body, const ShapeDef& shape, const Transform& pose, DebugColor color, bool awake) override {
        shapes.push_back({body, shape, pose, color, awake});
    }
    void drawContact(const DebugContact& contact) override { contacts.push_back(contact); }
    void drawJoint(JointId joint, JointType type, const Transform& frameA, const Transform& frameB) override {
        joints.push_back({joint, type, frameA, frameB});
    }
    void drawJointLimit(JointId joint, const DebugJointLimit& limit) override { limits.push_back({joint, limit}); }
    void drawBounds(BodyId body, const Vec3& min, const Vec3& max) override { bounds.push_back({body, min, max}); }

    std::size_t total() const { return shapes.size() + contacts.size() + joints.size() + limits.size() + bounds.size(); }

    std::vector<Shape> shapes;
    std::vector<DebugContact> contacts;
    std::vector<Joint> joints;
    std::vector<Limit> limits;
    std::vector<Bounds> bounds;
};

}  // namespace anyphys::test

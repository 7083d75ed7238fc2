// Particles against a compound whose child is a sensor: the sensor child counts for the body's
// volume and mass (fields), but particles pass through it; the solid child still pushes.
#include <gtest/gtest.h>

#include "anyphys/fields/field_forces.hpp"
#include "anyphys/fields/particles.hpp"

namespace anyphys {
namespace {

FieldShape sphereAt(const Vec3& at, double radius, bool sensor) {
    FieldShape s;
    s.type = ShapeType::Sphere;
    s.radius = radius;
    s.local.position = at;
    s.sensor = sensor;
    return s;
}

TEST(ParticleSensorShapes, ParticlesPassSensorChildrenAndMeetSolidOnes) {
    FieldBody body;
    body.shapes = {sphereAt(Vec3(-2, 0, 0), 1.0, false), sphereAt(Vec3(2, 0, 0), 1.0, true)};
    ParticleCollider c;
    c.body = &body;
    colliderBounds(c);
    // Bounds cover the solid child only: the sensor child has nothing to push with.
    EXPECT_DOUBLE_EQ(c.boundsMax.x(), -1.0);
    // A particle of radius 0.1 at rest (it starts the substep where it is), 0.1 inside the solid
    // child's surface: pushed out by 0.2 m.
    const Vec3 push = colliderPush(c, Vec3(-1.1, 0, 0), Vec3(-1.1, 0, 0), 0.1);
    EXPECT_NEAR(push.x(), 0.2, 1e-12);
    EXPECT_TRUE(colliderPush(c, Vec3(2, 0, 0), Vec3(2, 0, 0), 0.1).isZero(0)) << "inside the sensor child: no push";
}

}  // namespace
}  // namespace anyphys

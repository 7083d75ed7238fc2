// The built-in car on every backend that has wheel joints (the planar car on planar backends):
// the suspension's static sag, straight-line acceleration against the motor torque, the turning
// circle against the steering geometry, and a slope the planar car climbs or cannot.
#include <cmath>
#include <numbers>

#include "anyphys/containers/assembly.hpp"
#include "contact_helpers.hpp"
#include "contract_fixture.hpp"

namespace anyphys::test {
namespace {

constexpr double kSpring = 58860.0;  // N/m per wheel (docs/assemblies.md)
constexpr double kWheelRadius = 0.35, kWheelMass = 20.0, kWheelbase = 2.8;

struct Car {
    Scene scene;
    std::unique_ptr<World> world;
    SceneObjects objects;
    Body chassis;
    std::vector<Joint> suspensions, driven, steered;
    double chassisMass = 0.0, totalMass = 0.0;
};

// The car on flat ground (or on a plane tilted by `slope` rad about Z, the car facing uphill).
std::unique_ptr<Car> makeCar(const WorldSettings& settings, double slope = 0.0) {
    auto car = std::make_unique<Car>();
    const bool planar = settings.planar;
    car->scene.settings = settings;
    const Quat tilt(Eigen::AngleAxisd(slope, Vec3::UnitZ()));
    BodyDef ground = groundDef();
    ground.shape = ShapeDef::plane(tilt * Vec3::UnitY(), 0.0);
    car->scene.bodies.push_back(ground);
    appendInstance(car->scene, builtinAssembly(planar ? "vehicle_planar" : "vehicle"), Transform{Vec3::Zero(), tilt}, "");
    for (BodyDef& b : car->scene.bodies) b.allowSleep = false;
    car->world = std::make_unique<World>(car->scene.settings, car->scene.materials);
    car->objects = createSceneObjects(*car->world, car->scene);
    car->chassis = car->objects.body("chassis");
    for (const Joint& j : car->objects.joints) {
        car->suspensions.push_back(j);
        if (j.def().motor) car->driven.push_back(j);
        if (j.def().steering) car->steered.push_back(j);
    }
    for (const Body& b : car->objects.bodies)
        if (b.type() == BodyType::Dynamic) car->totalMass += b.massProperties().mass;
    car->chassisMass = car->chassis.massProperties().mass;
    return car;
}

class VehicleTest : public ContractTest {
protected:
    std::string requirement() const {
        if (!caps().jointTypes.contains("wheel")) return "joint type wheel";
        if (!caps().parameters.contains("joint.wheel.motor")) return "wheel motors";
        return lacking(caps(), {ShapeType::Sphere, ShapeType::Box, ShapeType::Plane}, Effect::Contacts | Effect::Friction);
    }
    std::string id(const std::string& name) const { return (planarTest() ? "planar.vehicle." : "vehicle.") + name; }

    // Settled on its springs, each wheel's suspension is compressed by its share of the chassis
    // weight over k: m g / (n k) = 5 cm, the wheels carrying their own weight to the ground.
    // 2 mm (4 %): a soft-constraint spring settles within it in 3 s at damping ratio 0.5.
    void staticSag() {
        const std::string missing = requirement();
        ANYPHYS_REQUIRE(missing.empty(), missing);
        auto car = makeCar(settings());
        while (car->world->time() < 3.0) car->world->step();
        const double expected = car->chassisMass * kG / (static_cast<double>(car->suspensions.size()) * kSpring);
        double worst = 0.0;
        for (const Joint& s : car->suspensions) worst = std::max(worst, std::abs(std::abs(s.position()) - expected));
        report(backend() + " suspension sag (exact " + std::to_string(expected) + " m): worst error", worst, "m");
        expectCriterion(id("sag"), worst <= 0.002,
                        "sag off by " + std::to_string(worst) + " m from m g / (n k) = " + std::to_string(expected) + " m",
                        worst);
    }

    // Full torque tau on the N driven wheels from rest: without slip the car accelerates at
    // a = N tau / (r (m + sum I_w / r^2)) (wheels are spheres, I_w = 2/5 m_w r^2). Measured from
    // 0.5 s (the springs settled) to 2.5 s; 5 %: rolling on soft contacts loses a little, and
    // the chassis pitches back at first. Then the motor's speed limit caps the speed at r w_max.
    void acceleration() {
        const std::string missing = requirement();
        ANYPHYS_REQUIRE(missing.empty(), missing);
        auto car = makeCar(settings());
        constexpr double kTorque = 400.0, kSpeedLimit = 20.0;  // N m, rad/s (7 m/s)
        while (car->world->time() < 0.5) car->world->step();
        for (Joint& j : car->driven) j.setMotor(JointMotor{kSpeedLimit, kTorque});
        const double v0 = car->chassis.linearVelocity().x(), t0 = car->world->time();
        while (car->world->time() < 2.5) car->world->step();
        const double a = (car->chassis.linearVelocity().x() - v0) / (car->world->time() - t0);
        const double inertia = 0.4 * kWheelMass * kWheelRadius * kWheelRadius;
        const double n = static_cast<double>(car->driven.size()), wheels = static_cast<double>(car->suspensions.size());
        const double expected = n * kTorque / (kWheelRadius * (car->totalMass + wheels * inertia / (kWheelRadius * kWheelRadius)));
        report(backend() + " acceleration (exact " + std::to_string(expected) + ")", a, "m/s^2");
        expectCriterion(id("acceleration"), std::abs(a - expected) <= 0.05 * expected,
                        "a = " + std::to_string(a) + " m/s^2, exact " + std::to_string(expected), std::abs(a - expected) / expected);
        while (car->world->time() < 8.0) car->world->step();
        const double top = car->chassis.linearVelocity().x();
        report(backend() + " speed at the motor's limit (exact " + std::to_string(kSpeedLimit * kWheelRadius) + ")", top, "m/s");
        // 3 %: the limit is a velocity constraint on the wheel, the car follows it without slip.
        expectCriterion(id("top_speed"), std::abs(top - kSpeedLimit * kWheelRadius) <= 0.03 * kSpeedLimit * kWheelRadius,
                        "top speed " + std::to_string(top) + " m/s, exact " + std::to_string(kSpeedLimit * kWheelRadius),
                        std::abs(top / (kSpeedLimit * kWheelRadius) - 1.0));
    }

    // At 1.75 m/s with the front wheels at delta = 0.3 rad, the chassis centre circles at
    // R = sqrt((L / tan delta)^2 + (L / 2)^2) (bicycle geometry about the rear axle's middle).
    // Both front wheels get the same angle (no Ackermann linkage): the inner wheel alone would
    // turn 9 % tighter and the outer 9 % wider, so 10 %.
    void turningCircle() {
        const std::string missing = requirement();
        ANYPHYS_REQUIRE(missing.empty(), missing);
        ANYPHYS_REQUIRE(!planarTest(), "steering in a planar world");
        ANYPHYS_REQUIRE(caps().parameters.contains("joint.wheel.steering"), "wheel steering");
        auto car = makeCar(settings());
        constexpr double kSteer = 0.3;
        for (Joint& j : car->driven) j.setMotor(JointMotor{5.0, 400.0});
        for (Joint& j : car->steered) j.setSteeringAngle(kSteer);
        while (car->world->time() < 6.0) car->world->step();
        double speed = 0.0, yaw = 0.0;
        int samples = 0;
        while (car->world->time() < 8.0) {
            car->world->step();
            const Vec3 v = car->chassis.linearVelocity();
            speed += std::hypot(v.x(), v.z());
            yaw += car->chassis.angularVelocity().y();
            ++samples;
        }
        const double radius = speed / std::abs(yaw);  // (mean speed) / (mean yaw rate)
        const double rear = kWheelbase / std::tan(kSteer);
        const double expected = std::hypot(rear, 0.5 * kWheelbase);
        report(backend() + " turning radius (bicycle " + std::to_string(expected) + " m)", radius, "m");
        EXPECT_GT(yaw, 0.0) << "a positive steering angle turns left (about +Y)";
        expectCriterion(id("turning_radius"), std::abs(radius - expected) <= 0.1 * expected,
                        "radius " + std::to_string(radius) + " m, bicycle geometry " + std::to_string(expected) + " m",
                        std::abs(radius / expected - 1.0));
        (void)samples;
    }

    // The car facing uphill with full torque: on 5 deg the drive force N tau / r = 1 143 N per
    // driven wheel beats the weight along the slope (546 N planar, 1 092 N 3D) and it climbs;
    // on 20 deg it needs 2 147 (planar) / 4 295 N (3D) and cannot: it rolls back.
    void slope(double degrees, bool climbs) {
        const std::string missing = requirement();
        ANYPHYS_REQUIRE(missing.empty(), missing);
        auto car = makeCar(settings(), degrees * std::numbers::pi / 180.0);
        const Vec3 uphill = Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Vec3::UnitZ())) * Vec3::UnitX();
        while (car->world->time() < 0.3) car->world->step();  // the brakes hold it while it settles
        const Vec3 start = car->chassis.position();
        for (Joint& j : car->driven) j.setMotor(JointMotor{20.0, 400.0});
        while (car->world->time() < 4.3) car->world->step();
        const double moved = (car->chassis.position() - start).dot(uphill);
        report(backend() + " on " + std::to_string(degrees) + " deg: moved uphill", moved, "m");
        // Climbing: at least 2 m in 4 s (it reaches the 7 m/s limit on flat ground); not: it
        // went nowhere up (the brakes are off: it rolls back).
        expectCriterion(id(climbs ? "climbs" : "stays_below"), climbs ? moved > 2.0 : moved < 0.0,
                        "moved " + std::to_string(moved) + " m uphill in 4 s on " + std::to_string(degrees) + " deg");
    }
};

TEST_P(VehicleTest, StaticSagIsWeightOverStiffness) { staticSag(); }
TEST_P(VehicleTest, AcceleratesAsMotorTorqueSays) { acceleration(); }
TEST_P(VehicleTest, TurnsOnTheSteeringGeometrysCircle) { turningCircle(); }
ANYPHYS_CONTRACT_SUITE(VehicleTest);

class PlanarVehicleTest : public VehicleTest {
protected:
    bool planarTest() const override { return true; }
};

TEST_P(PlanarVehicleTest, StaticSagIsWeightOverStiffness) { staticSag(); }
TEST_P(PlanarVehicleTest, AcceleratesAsMotorTorqueSays) { acceleration(); }
TEST_P(PlanarVehicleTest, ClimbsAGentleSlope) { slope(5.0, true); }
TEST_P(PlanarVehicleTest, CannotClimbASteepSlope) { slope(20.0, false); }
ANYPHYS_CONTRACT_SUITE(PlanarVehicleTest);

}  // namespace
}  // namespace anyphys::test

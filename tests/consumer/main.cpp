// Consumer check for the installed package: a ball dropped from y = 10 m for 60 default steps.
// With the default settings (gravity -9.81 m/s^2, dt = 1/60 s, semi-implicit Euler:
// v += h*a, then x += h*v) the height after N steps is exactly
//   y_N = y_0 - g*h^2 * N(N+1)/2,
// so the result must match to rounding (1e-9 m).
#include <cmath>
#include <cstdio>
#include <exception>

#include "anyphys/anyphys.hpp"

int main() {
    try {
        anyphys::World world;
        anyphys::BodyDef def;
        def.position = anyphys::Vec3(0.0, 10.0, 0.0);
        def.shape = anyphys::ShapeDef::sphere(0.5);
        anyphys::Body ball = world.createBody(def);

        constexpr int steps = 60;
        for (int i = 0; i < steps; ++i) world.step();

        const double g = 9.81;
        const double dt = 1.0 / 60.0;
        const double expected = 10.0 - g * dt * dt * steps * (steps + 1) / 2.0;
        const double y = ball.position().y();
        const double error = std::abs(y - expected);
        std::printf("consumer: backend %s, y after %d steps = %.17g (expected %.17g, error %.3g)\n",
                    world.backendName().c_str(), steps, y, expected, error);
        if (!(error <= 1e-9)) {
            std::fprintf(stderr, "consumer: FAILED: |y - expected| = %.3g > 1e-9\n", error);
            return 1;
        }
        std::printf("consumer: OK\n");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "consumer: FAILED: %s\n", e.what());
        return 1;
    }
}

#pragma once
// The implicit gyroscopic term as the layer defines it (GyroscopicMode::Implicit): backward
// Euler on the body-frame angular velocity, I (w1 - w0) + h w1 x (I w1) = 0, solved to
// convergence. ODE's own implicit mode is a single linearised step that can let |L| grow
// (+0.03 % in 10 s of the contract's spinning plate); the solved form never adds energy.
#include "anyphys/math.hpp"

namespace anyphys::ode {

/// The world angular velocity after a step of h seconds under the gyroscopic term alone.
Vec3 solveImplicitGyroscopic(const Vec3& worldOmega, const Quat& orientation, const Vec3& inertia, double h);

/// Whether the term can matter: it vanishes identically when all principal moments are equal.
inline bool isAnisotropic(const Vec3& inertia) {
    return inertia.maxCoeff() - inertia.minCoeff() > 1e-12 * inertia.maxCoeff();
}

}  // namespace anyphys::ode

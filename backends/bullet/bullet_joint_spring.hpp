#pragma once
// Joint springs of the Bullet backend. Bullet's 6-DOF spring applies the force of the substep's
// start, P = -h (k C + c v) (C the stretch, v its rate): a free spring keeps its energy, but the
// step diverges once (omega h)^2 + 2 h c / m passes 4 (a 15 Hz spring with damping at 60 Hz, any
// stiff spring). Here that force is kept while the spring is soft, h (h k + c) K <= 1.5 (K the
// inverse effective mass along the spring, with the joint's own rigid rows acting: a hinge's
// spring turns its body about the hinge), inside its stable range with a margin; and the springs of
// one body share that range: the test is on h (h k + c) K times the count of sprung joints on the
// busier body (four 500 N/m springs on a 0.1 kg body, each soft alone, diverged). A stiffer spring
// is implicit, the force at the end of the substep, P = -h (k (C + h v') + c v') with v' the rate
// after it: stable at any stiffness, at the price of damping a free oscillation by about
// (omega h)^2 / 2 per step. Sequential impulses solve it as a soft row with everything else
// (contacts, other joints: a loaded suspension sags m g / k exactly); the MLCP solver ignores a
// row's CFM, so there it is the impulse of the joint alone, which is weaker than the coupled one
// when other constraints carry load through the spring.
#include <btBulletDynamicsCommon.h>

namespace anyphys::bullet {

/// One constraint row: its Jacobian, J v = l1 . vA + a1 . wA + l2 . vB + a2 . wB.
struct JointRow {
    btVector3 l1{0, 0, 0}, a1{0, 0, 0}, l2{0, 0, 0}, a2{0, 0, 0};
};

/// The spring's row, the joint's rigid rows with their target rates, and the substep.
struct SpringRowInput {
    JointRow spring;
    double stretch = 0.0;                    ///< C: m or rad from the rest position
    double stiffness = 0.0, damping = 0.0;
    const JointRow* rigid = nullptr;         ///< the joint's unbounded rows (none: the spring alone)
    const btScalar* rigidTargets = nullptr;  ///< each rigid row's target rate (its constraint error)
    int rigidCount = 0;
    double h = 0.0;                          ///< s, the substep
    bool softRows = true;                    ///< the solver honours a row's CFM (sequential impulses)
    int springsOnBusierBody = 1;             ///< the most sprung joints on either body (at least 1)
};

/// Writes row `s` of `info`: the spring for bodies a and b at the start of the substep, their
/// forces of the substep (gravity included) counted as the solver counts them.
void writeSpringRow(btTypedConstraint::btConstraintInfo2* info, int s, const btRigidBody& a, const btRigidBody& b,
                    const SpringRowInput& in);

}  // namespace anyphys::bullet

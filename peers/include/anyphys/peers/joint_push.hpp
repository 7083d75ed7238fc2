#pragma once
// The fastest a joint's anchor gap is pulled shut, shared by every backend that bounds it itself.

namespace anyphys {

/// m/s. Engines pull a joint's gap shut at ERP x gap / h, without bound: a bob set 3 m off its
/// hinge was flung back at 226 m/s (native's uncapped soft step), 55 (ODE) and 25 (Bullet), and
/// ODE's torn 40-link chain flew apart at 1.7 km/s. Capped, the bob comes back at 4.5 to 5.3 m/s.
/// At 5 m/s native's cap binds in none of the chains' and ragdoll piles' runs at the default
/// settings (3 m/s let a swinging chain with a 100x end stretch 57 mm instead of 34). Box2D v3
/// caps its contacts' push the same way, not its joints.
inline constexpr double kJointPushMaxVelocity = 5.0;

}  // namespace anyphys

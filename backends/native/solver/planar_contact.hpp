#pragma once
// Contact constraints of a planar world (WorldSettings::planar), in the wide layout of
// contact_constraint.hpp but with three degrees of freedom per body: x, y and the angle about Z.
// A planar body has no inverse mass along Z and no inverse inertia about X or Y (the plane holds
// it), so the 3D rows along Z and the twist about an in-plane normal move nothing; this path
// leaves them out. Per manifold: a normal impulse per point and one friction row at the
// manifold's centre along the in-plane tangent, clamped to mu * the sum of the normal impulses
// (the 3D friction circle with its Z part always zero). A lane costs about a third of a 3D lane
// in arithmetic and in memory, which is what every pass streams.
//
// The bodies' solver states stay the 3D ones (SolverState), so integration, joints and the
// force callback are shared: the kernels read v.x, v.y, w.z, dp.x, dp.y and the rotation about
// Z of dq (w, 0, 0, z), and write v.x, v.y, w.z.
#include <cstdint>

#include "solver/contact_constraint.hpp"

namespace anyphys::native {

/// What every pass reads and writes for one point (every lane).
struct PlanarContactPoint {
    wide::FloatW anchorAx, anchorAy, anchorBx, anchorBy;  // point - centre of mass, step start
    wide::FloatW baseSeparation;                           // s = base + n . (dpB - dpA + qB rB - qA rA)
    wide::FloatW normalMass;
    wide::FloatW normalImpulse;                            // accumulated within the substep, N s
    wide::FloatW maxImpulse;                               // largest accumulated impulse seen
    wide::FloatW stepImpulse;                              // sum over the step's substeps (what events report)
};

/// What every pass reads and writes of eight manifolds (as WideContact, whatever the passes do not
/// read is in PlanarContactCold).
struct PlanarContact {
    std::int32_t bodyA[wide::kLanes];  // solver body index or kStaticBody
    std::int32_t bodyB[wide::kLanes];
    bool writeA[wide::kLanes];
    bool writeB[wide::kLanes];
    int pointCount;
    bool reverse = false;  // PGS: the next solve visits the points last to first
    bool unjointed[wide::kLanes];  // no joint holds either body: the lane may be swept again (manifold_sweeps.hpp)
    bool multiPoint[wide::kLanes]; // more than one point: the lane's normal rows join the later sweeps
    bool turnArmA[wide::kLanes];   // as WideContact's: a kinematic or turning body's friction arm turns with it
    bool turnArmB[wide::kLanes];
    bool turnsArms;                // some lane turns an arm
    wide::FloatW invMassA, invMassB, invIA, invIB;  // in-plane mass, inverse inertia about Z
    wide::FloatW normalX, normalY;                  // tangent = (-normalY, normalX)
    wide::FloatW centerAx, centerAy, centerBx, centerBy;  // friction centre relative to each centre of mass
    wide::FloatW tangentMass, friction, frictionImpulse;
    wide::FloatW biasRate, massScale, impulseScale;
    PlanarContactPoint points[4];
};

/// What only the prepare, restitution and store stages read, beside the PlanarContacts: the same
/// per-lane fields as a 3D record's.
using PlanarContactCold = WideContactCold;

/// A record's accumulated impulses as each lane's change of velocity, beside the PlanarContacts
/// (as WideWarmStart in 3D): written by the prepare stage and by the pass that ends each substep,
/// so that the warm start reads these 480 bytes a record (60 a lane) instead of the anchors, masses and
/// impulses of the whole PlanarContact.
struct PlanarWarmStart {
    std::int32_t bodyA[wide::kLanes];
    std::int32_t bodyB[wide::kLanes];
    bool writeA[wide::kLanes];
    bool writeB[wide::kLanes];
    wide::FloatW vxA, vyA, wA;  // subtracted from body A's velocity
    wide::FloatW vxB, vyB, wB;  // added to body B's
};

/// Fills `pc` from up to kLanes lanes (the rest are padding with no effect).
void preparePlanarContacts(PlanarContact& pc, PlanarContactCold& cold, const ContactLane* lanes, int count,
                           const SolverBody* bodies, const SolverState* states, const ContactPrepareParams& params);
/// Sums each record's impulses into `warm` (the prepare stage's warm start).
void summarizePlanarImpulses(const PlanarContact* contacts, PlanarWarmStart* warm, int count);
void warmStartPlanarContacts(const PlanarWarmStart* warm, int count, SolverState* states);
/// As solveContacts: a pass that ends a substep sums its impulses into `warm` for the next one.
void solvePlanarContacts(PlanarContact* contacts, PlanarWarmStart* warm, int count, SolverState* states,
                         const ContactSolveParams& params, bool useBias, bool endOfSubstep);
/// As applyRestitution: true when some row bounced or held.
bool applyPlanarRestitution(PlanarContact* contacts, PlanarContactCold* cold, int count, SolverState* states,
                            Vec3* supports, const ContactSolveParams& params);
void storePlanarImpulses(const PlanarContact* contacts, const PlanarContactCold* cold, int count);

}  // namespace anyphys::native

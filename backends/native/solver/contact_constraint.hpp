#pragma once
// Contact constraints in the wide layout: each lane of a WideContact is one manifold (up to four
// points sharing a normal), and the eight lanes of one WideContact never share a dynamic body
// (they come from one graph colour). Per manifold: a normal impulse per point (non-penetration,
// soft or Baumgarte), and friction at the manifold's centre (two tangents clamped to the
// friction circle, plus twist about the normal), as Box3D does; that is 3 friction rows per
// manifold instead of 8, with the same total force on a sliding face.
//
// The stages, each over a range of WideContacts:
//   prepareContacts     once per step: anchors, effective masses, warm-start impulses
//   warmStartContacts   each substep: apply the accumulated impulses again (as summed by
//                       summarizeImpulses at the end of prepare and of each substep)
//   solveContacts       each pass: friction, then non-penetration (with or without bias)
//   applyRestitution    after the substeps, in rounds over the colours (kRestitutionRounds)
//   storeImpulses       once per step: impulses back to the manifolds for the next step (without
//                       the restitution stage's: the next step warm-starts from the contact's load)
#include <algorithm>
#include <cstdint>

#include "collision/shape.hpp"
#include "solver/solver_body.hpp"
#include "solver/wide.hpp"

namespace anyphys::native {

struct ContactManifold;

struct WideContactPoint {
    wide::Vec3W anchorA, anchorB;      // contact point - centre of mass, world frame, step start
    wide::FloatW baseSeparation;       // s = base + n . (dpB - dpA + dqB rB - dqA rA)
    wide::FloatW normalMass;
    wide::FloatW normalImpulse;        // accumulated within the substep, N s
    wide::FloatW stepImpulse;          // sum over the step's substeps (what events report)
    wide::FloatW maxImpulse;           // largest accumulated impulse seen (did it push at all?)
    wide::FloatW leverArm;             // distance to the friction centre (twist friction limit)
};

/// What every pass reads and writes of eight manifolds. The passes stream these records and wait
/// on memory more than they compute, so whatever a pass can work out (the second tangent) or does
/// not read (WideContactCold) stays out.
struct WideContact {
    std::int32_t bodyA[wide::kLanes];  // solver body index or kStaticBody
    std::int32_t bodyB[wide::kLanes];
    bool writeA[wide::kLanes];         // the lane's body takes impulses (dynamic, not a padding lane)
    bool writeB[wide::kLanes];
    int pointCount;                    // most points in any lane
    bool reverse = false;              // the next solve visits the points last to first
    bool unjointed[wide::kLanes];      // no joint holds either body: friction joins the later sweeps (manifold_sweeps.hpp)
    bool multiPoint[wide::kLanes];     // the lane's manifold has more than one point: its normal rows join the later sweeps
    bool turnArmA[wide::kLanes];       // the pair is flat and body A kinematic or turning: its friction arm turns with it (turnsFrictionArm)
    bool turnArmB[wide::kLanes];
    bool turnsArms;                    // some lane turns an arm
    wide::FloatW invMassA, invMassB;   // the same along every axis (a planar world has PlanarContact)
    wide::SymMat3W invIA, invIB;
    wide::Vec3W normal, tangent1;      // second tangent: normal x tangent1 (secondTangent)
    wide::Vec3W centerA, centerB;      // friction centre relative to each centre of mass
    wide::SymMat2W tangentMass;
    wide::FloatW twistMass;
    wide::FloatW friction;
    wide::FloatW frictionImpulse1, frictionImpulse2, twistImpulse;
    wide::FloatW biasRate, massScale, impulseScale;  // soft-contact coefficients of the lane
    WideContactPoint points[4];
};

/// What only the prepare, restitution and store stages read of the same eight manifolds, in an
/// array beside the WideContacts (the same index), kept out of the records the passes stream (it
/// made them 13 % larger).
struct WideContactCold {
    ContactManifold* manifold[wide::kLanes];  // source of each lane; null in padding lanes
    wide::FloatW restitution;
    wide::FloatW relativeVelocity[4];         // per point: normal velocity at the step start (< 0: approaching)
    wide::FloatW restitutionTarget[4];        // per point: normal velocity a bounce aims for
    wide::FloatW restitutionImpulse[4];       // per point: what the restitution stage added (not warm-started)
    wide::MaskW impactRow[4];                 // per point: the restitution stage bounced or held the row
    wide::MaskW touching[4];                  // per point: within linearSlop at the step start (restitution_rows.hpp)
};

/// The impulse a manifold point stores for the next step's warm start and load: what its last
/// substep pushed, less the restitution stage's share. A row the stage bounced or held passed an
/// impact, and the pair it bounced leaves: it keeps no more than it carried into this step.
/// Warm-started with the impact, a 30 kg ball bouncing off a 10 kg box at e = 0.2 was kicked
/// again a step later (the ball, 2 mm into the box, got 1.3 m/s from the warm start, and the soft
/// passes took back only part of it through the chain), rising up to 2.3 times its share.
inline double storedNormalImpulse(const WideContactCold& cold, int point, int lane, double lastSubstep,
                                  double carriedIn) {
    const double load = lastSubstep - cold.restitutionImpulse[point][lane];
    return cold.impactRow[point][lane] != 0 ? std::min(load, carriedIn) : load;
}

/// A record's accumulated impulses as each lane's change of velocity, written by the prepare stage
/// and by the pass that ends each substep, for the next substep's warm start: the warm start reads
/// these 864 bytes a record (108 a lane) instead of the whole WideContact, whose impulses do not change between
/// the two.
struct WideWarmStart {
    std::int32_t bodyA[wide::kLanes];
    std::int32_t bodyB[wide::kLanes];
    bool writeA[wide::kLanes];
    bool writeB[wide::kLanes];
    wide::Vec3W linearA, angularA;  // subtracted from body A's v and w
    wide::Vec3W linearB, angularB;  // added to body B's
};

/// A record's lanes' bodies and write flags, copied into its warm-start summary (WideWarmStart,
/// PlanarWarmStart), which the warm start reads instead of the record.
template <class Record, class Summary>
ANYPHYS_WIDE void copyLaneBodies(const Record& c, Summary& out) {
    for (int lane = 0; lane < wide::kLanes; ++lane) {
        out.bodyA[lane] = c.bodyA[lane];
        out.bodyB[lane] = c.bodyB[lane];
        out.writeA[lane] = c.writeA[lane];
        out.writeB[lane] = c.writeB[lane];
    }
}

/// The second friction direction, normal x tangent1, as the prepare stage chose it.
ANYPHYS_WIDE wide::Vec3W secondTangent(const WideContact& c) { return wide::cross(c.normal, c.tangent1); }

/// One manifold to place in a lane: its solver bodies (kStaticBody for static or asleep) and
/// the contact's mixed material.
struct ContactLane {
    ContactManifold* manifold = nullptr;
    std::int32_t bodyA = kStaticBody, bodyB = kStaticBody;
    double friction = 0.0, restitution = 0.0;
    std::uint32_t orderKey = 0;  // a hash of the pair and manifold: where the solver visits it (ConstraintGraph)
    // Neither shape is round: where they touch is a point of each body (on a round shape it is
    // not: a rolling ball's stays below it), so a kinematic body's friction arm may turn with it
    // within the step (the passes in contact_solve.cpp and planar_solve.cpp).
    bool flatPair = false;
};

/// A dynamic body turning less than this in a step keeps its step's first friction arm: turned,
/// the arm would move by little more than a rounding, and the passes would turn it for nothing
/// (a resting pile turns about 1e-6 rad a step).
inline constexpr double kLeastArmTurn = 1e-3;  // rad per step

/// Whether `body`'s friction arm in lane `in` turns with it within the step: the pair is flat
/// (ContactLane::flatPair) and the body kinematic, or dynamic and turning `turnPerStep` (rad, its
/// angular speed at the step's start times the step) more than kLeastArmTurn. The passes' reasons
/// are in contact_solve.cpp.
inline bool turnsFrictionArm(const ContactLane& in, std::int32_t body, const SolverBody* bodies, double turnPerStep) {
    if (!in.flatPair || body == kStaticBody) return false;
    return !bodies[body].dynamic || turnPerStep > kLeastArmTurn;
}

/// Soft-constraint coefficients of a spring of `hertz` with damping ratio `zeta` over step h
/// (implicit Euler on a mass-spring-damper; Catto, "Solver2D", 2024). Zero hertz: rigid.
struct Softness {
    double biasRate = 0.0;
    double massScale = 1.0;
    double impulseScale = 0.0;
};
Softness makeSoftness(double hertz, double zeta, double h);

/// Loaded contacts made stiffer (contactSoftness). A contact's spring is written for the mass of its
/// two bodies, so in a column of N boxes the bottom contacts sag and yield N times as far as the
/// top one: the column leans, and a tall stack of small boxes tipped over at 60 Hz.
struct LoadStiffening {
    double hertz = 0.0;         // the contacts' frequency between two moving bodies
    double maxHertz = 0.0;      // the stiffness cap (StepSolver::solve)
    double dampingRatio = 0.0;
    double h = 0.0;             // s, substep
    double gravity = 0.0;       // m/s^2, |g|: a carried mass is the impulse over g h; 0: off
};

struct ContactPrepareParams {
    Softness dynamicSoftness;          // contacts between two moving bodies
    Softness staticSoftness;           // contacts with a static body: stiffer, so piles do not sink
    LoadStiffening load;
    double speculativeDistance = 0.0;  // m: points farther than this weigh little in the friction centre
    double linearSlop = 0.0;           // m: a point this close at the step start touches
    double velocityTimeOffset = 0.0;   // s: where the integrator's velocity sits in time (restitution)
    double stepTime = 0.0;             // s: the whole step (an impact falls within it)
    double substep = 0.0;              // s: the solver's substep
    bool warmStart = true;
};

/// The softness of manifold m's contact: against a static body `staticSoftness`; between two moving
/// bodies (inverse masses invMassA, invMassB) `dynamicSoftness` while its points carried no more
/// than the pair's weight over the last substep (the warm start), and above it a frequency raised
/// by the square root of the carried mass over the pair's, so that every contact of a column sags
/// as far as the top one, up to the cap (LoadStiffening). Shared by the 3D and planar prepares.
Softness contactSoftness(const ContactPrepareParams& params, bool againstStatic, const ContactManifold& m, double invMassA,
                         double invMassB);

/// The normal velocity a point `s` apart should leave a bounce of restitution e with, from its
/// step-start normal velocity vn under the relative normal acceleration an (bounceVelocity, with the
/// step's timing from params), the bodies sliding along the surface at `slide`. Shared by the 3D
/// and the planar prepares.
double restitutionTarget(const ContactPrepareParams& params, double e, double s, double vn, double an, double slide);

/// Fills `wc` and `cold` from up to kLanes lanes (`count` of them; the rest are padding with no effect).
void prepareContacts(WideContact& wc, WideContactCold& cold, const ContactLane* lanes, int count,
                     const SolverBody* bodies, const SolverState* states, const ContactPrepareParams& params);

struct ContactSolveParams {
    double invH = 0.0;                 // 1 / substep
    double pushMaxVelocity = 0.0;      // m/s, fastest push-out of overlap
    bool soft = true;                  // soft contacts; false: PGS with Baumgarte bias
    double baumgarte = 0.0;            // PGS: fraction of overlap (beyond linearSlop) per substep
    double linearSlop = 0.0;
    bool friction = true;
    double restitutionThreshold = 0.0; // m/s
    // Each pass also asks for the records ahead (prefetch.hpp): only worth it once they outgrow a
    // core's cache; below that the hints cost the 1 000-box drop 5 %.
    bool prefetchRecords = false;
};

/// Sums each record's impulses into `warm` (the prepare stage's warm start).
void summarizeImpulses(const WideContact* contacts, WideWarmStart* warm, int count);
void warmStartContacts(const WideWarmStart* warm, int count, SolverState* states);
/// One Gauss-Seidel pass. `useBias`: push overlap apart (soft or Baumgarte); false is the relax
/// pass. `endOfSubstep`: this pass ends a substep, so its impulses add to the step's total and
/// are summed into `warm` for the next substep.
void solveContacts(WideContact* contacts, WideWarmStart* warm, int count, SolverState* states,
                   const ContactSolveParams& params, bool useBias, bool endOfSubstep);
/// One round of the restitution stage over a colour's records; true when some row bounced or held.
/// `supports`: per solver body, the direction a support holds it in this stage (restitution_rows.hpp).
bool applyRestitution(WideContact* contacts, WideContactCold* cold, int count, SolverState* states, Vec3* supports,
                      const ContactSolveParams& params);
void storeImpulses(const WideContact* contacts, const WideContactCold* cold, int count);

/// Whether the per-pass kernels run their AVX2 build (the CPU has AVX2, and no one turned it
/// off). Both builds give the same bits; tests switch to compare them.
bool contactKernelsUseAvx2();
/// Chooses the AVX2 build when `enable` and the CPU has it; returns what is now in use.
bool setContactKernelsAvx2(bool enable);

}  // namespace anyphys::native

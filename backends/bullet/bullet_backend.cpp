// Registration record of the Bullet backend: its name, capabilities and world factory.
#include <memory>
#include <string>

#include "anyphys/limits.hpp"
#include "anyphys/peers/backend.hpp"
#include "bullet_world.hpp"

namespace anyphys {

Backend makeBulletBackend() {
    Backend backend;
    backend.name = "bullet";
    backend.description = "Bullet " + std::to_string(BT_BULLET_VERSION / 100) + "." +
                          std::to_string(BT_BULLET_VERSION % 100) + " (btDiscreteDynamicsWorld, " +
                          (sizeof(btScalar) == sizeof(double) ? "double" : "single") +
                          " precision): sequential impulses or the MLCP (Dantzig) solver";
    Capabilities& caps = backend.capabilities;
    caps.dimensions = 3;
    caps.planar = true;  // linear factor (1, 1, 0), angular factor (0, 0, 1)
    caps.shapes = {ShapeType::Sphere, ShapeType::Box,  ShapeType::Capsule, ShapeType::Plane,
                   ShapeType::Convex, ShapeType::Mesh, ShapeType::Compound};
    caps.bodyTypes = {BodyType::Static, BodyType::Kinematic, BodyType::Dynamic};
    caps.effects = Effects::all();
    caps.jointTypes = {"fixed", "ball", "hinge", "slider", "distance", "cone", "wheel"};
    caps.solvers = {Solver::ProjectedGaussSeidel, Solver::Direct};
    caps.defaultSolver = Solver::ProjectedGaussSeidel;
    // Bullet's own defaults. Bullet substeps the whole step (free bodies too): with n > 1 a free
    // body takes n semi-implicit Euler steps of dt / n rather than one of dt.
    caps.defaultSubsteps = 1;
    // 30 sequential-impulse iterations: at Bullet's 10 a 20-row pyramid spreads 68 cm in 5 s (29 cm
    // at 20), at 30 it stays within 5 mm.
    caps.defaultIterations = 30;
    caps.contactImpulses = true;  // btManifoldPoint::getAppliedImpulse, the solver's normal impulse
    caps.queries = {"raycast", "overlap"};
    // Measured on 2026-12-02 (a 0.1 m and a 2 m box resting on the ground for 2 s, masses by
    // decade, the same at both sizes, its height read every step): from 1e16 kg both solvers let
    // it sink through; up to 1e-16 kg the MLCP solver does (quickstep held down to 1e-27 kg); from
    // 1e12 kg the MLCP solver lets it fall freely for the first step (2.1 to 2.7 mm) before it
    // holds (quickstep held to 1e15 kg).
    caps.lightestBody = 1e-15;
    caps.heaviestBody = 1e11;
    caps.integrators = {Integrator::SemiImplicitEuler};  // Bullet's own
    caps.gyroscopicModes = {GyroscopicMode::None, GyroscopicMode::Explicit, GyroscopicMode::Implicit};
    caps.forceEvaluation = ForceEvaluation::PerStep;
    caps.parameters = {"settings.gravity", "settings.timeStep", "settings.integrator", "settings.substeps",
                       "settings.effects", "settings.solver", "settings.iterations", "settings.baumgarte",
                       "settings.contactPushMaxVelocity", "settings.restitutionThreshold", "settings.sleepLinearVelocity",
                       "settings.sleepAngularVelocity", "settings.timeToSleep", "body.type", "body.position",
                       "body.orientation", "body.linearVelocity", "body.angularVelocity", "body.shape", "body.mass",
                       "body.density", "body.inertia", "body.linearDamping", "body.angularDamping",
                       "body.gravityScale", "body.gyroscopic", "body.material", "body.isTrigger", "body.layer",
                       "body.mask", "body.allowSleep", "body.isAwake", "body.shape.shapes.material", "body.shape.shapes.isTrigger",
                       "body.shape.shapes.layer", "body.shape.shapes.mask"};
    // Joint parameters honoured (each checked by tests/backends/bullet/test_bullet_joints.cpp).
    for (const char* type : {"fixed", "ball", "hinge", "slider", "distance", "cone", "wheel"})
        for (const char* field : {"breakForce", "breakTorque", "collideConnected"})
            caps.parameters.insert(std::string("joint.") + type + "." + field);
    for (const char* field : {"joint.hinge.limits", "joint.hinge.motor", "joint.hinge.spring", "joint.slider.limits",
                              "joint.slider.motor", "joint.slider.spring", "joint.wheel.limits", "joint.wheel.motor",
                              "joint.wheel.spring", "joint.wheel.steering", "joint.distance.spring",
                              "joint.distance.minLength", "joint.distance.maxLength", "joint.cone.swingLimit",
                              "joint.cone.twistLimits"})
        caps.parameters.insert(field);
    caps.options = {
        {.name = "erp2", .meaning = "fraction of deep overlap (beyond splitImpulseDepth) removed per step by split impulse; default settings.baumgarte", .min = 0, .max = 1},
        {.name = "splitImpulse", .meaning = "1: push deep overlap apart without adding velocity (Bullet's split impulse), 0: Baumgarte only; default 1", .min = 0, .max = 1, .integer = true},
        {.name = "splitImpulseDepth", .meaning = "m, overlap beyond which split impulse takes over from Baumgarte; default 0.04", .min = 0},
        {.name = "cfm", .meaning = "constraint force mixing (softness) of every contact; default 0", .min = 0},
        {.name = "frictionDirections", .meaning = "1: friction along the sliding direction only, 2: also across it; default 2", .min = 1, .max = 2, .integer = true},
        {.name = "frictionCaching", .meaning = "1: keep each point's friction directions across steps; default 0", .min = 0, .max = 1, .integer = true},
        {.name = "fixedFrictionDirections", .meaning = "1: friction directions from the normal only, not the sliding velocity; default 0", .min = 0, .max = 1, .integer = true},
        {.name = "decoupledJoints", .meaning = "1: each joint's rigid rows are handed to the solver in a basis where they do not interact (solved in one pass), 0: Bullet's rows as they are; default 1", .min = 0, .max = 1, .integer = true},
        {.name = "jointIterations", .meaning = "sequential-impulse iterations of joint rows (Bullet does not warm start them); default 10 x settings.iterations", .min = 1, .max = kMaxIterations, .integer = true},
        {.name = "linearSlop", .meaning = "m, overlap the solver leaves uncorrected; default 0", .min = 0},
        {.name = "planeMultipoint", .meaning = "1: a convex shape on a plane keeps its whole face of contact points (Bullet's perturbation, 5 tilts whenever the face lacks 4 points, with stale points dropped first) and a capsule both ends of its core, 0: one new point per step (Bullet's default); default 1", .min = 0, .max = 1, .integer = true},
        {.name = "warmstarting", .meaning = "fraction of last step's impulses to start from; default 0.85", .min = 0, .max = 1},
    };
    caps.knownDeviations = {
        {"joints.motor_lever",
         "a 1 000 N m hinge motor at 1 rad/s turning a 1 kg point-like bob on a 1 m arm under gravity lags: 0.53 rad/s "
         "off its speed at worst, 1.21 rad after 2 s (exact 2). Sequential impulses do not carry the motor's torque "
         "through the pin at a lever 1 000 times the bob's own inertia (the MLCP solver turns it at 1 rad/s)"},
        {"planar.joints.motor_lever", "as joints.motor_lever, in a planar world (the same figures)"},
        {"vehicle.turning_radius",
         "the car turns 14 % wide (10.4 m for the bicycle geometry's 9.16 m at 0.3 rad) at 1 substep x 30 "
         "iterations: the steered wheel joints do not converge (100 iterations: 9.46 m, 4 substeps: 9.61 m)"},
        {"planar.pyramid20.drift",
         "as pyramid20.drift, planar: 14 cm"},
        {"pyramid20.sink",
         "the 20-row pyramid's top box is thrown up 10 cm as it comes apart (as pyramid20.drift)"},
        {"pyramid20.drift",
         "the 20-row pyramid comes apart with sleeping off: boxes drift 12 cm sideways within 5 s (as stability.pyramid20.pgs.s1)"},
        {"planar.stack10.top_drift",
         "as stack10.top_drift, planar: 1.4 cm over 10 s; 0.8 mm at 4 substeps"},
        {"stack10.top_drift",
         "the 10-box stack's top drifts 1.8 cm sideways over 10 s with sleeping off (1 substep, pgs, 30 iterations); 1.1 mm at 4 substeps"},
        // Joints and assemblies, measured by their contract at the defaults (one 1/60 s step).
        {"joints.pendulum_energy",
         "a 0.3 rad pendulum loses 6.2 % of its swing energy in 20 periods at one 1/60 s step: Bullet's Baumgarte position correction on joint rows drains the swing; 4 substeps keep it under 1.2 %"},
        {"joints.wide_pendulum_energy",
         "a 1.5 rad pendulum loses 48 % of its swing energy in 20 periods (as joints.pendulum_energy)"},
        {"joints.wide_pendulum_period",
         "the 1.5 rad pendulum's mean period is 4.5 % short (2.231 s, exact 2.336) as the swing drains (joints.wide_pendulum_energy); 0.24 % at 4 substeps"},
        {"planar.joints.pendulum_energy",
         "as joints.pendulum_energy, in a planar world (6.2 %)"},
        {"planar.joints.wide_pendulum_energy",
         "as joints.wide_pendulum_energy, in a planar world (48 %)"},
        {"planar.joints.wide_pendulum_period",
         "as joints.wide_pendulum_period, in a planar world (4.5 % short)"},
        {"joints.double_pendulum_energy_fast",
         "the double pendulum's fast mode (period 1.09 s) loses 8.7 % of its swing energy in 20 s at one 1/60 s step (Baumgarte correction on the joint rows); the slow mode keeps it within 2.3 %"},
        {"planar.joints.double_pendulum_energy_fast",
         "as joints.double_pendulum_energy_fast, in a planar world (8.7 %)"},
        {"joints.distance_rod",
         "a swinging 1 m rod stretches by 12.8 mm at one 1/60 s step: Baumgarte correction at ERP 0.2 leaves g h^2 / ERP = 13.6 mm of sag (predicted), above the 1 cm bound"},
        {"planar.joints.distance_rod",
         "as joints.distance_rod, in a planar world (12.8 mm)"},
        {"joints.conical_pendulum",
         "cone angle error 0.022 rad and orbit phase 0.20 rad after 10 s (bounds 0.02 and 0.1): the first-order step at 1/60 s; both pass at 4 substeps"},
        {"hard.chain40.gap",
         "the catalogue's chain_40 comes apart as the contract's chain does (joints.chain_gap): gaps of 5.2 m (10.7 before "
         "the joints' pull was capped at 5 m/s)"},
        {"planar.hard.chain40.gap", "as hard.chain40.gap, planar: 6.0 m (9.8 before the cap)"},
        {"joints.chain_gap",
         "a 40-link ball chain of 10 cm links released horizontal comes apart at one 1/60 s step (gaps of metres after about a second, both solvers): the whipping links turn about 1 rad per step, beyond what one linearised step holds; substeps hold it"},
        {"joints.chain_gap_heavy",
         "the same chain with a 100x end mass comes apart too (as joints.chain_gap)"},
        {"joints.chain_gap.direct",
         "with the MLCP (direct) solver the chain comes apart too (as joints.chain_gap)"},
        {"joints.chain_gap_heavy.direct",
         "as joints.chain_gap.direct, with a 100x end mass"},
        {"planar.joints.chain_gap",
         "as joints.chain_gap, in a planar world"},
        {"planar.joints.chain_gap_heavy",
         "as joints.chain_gap_heavy, in a planar world"},
        {"planar.joints.chain_gap.direct",
         "as joints.chain_gap.direct, in a planar world"},
        {"planar.joints.chain_gap_heavy.direct",
         "as joints.chain_gap_heavy.direct, in a planar world"},
        {"assemblies.ragdoll_rest",
         "a pile of four ragdolls still moves at 0.27 m/s after 10 s (median of nine draws, 0.04 to 0.37; the single run gave 0.34; sleeping off; bound 0.1): its joints and contacts keep jittering. The 10-ragdoll pile over 12 nudged runs ends between 0.11 and 0.82 m/s (median 0.30), planar between 0.21 and 4.8 m/s; before capsules lying on boxes kept both ends, 0.17 to 0.63 and 0.24 to 6.3, and this pile 0.031"},
        {"planar.assemblies.ragdoll_rest",
         "a planar pile of four ragdolls still moves at 0.21 m/s after 10 s (median of nine draws, 0.01 to 1.14; sleeping off; bound 0.1): as assemblies.ragdoll_rest, its joints and contacts keep jittering (the single run gave 0.010 and passed)"},
        {"assemblies.pinched_pile_gap",
         "the soak run's pinched pile of ragdolls opens a joint 100 mm (median of nine nudged draws, all within 0.01 mm; bound 5 cm; 116 mm while limbs were clamped): Baumgarte joint rows at one 1/60 s step yield under the impacts"},
    };
    // Stability over the whole run, sleeping off, per solver and substep count
    // (tests/contract/test_stability.cpp: drift 1 cm, sink linearSlop per contact, lift 1 mm).
    caps.knownDeviations.insert({
        {"stability.stack10.pgs.s1",
         "at 1 substep the 10-box stack drifts 1.8 cm over 10 s (bound 1 cm); 1.1 mm at 4 substeps"},
        {"stability.stack10.direct.s1",
         "the MLCP solver at 1 substep: the stack drifts 1.8 cm; 1.1 mm at 4 substeps"},
        {"stability.pyramid20.pgs.s1",
         "the 20-row pyramid comes apart: boxes drift 12 cm and the top box lifts 10 cm over 5 s"},
        {"stability.pyramid20.pgs.s4",
         "at 4 substeps the pyramid still comes apart: drift 4.0 cm, top lifts 11 cm"},
        {"planar.stability.stack10.pgs.s1",
         "as stability.stack10.pgs.s1, planar: 1.4 cm"},
        {"planar.stability.stack10.direct.s1",
         "as stability.stack10.direct.s1, planar: 1.4 cm"},
        {"planar.stability.pyramid20.pgs.s1",
         "as stability.pyramid20.pgs.s1, planar: drift 14 cm, top lifts 6.4 cm"},
        {"planar.stability.pyramid20.pgs.s4",
         "as stability.pyramid20.pgs.s4, planar: drift 4.5 cm, top lifts 7.6 cm"},
        {"stability.dropped_column.pgs.s1.box",
         "a column of ten cubes dropped onto a static box rocks harder every second: its fastest cube moves at 0.61 m/s "
         "over 15 to 20 s (1 mm gaps; bound 1 cm/s), 0.21 m/s in its tenth second. Bullet starts each contact row from 0.85 of "
         "the last step's impulse (the backend's warm-start fraction), and that impulse holds the Baumgarte push "
         "(erp2 0.2): past 1 / (1 + erp2) = 0.83 the carried push drives a motion the 30 iterations do not "
         "converge on, and it grows. A fraction of 0.75 settles columns of ten but lets taller stacks lean "
         "(hard_stack_20 0.28 -> 0.56 m against a 0.6 ceiling); erp2 0.1 settles them but tips the 20-box stack "
         "over its ceiling; split impulse at every depth topples the stacks: not changed yet"},
        {"stability.dropped_column.pgs.s1.plane",
         "as stability.dropped_column.pgs.s1.box, onto the plane (Bullet's own box-plane collision): 1.8 cm/s, settling slowly"},
        {"stability.dropped_column.direct.s1.box", "as stability.dropped_column.pgs.s1.box, the MLCP solver: 0.62 m/s"},
        {"stability.dropped_column.direct.s1.plane", "as stability.dropped_column.pgs.s1.box, the MLCP solver, onto the plane: 0.48 m/s"},
        {"stability.dropped_column.pgs.s4.box",
         "as stability.dropped_column.pgs.s1.box at 4 substeps: 0.18 m/s with 5 cm gaps (1 mm gaps settle)"},
        {"stability.dropped_column.pgs.s4.plane", "as stability.dropped_column.pgs.s4.box, onto the plane: 3.6 cm/s"},
        {"stability.dropped_column.direct.s4.box", "as stability.dropped_column.pgs.s4.box, the MLCP solver: 0.18 m/s"},
        {"stability.dropped_column.direct.s4.plane", "as stability.dropped_column.pgs.s4.plane, the MLCP solver: 0.16 m/s"},
        {"planar.stability.dropped_column.pgs.s1.box", "as stability.dropped_column.pgs.s1.box, planar: 0.12 m/s with 5 cm gaps"},
        {"planar.stability.dropped_column.pgs.s1.plane", "as stability.dropped_column.pgs.s1.plane, planar: 6.4 cm/s with 5 cm gaps"},
        {"planar.stability.dropped_column.direct.s1.box", "as stability.dropped_column.direct.s1.box, planar: 0.32 m/s with 5 cm gaps"},
        {"planar.stability.dropped_column.direct.s1.plane", "as stability.dropped_column.direct.s1.plane, planar: 7.6 cm/s with 5 cm gaps"},
        {"planar.restitution.very_heavy_ball_on_box",
         "a 65 kg ball (e = 0.5) landing at 2.5 to 4 m/s on a 10 kg box resting on the ground rises down to 85 % of "
         "e^2 h (3.9 m/s, 1.07 times the bound; 92 % in 3D, within it): the sequential-impulse iterations pass the "
         "bounce between the ball and the box's ground contact and do not converge at 6.5 to 1"},
        {"restitution.very_heavy_ball_on_box_stack",
         "the same ball on three stacked 10 kg boxes hardly rises: 4.4 % of e^2 h at 3.8 m/s (6.9 times the bound), the "
         "bounce spread down the stack, as planar.restitution.very_heavy_ball_on_box"},
        {"planar.restitution.very_heavy_ball_on_box_stack",
         "as restitution.very_heavy_ball_on_box_stack, planar: 4.3 % (6.9 times the bound)"},
        {"restitution.near_threshold",
         "with e = 0.2, 3 of 13 impacts at 1.25 to 2.45 m/s (1.25, 1.45, 1.75) do not bounce at all (2.3 times the bound "
         "at 1.75 m/s; the catalogue's 0.5 m ball, dropped from other heights, lost 9 of 15 at 1.05 to 2.45): Bullet "
         "finds the ball a step early, as a speculative point with a gap the step closes; bounced at once from there "
         "(judgeImpact), the rebound that reaches e^2 h from contact cannot climb back to the gap, so the ball stops "
         "at the gap for a step and lands again below the restitution threshold"},
        {"planar.restitution.near_threshold", "as restitution.near_threshold, planar"},
    });
    backend.createWorld = [](const WorldSettings& settings) -> std::unique_ptr<WorldPeer> {
        return std::make_unique<bullet::BulletWorld>(settings);
    };
    // Ceilings of the declared misses above, in each test's measure (stability: the worst of
    // drift, sink and lift as a multiple of its bound; about 1.5 x the figure measured).
    caps.deviationCeilings = {
        {"joints.motor_lever", 160},  // in multiples of its bounds, measured 79.3
        {"planar.joints.motor_lever", 160},  // measured 79.3
        {"vehicle.turning_radius", 0.2},
        {"planar.pyramid20.drift", 0.24},
        {"pyramid20.sink", 0.21},
        {"pyramid20.drift", 0.24},
        {"planar.stack10.top_drift", 0.03},
        {"stack10.top_drift", 0.036},
        {"stability.stack10.pgs.s1", 3.6},
        {"stability.stack10.direct.s1", 3.6},
        // Dropped columns, in multiples of the bounds (1 cm/s, 1 deg, 0.1 m). The rocking grows
        // with the run; a toppled column's tilt alone is 90.
        {"stability.dropped_column.pgs.s1.box", 80},  // measured 61.1
        {"stability.dropped_column.pgs.s1.plane", 80},  // measured 1.78 (the same rocking at other starts: 48.5)
        {"stability.dropped_column.direct.s1.box", 80},  // measured 61.9
        {"stability.dropped_column.direct.s1.plane", 80},  // measured 48.5
        {"stability.dropped_column.pgs.s4.box", 40},  // measured 17.7
        {"stability.dropped_column.pgs.s4.plane", 40},  // measured 3.64
        {"stability.dropped_column.direct.s4.box", 40},  // measured 17.8
        {"stability.dropped_column.direct.s4.plane", 40},  // measured 16.0
        {"planar.stability.dropped_column.pgs.s1.box", 80},  // measured 12.3
        {"planar.stability.dropped_column.pgs.s1.plane", 80},  // measured 6.37
        {"planar.stability.dropped_column.direct.s1.box", 80},  // measured 32.4
        {"planar.stability.dropped_column.direct.s1.plane", 80},  // measured 7.58
        {"stability.pyramid20.pgs.s1", 210},
        {"stability.pyramid20.pgs.s4", 225},
        {"planar.stability.stack10.pgs.s1", 3},
        {"planar.stability.stack10.direct.s1", 3},
        {"planar.stability.pyramid20.pgs.s1", 125},
        {"planar.stability.pyramid20.pgs.s4", 155},
        {"planar.restitution.very_heavy_ball_on_box", 1.6},  // in multiples of its bound, measured 1.07
        // Measured 6.87 and 6.88; a ball that does not rise at all scores 6.1 to 7.5 over the sweep, so
        // these catch one that ends inside the stack.
        {"restitution.very_heavy_ball_on_box_stack", 7.3},
        {"planar.restitution.very_heavy_ball_on_box_stack", 7.3},
        // Measured 2.32; a bounce lost at any impact of the sweep scores at most 3.22, so these
        // catch a ball that ends inside the ground.
        {"restitution.near_threshold", 3.3},
        {"planar.restitution.near_threshold", 3.3},
    };
    // Hard cases (`anyphys hardcases`, docs/hardcases.md) and the friction directions, measured
    // with sleeping off at the defaults; each ceiling is about 1.5 to 2 times the measured miss.
    caps.knownDeviations.insert({
        {"hard.stack20.drift",
         "the 20-box stack's top drifts 28 cm over 10 s with sleeping off (as stack10.top_drift, worse with height)"},
        {"hard.heavy_on_light.displacement",
         "the 1000 kg box goes through the 1 kg one to the ground (1.12 m): at a mass ratio of 1000 its 30 sequential-"
         "impulse iterations hold nothing. Measured: 500 iterations 5.7 mm, 8 substeps 7.0 cm, 4 substeps 10.5 cm, 50 "
         "iterations 2.07 m, the direct solver 1.98 m (before each contact's push was capped at "
         "settings.contactPushMaxVelocity: 1.47 m, 50 iterations 1.16 m)"},
        {"planar.hard.heavy_on_light.displacement",
         "as hard.heavy_on_light.displacement, planar: 1.02 m (8 substeps 4.2 mm; 1.41 m before the push cap)"},
        {"hard.column40.drift", "the 40-box column falls (its top box ends 53 m away within 30 s): as hard.stack20.drift, worse with height"},
        {"planar.hard.column40.drift", "as hard.column40.drift, planar: the top box ends 68 m away"},
        {"planar.hard.pyramid100.drift",
         "the 5050-box planar pyramid collapses (boxes 10 m from where they started within 5 s; as pyramid20.drift)"},
        {"hard.arch.displacement",
         "the arch's blocks move 1.23 cm (native: 2.2 mm over 5 s; over six nudged runs 1.23 to 1.69 cm, 1.53 to 1.94 before hull pairs kept their whole faces, bullet_hull_pairs.hpp). Measured before that change, the cause not wholly found: the crown dropped 1.55 cm in its first 4 steps, each joint first found 2 mm open with one contact point (the two 1 mm hull margins: Bullet's face clipping sees the shrunk cores, and started only once they overlapped), the crown falling freely for two steps, and its joints, leaning 10 deg from vertical, hold from step 3, 2 to 4 mm deep; a 0.1 mm margin still drops it 7 mm, then the blocks creep (the crown 2 cm out of the arch's plane by 5 s); 300 iterations or the direct solver change nothing, 4 substeps give 1.1 cm, SAT normals (m_enableSatConvex) 2.7 cm"},
        {"planar.hard.arch.displacement",
         "as hard.arch.displacement, planar: 1.13 cm"},
        {"hard.mixed_pile_mesh.sink",
         "a tumbling piece sinks 7.35 cm into the floor (6.25 cm, a hull landing at 5.9 m/s and turning at 19 rad/s, 1.2 s in, before swept bodies met the floor at their surface; over 16 runs with the pieces moved k x 0.1 mm along x, 2.1 to 11.7 cm, median 2.2, and k x 1 mm, 2.1 to 7.6 cm, median 4.8, once boxes, hulls, capsules and spheres kept whole faces on mesh triangles, bullet_face_on_triangle.hpp; before that, 5.2 cm unnudged, and so moved 2.1 to 14.8 cm, median 3.8, and 2.6 to 13.4 cm, median 7.1; over 12 nudged runs 2.4 to 8.0 cm, median 5.25, after mesh edge normals were corrected and hull and capsule pairs kept whole faces and lines; 3.0 to 10.1 cm, median 6.5, before; over six, 3.0 to 9.2 cm, and 4.6 to 10.5 before contacts were kept out to twice linearSlop, and 10.5 in the unnudged run; 5.5 before boxes gained polyhedral features, which changed the pile's course; before it, 5.7 cm when the floor is a box): Bullet keeps contact points only out to its breaking threshold, 2 % of a shape's size and at least twice linearSlop (10 mm for these pieces), so a vertex swinging down faster than that per step (0.8 m/s) is first seen inside the floor. Verified: 4 substeps leave 4.7 mm, and a ball ending a step 1 cm above any ground at 3.55 m/s sinks 5.2 cm where 4 mm above it is caught at the surface. (A second, mesh-only cause is fixed: triangles were tested only once bounding boxes overlapped, 6.2 cm before)"},
        {"contacts.wall_stop",
         "a box on ice sliding into a static wall with no restitution bounces back at up to 16 % of its speed (3 m/s; 0 to "
         "12 % at 1 m/s, by the step's phase at impact, none at 0.3 m/s; bound 0.5 %): the box-box test keeps points only within 5 mm, so a "
         "box closing faster than that per step is first found inside the wall, and Baumgarte (below the split-impulse "
         "depth) pushes the overlap out as a velocity. Tried: speculative points for box pairs closing faster than the "
         "reach (found out to the step's approach, kept where their own closing covers the gap) stop it dead at every "
         "phase, but the top box of a column of ten unit cubes dropped onto a box then slid at 0.45 to 0.47 m/s after 10 "
         "s in three of five drops (starts nudged by 0, 0.1, 1, 3 and 10 mm; without them 0.002 to 0.017 m/s), though "
         "no speculative point was made after the landings; cause not found"},
        {"planar.contacts.wall_stop", "as contacts.wall_stop, planar: up to 16 %"},
        {"hard.ragdoll_pile.joint_gap",
         "joints of a pile of 10 ragdolls open by up to 5.6 cm: Baumgarte joint rows at one 1/60 s step yield under the impacts (a chaotic pile: over 12 nudged runs 4.2 to 8.8 cm, median 5.1, before swept bodies met the ground at their surface, 5.2 cm unnudged; 18.5 cm while limbs were clamped)"},
        {"planar.hard.ragdoll_pile.joint_gap",
         "as hard.ragdoll_pile.joint_gap, planar: 5.1 cm (over 12 nudged runs 5.1 to 5.7 cm, 5.3 unnudged, before swept bodies met the ground at their surface; 21 cm while limbs were clamped)"},
        {"compound.fast_body_passes_filtered_child",
         "a body fast enough for continuous collision (over half its inner radius per step) is held at a compound "
         "child whose filter lets it through: a 40 m/s ball is 1.01 m behind free flight after passing it (then lands "
         "on the next child as it should). Bullet's sweeps test the compound as one shape and cannot tell the child "
         "apart (sensor children are taken out of the sweep; a filter depends on the swept body). Verified: with the "
         "continuousCollision effect off the hold goes (and the ball then tunnels the thin child below); excluding "
         "such pairs from the sweep instead made the ball tunnel"},
        {"friction.impact.default",
         "a ball landing at 3 m/s down, 0.3 of a step into a step, is 3.5 cm into the ground when Bullet first sees the contact: Baumgarte pushes that overlap out at 0.42 m/s (e = 0; split impulse takes over only beyond splitImpulseDepth, 4 cm), and friction, mu times a normal impulse that includes the push, takes 14 % too much at mu 0.1. Landing at a step's end it is exact (2.143 m/s, -8.571 rad/s), and so it is at 4 substeps. Verified: splitImpulseDepth 0 makes the landing exact, but then the 20-box stack topples (18 m)"},
        {"friction.impact.pgs.s1", "as friction.impact.default: rebound 0.42 m/s"},
        {"friction.impact.direct.s1", "as friction.impact.default: rebound 0.42 m/s"},
        {"planar.friction.impact", "as friction.impact.default, planar: rebound 0.42 m/s"},
    });
    caps.deviationCeilings.insert({
        // The joint and assembly criteria's measures (contract run 2026-11-24) twice over; chains
        // that tear five times over, as their figure depends on the step the tear starts at.
        {"compound.fast_body_passes_filtered_child", 1.5},  // metres behind free flight, measured 1.01
        {"hard.chain40.gap", 26},  // torn: 5x the 5.19 m measured
        {"planar.hard.chain40.gap", 30},  // torn: 5x the 6.02 m measured
        {"joints.chain_gap", 39.6},  // torn: 5x, the figure depends on when it tore
        {"joints.chain_gap.direct", 43.5},  // torn: 5x, the figure depends on when it tore
        {"joints.chain_gap_heavy", 78},  // torn: 5x, the figure depends on when it tore
        {"joints.chain_gap_heavy.direct", 63.3},  // torn: 5x, the figure depends on when it tore
        {"joints.conical_pendulum", 4.03},
        {"joints.distance_rod", 0.0255},
        {"joints.double_pendulum_energy_fast", 0.173},
        {"joints.pendulum_energy", 0.123},
        {"joints.wide_pendulum_energy", 0.951},
        {"joints.wide_pendulum_period", 0.0897},
        {"planar.joints.chain_gap", 49.1},  // torn: 5x, the figure depends on when it tore
        {"planar.joints.chain_gap.direct", 48.1},  // torn: 5x, the figure depends on when it tore
        {"planar.joints.chain_gap_heavy", 73.6},  // torn: 5x, the figure depends on when it tore
        {"planar.joints.chain_gap_heavy.direct", 70},  // torn: 5x, the figure depends on when it tore
        {"planar.joints.distance_rod", 0.0255},
        {"planar.joints.double_pendulum_energy_fast", 0.173},
        {"planar.joints.pendulum_energy", 0.123},
        {"planar.joints.wide_pendulum_energy", 0.951},
        {"planar.joints.wide_pendulum_period", 0.0897},
        {"assemblies.ragdoll_rest", 1.0},
        {"planar.assemblies.ragdoll_rest", 0.45},  // m/s, measured 0.21
        {"assemblies.pinched_pile_gap", 0.15},
        {"friction.impact.default", 12.5},  // in multiples of its bounds
        {"friction.impact.pgs.s1", 12.5},
        {"friction.impact.direct.s1", 12.5},
        {"planar.friction.impact", 12.5},
        {"hard.stack20.drift", 0.6},
        {"hard.heavy_on_light.displacement", 3.0},         // m, through: 1.12 measured (1.47 before the push cap)
        {"planar.hard.heavy_on_light.displacement", 2.9},  // m, through: 1.02 measured (1.41 before the push cap)
        {"hard.column40.drift", 270},
        {"planar.hard.column40.drift", 110},
        {"planar.hard.pyramid100.drift", 15},
        {"hard.arch.displacement", 0.03},
        {"planar.hard.arch.displacement", 0.025},
        {"hard.mixed_pile_mesh.sink", 0.13},  // m, measured 0.0735 (moved runs up to 0.117)
        {"hard.ragdoll_pile.joint_gap", 0.15},
        {"contacts.wall_stop", 0.25},         // fraction of the impact speed, measured 0.16
        {"planar.contacts.wall_stop", 0.25},  // measured 0.16
        {"planar.hard.ragdoll_pile.joint_gap", 0.15},
    });
    return backend;
}

}  // namespace anyphys

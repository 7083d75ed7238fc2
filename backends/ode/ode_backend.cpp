// Registration record of the ODE backend: its name, capabilities and world factory.
#include <memory>
#include <string>

#include "anyphys/peers/backend.hpp"
#include "ode_tuning.hpp"
#include "ode_world.hpp"

namespace anyphys {

Backend makeOdeBackend() {
    Backend backend;
    backend.name = "ode";
    backend.description =
        "Open Dynamics Engine 0.16 (double precision): quickstep (PGS) or dWorldStep (direct) solver, "
        "semi-implicit Euler, hash-space collision";
    Capabilities& caps = backend.capabilities;
    caps.dimensions = 3;
    caps.planar = true;  // dJointCreatePlane2D per dynamic body, drift projected out after each step
    caps.shapes = {ShapeType::Sphere, ShapeType::Box,  ShapeType::Capsule, ShapeType::Plane,
                   ShapeType::Convex, ShapeType::Mesh, ShapeType::Compound};
    caps.bodyTypes = {BodyType::Static, BodyType::Kinematic, BodyType::Dynamic};
    // Continuous collision is the backend's approximation (ode_continuous.cpp): ODE itself has none.
    caps.effects = Effects::all();
    // Joints (ode_joints.hpp): ODE's fixed, ball, slider, double ball (distance) and hinge2
    // (wheel) joints, ball joints with angular-motor rows (hinge, cone), and speculative stops.
    caps.jointTypes = {"fixed", "ball", "hinge", "slider", "distance", "cone", "wheel"};
    caps.integrators = {Integrator::SemiImplicitEuler};  // ODE's own
    caps.solvers = {Solver::ProjectedGaussSeidel, Solver::Direct};
    caps.defaultSolver = Solver::ProjectedGaussSeidel;
    caps.defaultSubsteps = ode::kDefaultSubsteps;
    caps.defaultIterations = ode::kDefaultIterations;
    caps.gyroscopicModes = {GyroscopicMode::None, GyroscopicMode::Implicit};  // ODE 0.16 has no explicit term
    caps.forceEvaluation = ForceEvaluation::PerStep;  // forces are held constant over an ODE step
    caps.contactImpulses = true;                      // from the contact joints' feedback
    caps.queries = {"raycast", "overlap"};
    // Debian's ODE collides a hull with a mesh through libccd, and that collider crashes: the pair is
    // never collided, so the layer refuses worlds that would need it.
    caps.missingShapePairs = {{ShapeType::Convex, ShapeType::Mesh}};
    caps.parameters = {"settings.gravity", "settings.timeStep", "settings.integrator", "settings.substeps",
                       "settings.effects", "settings.solver", "settings.iterations", "settings.baumgarte",
                       "settings.contactPushMaxVelocity", "settings.restitutionThreshold", "settings.linearSlop",
                       "settings.sleepLinearVelocity", "settings.sleepAngularVelocity", "settings.timeToSleep",
                       "body.type", "body.position", "body.orientation", "body.linearVelocity",
                       "body.angularVelocity", "body.shape", "body.mass", "body.density", "body.inertia",
                       "body.linearDamping", "body.angularDamping", "body.gravityScale", "body.gyroscopic",
                       "body.material", "body.isTrigger", "body.layer", "body.mask", "body.allowSleep",
                       "body.isAwake", "body.shape.shapes.material", "body.shape.shapes.isTrigger",
                       "body.shape.shapes.layer", "body.shape.shapes.mask",
                       // Joints: only what ode_joints.cpp honours and tests/backends/ode/test_ode_joints.cpp
                       // checks.
                       "joint.hinge.limits", "joint.hinge.motor", "joint.hinge.spring",
                       "joint.slider.limits", "joint.slider.motor", "joint.slider.spring",
                       "joint.wheel.limits", "joint.wheel.motor", "joint.wheel.spring", "joint.wheel.steering",
                       "joint.distance.spring", "joint.distance.minLength", "joint.distance.maxLength",
                       "joint.cone.swingLimit", "joint.cone.twistLimits"};
    // Every type: collideConnected (the near callback skips joined pairs), and breaking, which the
    // layer does from the reactions (ODE's joint feedback, in N and N m).
    for (const char* type : {"fixed", "ball", "hinge", "slider", "distance", "cone", "wheel"})
        for (const char* field : {"breakForce", "breakTorque", "collideConnected"})
            caps.parameters.insert(std::string("joint.") + type + "." + field);
    caps.options = {
        {.name = "erp", .meaning = "error reduction parameter: fraction of contact overlap (and of slider and wheel joint drift) "
                "corrected per step; default settings.baumgarte (0.2). Ball, hinge, cone, fixed and "
                "distance joints use their own 0.8",
         .min = 0, .max = 1},
        {.name = "cfm", .meaning = "constraint force mixing: softness of resting contacts; default 1e-6 (bouncing contacts "
                "use 1e-10 so softness does not absorb the rebound)",
         .min = 0},
    };
    backend.createWorld = [](const WorldSettings& settings) -> std::unique_ptr<WorldPeer> {
        return std::make_unique<ode::OdeWorld>(settings);
    };
    // Measured by the joint and assembly contract at the defaults (one 1/60 s step, quickstep 50
    // iterations); tests/contract/test_joints.cpp, test_assemblies.cpp.
    caps.knownDeviations = {
        {"joints.stiff_hinge_lever",
         "a 1 kg point-like bob on a 1 m arm held by a 1e5 N m/rad hinge spring (omega h = 5.3), critically damped, is "
         "at +0.016 rad, 0.026 rad/s after 2 s (exact -9.8e-5 rad, at rest); undamped, it swings by 0.040 rad about "
         "-0.024 rad in the second second (exact: by 9.8e-5 about -9.8e-5): quickstep's 50 iterations do not converge "
         "the spring's ERP / CFM row with the hinge's pin at a lever 1 000 times the bob's own inertia (the direct "
         "solver rests it exactly; a 1 m rod, 4x, rests exactly)"},
        {"planar.joints.stiff_hinge_lever",
         "as joints.stiff_hinge_lever, in a planar world (undamped: a swing of 0.038 rad about -0.019 rad)"},
        {"joints.motor_lever",
         "a 1 000 N m hinge motor at 1 rad/s turning a 1 kg point-like bob on a 1 m arm under gravity is 10.4 rad/s off its "
         "speed at worst and ends at -0.51 rad after 2 s (exact 2): quickstep's 50 iterations do not carry the motor's "
         "torque through the pin at a lever 1 000 times the bob's own inertia (the direct solver turns it at 1 rad/s)"},
        {"planar.joints.motor_lever", "as joints.motor_lever, in a planar world (13.3 rad/s off, -0.80 rad after 2 s)"},
        {"assemblies.ragdoll_limits",
         "an elbow bends 17.4 deg past its limit as a ragdoll lands (15.9, median of the pile's nine draws; 14.6 while speculative points within linearSlop of their gap were kept, 12.4 before contacts became speculative, ode_speculative.hpp; a chaotic pile: 6.9 on one version of them; quickstep, 1 substep x 50 iterations; 34 deg before continuous collision ignored jointed partners, and 9 to 51 deg over eight starting turns of the pile then, 2026-11-27); 4 substeps: 7.4 deg, 200 iterations: 9.7 deg (measured before hull and capsule contacts were completed)"},
        {"planar.assemblies.ragdoll_limits",
         "as assemblies.ragdoll_limits, planar: 17.3 deg (19.8 while speculative points within linearSlop of their gap were kept, 23.3 before contacts became speculative; 33.7 before continuous collision ignored jointed partners)"},
        // tests/contract/test_events.cpp, 2026-12-02.
        {"events.within_slop",
         "bodies placed 1 mm apart (a fifth of linearSlop) never touch, whatever their shapes and sizes: ODE's colliders report a pair only while the "
         "geoms overlap, where the layer's rule counts a gap under linearSlop as touching (a pair that has touched "
         "keeps touching while within twice linearSlop: reportNearPair)"},
        {"planar.events.within_slop", "as events.within_slop, in a planar world"},
        {"joints.wide_pendulum_energy",
         "a 1.5 rad pendulum loses 8.7 % (hinge) and 9.6 % (ball) of its swing energy in 20 periods: ODE's first-order joint rows at one 1/60 s step (ERP correction drains the swing); 4 substeps keep it under 1 %"},
        {"planar.joints.wide_pendulum_energy",
         "in a planar world the 1.5 rad hinge pendulum loses 10.8 % of its swing energy in 20 periods (as joints.wide_pendulum_energy)"},
        {"joints.hinge_axis_spin",
         "a hinge pendulum about a horizontal axis between x and z spins its bob across the axis at up to 0.75 rad/s (0.18 of the swing's fastest turn at 1.5 rad, 0.13 at 0.3 rad; 0 about z): quickstep's 50 iterations leave the hinge's rows unconverged; the direct solver leaves 0, 1 000 iterations 2e-4 rad/s, 4 substeps 0.18 rad/s"},
        {"joints.hinge_limit",
         "a point-like bob on a 1 m arm (m L^2 / I = 250) held by a -0.5 rad limit keeps spinning slightly (0.057 rad/s) at the stop: quickstep's 50 iterations do not converge at that lever; the angle itself stays within 0.0013 rad of the stop"},
        {"joints.conical_pendulum",
         "the cone angle wanders by 0.14 rad and the orbit's phase by 2.6 rad over 10 s: quickstep converges slowly when a light body swings on a long arm (the direct solver: 0.022 rad)"},
        {"joints.double_pendulum_slow",
         "slow normal mode 2.1 % long (2.675 s, exact 2.621): quickstep does not converge on the two-arm coupling at 50 iterations; the direct solver passes"},
        {"joints.double_pendulum_fast",
         "fast normal mode 2.1 % long (1.108 s, exact 1.086), as joints.double_pendulum_slow"},
        {"planar.joints.double_pendulum_slow",
         "slow normal mode 1.9 % long in a planar world (as joints.double_pendulum_slow)"},
        {"planar.joints.double_pendulum_fast",
         "fast normal mode 1.8 % long in a planar world (as joints.double_pendulum_slow)"},
        {"joints.double_pendulum_energy_slow",
         "the double pendulum's slow mode loses 42 % of its swing energy in 20 s: quickstep's unconverged two-arm coupling with ERP correction drains it (the direct solver keeps it)"},
        {"joints.double_pendulum_energy_fast",
         "the fast mode loses 47 % in 20 s (as joints.double_pendulum_energy_slow)"},
        {"planar.joints.double_pendulum_energy_slow",
         "as joints.double_pendulum_energy_slow, in a planar world (48 %)"},
        {"planar.joints.double_pendulum_energy_fast",
         "as joints.double_pendulum_energy_fast, in a planar world (46 %)"},
        {"hard.chain40.gap",
         "the catalogue's chain_40 comes apart as the contract's chain does (joints.chain_gap): gaps of 9.1 m (53 m, its "
         "links flying at 1.6 km/s, before the joints' pull was capped at 5 m/s)"},
        {"planar.hard.chain40.gap", "as hard.chain40.gap, planar: 8.5 m (51 m before the cap)"},
        {"joints.chain_gap",
         "a 40-link ball chain of 10 cm links released horizontal comes apart at one 1/60 s step (gaps of metres after about a second, both solvers): the whipping links turn about 1 rad per step, beyond what one linearised step holds; substeps hold it"},
        {"joints.chain_gap_heavy",
         "the same chain with a 100x end mass comes apart too (as joints.chain_gap)"},
        {"joints.chain_gap.direct",
         "with the direct solver the chain comes apart too: the error is the step's linearisation, not the iterations (as joints.chain_gap)"},
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
        {"assemblies.ragdoll_gap",
         "joints of a pile of four ragdolls open by up to 103 mm as the ragdolls land on each other (median of nine draws, 76 to 150; bound 5 cm): quickstep at one 1/60 s step yields under the impacts. 94 mm while speculative points within linearSlop of their gap were kept, 160 mm before contacts became speculative (ode_speculative.hpp). Before continuous collision ignored jointed partners (which froze a limb swept through its own chest) 214 mm, and 98 to 456 mm over eight starting turns of the pile"},
        {"planar.assemblies.ragdoll_gap",
         "as assemblies.ragdoll_gap, in a planar world (99 mm, median of nine draws, 77 to 127; the single run 126; 88 while speculative points within linearSlop of their gap were kept, 107 before contacts became speculative, 52 before continuous collision ignored jointed partners: the pile is chaotic)"},
        {"planar.assemblies.ragdoll_rest",
         "a planar pile of four ragdolls still moves at 0.15 m/s after 10 s (median of nine draws, 0.08 to 0.22; the single run 0.19; quickstep leaves the pile jittering; 0.34 m/s while speculative points within linearSlop of their gap were kept, 2.17 m/s before contacts became speculative, as the top ragdoll, jittering, crept off the pile from 8 s and fell; 0.22 m/s before continuous collision ignored jointed partners, on another course of this chaotic pile)"},
        {"assemblies.pinched_pile_gap",
         "the soak run's pinched pile of ragdolls opens a joint 104.6 mm (median of nine nudged draws, all 104.6 mm; bound 5 cm), as assemblies.ragdoll_gap: quickstep yields under the impacts. Its course hangs on the contacts' details. With velocities nudged by k x 1e-4 and 3e-4 of themselves (k = 0..8) the medians are 81 and 58 mm (48 to 181), against 127 and 98 mm (38 to 404) while speculative points within linearSlop of their gap were kept (82.7 mm unnudged); 61 mm (61 to 108) before contacts became speculative (ode_speculative.hpp), and 50.2 mm while the look-ahead pass (OdeWorld::collideAhead) took only bodies moving more than linearSlop a step; with velocities nudged by k x 1e-4, 3e-4 and 1e-3 of themselves (k = 0..8) that version's medians were 64, 68 and 83 mm against 70 and 81 mm (1e-4, 3e-4) before; 41 mm while ODE's own collider gave a capsule on a box one point, 65 mm with the backend's collider placing face contacts midway through the overlap, 55 mm (55 to 68) before balls' points on still bodies moved onto the ball"},
    };
    // Stability over the whole run, sleeping off, per solver and substep count
    // (tests/contract/test_stability.cpp: drift 1 cm, sink linearSlop per contact, lift 1 mm).
    caps.knownDeviations.insert({
        {"joints.heavy_joints",
         "below 1 t (kCfmReferenceMass) a pair's rows keep the world's CFM, absolute in ODE, so a light body's joints "
         "are stiffer than a heavy one's: a bob on a 1 m arm resting on a hinge limit sits 1.3 mm past it at 1 kg and "
         "3.3 mm at 1e5 and 1e7 kg alike (a 1 t bob's figure; bound 2.5 mm). The pendulums, the fixed joint and the "
         "slider hold within the bound"},
        {"planar.joints.heavy_joints", "as joints.heavy_joints, planar: 1.4 mm at 1 kg, 3.0 mm at 1e5 and 1e7 kg"},
        {"restitution.very_heavy_ball_on_box_stack",
         "a 65 kg ball (e = 0.5) landing at 2.5 to 4 m/s on three stacked 10 kg boxes rises down to 39 % of e^2 h (2.7 m/s, "
         "3.2 times the bound; on one box within 1 %): quickstep's iterations pass the bounce down the stack and back "
         "without converging at 6.5 to 1"},
        {"planar.restitution.very_heavy_ball_on_box_stack",
         "as restitution.very_heavy_ball_on_box_stack, planar: 58 % (3.7 m/s, 3.0 times the bound)"},
        {"stability.dropped_column.pgs.s1.plane",
         "a column of ten cubes dropped onto the ground keeps jittering with quickstep at 1 substep: its fastest cube "
         "moves at 2.6 cm/s over 15 to 20 s (bound 1 cm/s; 1.5 to 7.6 cm/s over a minute, not growing), upright and "
         "in place (3.7 cm). At 4 substeps 3.5 mm/s, the direct solver 1e-13 m/s"},
        {"stability.dropped_column.pgs.s1.box", "as stability.dropped_column.pgs.s1.plane, onto a static box: 3.0 cm/s"},
        {"planar.stability.dropped_column.pgs.s1.plane", "as stability.dropped_column.pgs.s1.plane, planar: 1.9 cm/s"},
        {"planar.stability.dropped_column.pgs.s1.box", "as stability.dropped_column.pgs.s1.box, planar: 2.5 cm/s"},
    });
    // Ceilings of the declared misses above, in each test's measure (stability: the worst of
    // drift, sink and lift as a multiple of its bound; about 1.5 x the figure measured).
    caps.deviationCeilings = {
        {"joints.stiff_hinge_lever", 24500},  // in multiples of its bounds, measured 12 245 (undamped)
        {"planar.joints.stiff_hinge_lever", 19200},  // measured 9 619 (undamped)
        {"joints.motor_lever", 2100},  // in multiples of its bounds, measured 1 041
        {"planar.joints.motor_lever", 2700},  // measured 1 330
        {"assemblies.ragdoll_limits", 90.0},
        {"assemblies.pinched_pile_gap", 0.15},  // m, measured 0.1046 (other versions: draws up to 0.211)
        {"planar.assemblies.ragdoll_limits", 60.0},
        {"joints.heavy_joints", 2.0},          // in multiples of its bound, measured 1.29
        {"planar.joints.heavy_joints", 1.7},   // measured 1.09
        {"restitution.very_heavy_ball_on_box_stack", 5.0},  // in multiples of its bound, measured 3.21
        {"planar.restitution.very_heavy_ball_on_box_stack", 4.5},  // measured 2.96
        // In multiples of the bounds (1 cm/s, 1 deg, 0.1 m); the speed wanders, up to 7.6 over a minute.
        {"stability.dropped_column.pgs.s1.plane", 10.0},  // measured 2.62
        {"stability.dropped_column.pgs.s1.box", 10.0},  // measured 2.98
        {"planar.stability.dropped_column.pgs.s1.plane", 10.0},  // measured 1.92
        {"planar.stability.dropped_column.pgs.s1.box", 10.0},  // measured 2.50
    };
    // Hard cases (`anyphys hardcases`, docs/hardcases.md) and the friction directions, measured
    // with sleeping off at the defaults; each ceiling is about 1.5 to 2 times the measured miss.
    caps.knownDeviations.insert({
        {"contacts.overhang_stands",
         "four boxes over a table's edge at 90 % of the harmonic offsets (each partial stack's centre of mass 5 cm inside its edge) stand, but the top box shifts 2.9 cm sideways and down within 3 s before it settles (4.3 cm before contacts became speculative, ode_speculative.hpp): each box creeps toward the overhang (ODE also rests 1 to 4 mm low, and a single box 2 mm short of a table's edge creeps off it within 4 s)"},
        {"planar.contacts.overhang_stands", "as contacts.overhang_stands, planar: 3.0 cm (3.2 before contacts became speculative)"},
        {"hard.stack20.drift",
         "the 20-box stack topples (the top 2.2 m sideways within 10 s; 2.6 m before contacts became speculative, 1.6 m before resting boxes kept their four corners): quickstep's 50 iterations at 1 substep do not converge for 20 stacked contacts. Verified: 200 iterations leave 1.8 cm, 4 substeps 3.2 mm (the direct solver topples too, 11.7 m, its Dantzig LCP reporting s <= 0)"},
        {"hard.column40.drift",
         "the 40-box column falls (its top box ends 46 m away within 30 s; 26 m before resting boxes kept their four corners: where it lands is chance), as the 20-box stack topples"},
        {"planar.hard.column40.drift", "as hard.column40.drift, planar: the top box ends 44 m away (33 m while speculative points within linearSlop of their gap were kept, 69 m before contacts became speculative: where it lands is chance)"},
        {"planar.hard.pyramid100.drift",
         "the 5050-box planar pyramid spreads 17 cm within 5 s (quickstep at 1 substep x 50 iterations)"},
        {"hard.arch.displacement",
         "the arch's blocks shift 4.2 cm: ODE's convex-convex test gives NaN normals for flush hull faces, which the backend drops, and one point per pair, which it completes by tilting (ode_contact_completion.hpp); with one point the arch collapsed (2.4 m)"},
        {"planar.hard.arch.displacement",
         "as hard.arch.displacement, planar: 4.2 cm"},
        {"hard.heavy_plank.displacement",
         "the 1 kg boxes sink 2.2 cm under the 100 kg plank: at a mass ratio of 100 quickstep's 50 iterations do not converge. Verified: 500 iterations leave 3.2 mm, the direct solver 0, while CFM 1e-10 still leaves 1.7 cm (so the softness is not the cause)"},
        {"planar.hard.heavy_plank.displacement",
         "as hard.heavy_plank.displacement, planar: 1.5 cm"},
        {"hard.heavy_on_light.displacement",
         "the 1000 kg box goes through the 1 kg one to the ground (1.65 m): at a mass ratio of 1000 quickstep's 50 "
         "iterations hold nothing (as hard.heavy_plank.displacement). Measured: the direct solver 2.6 mm, 8 substeps "
         "3.4 cm, 4 substeps 9.8 cm, 500 iterations 9.3 cm"},
        {"planar.hard.heavy_on_light.displacement",
         "as hard.heavy_on_light.displacement, planar: 2.19 m"},
        {"hard.overlap25.speed",
         "25 % overlap is pushed apart at 5.8 m/s: each contact's correction is capped at settings.contactPushMaxVelocity (3 m/s, dWorldSetContactMaxCorrectingVel), and the upper box gets its own 3 m/s on top of the lower one's 2.9. Verified by the setting: 1.5 m/s gives 3.0, 1 m/s gives 2.0"},
        {"planar.hard.overlap25.speed",
         "as hard.overlap25.speed, planar: 5.8 m/s"},
        {"hard.ragdoll_pile.joint_gap",
         "joints of a pile of 10 ragdolls open by up to 11.7 cm (as assemblies.ragdoll_gap; 12.1 cm while speculative points within linearSlop of their gap were kept, 14.5 cm before contacts became speculative, 28 cm before continuous collision ignored jointed partners, 13.8 before resting boxes kept their four corners)"},
        {"planar.hard.ragdoll_pile.joint_gap",
         "as hard.ragdoll_pile.joint_gap, planar: 10.9 cm (12.7 before the joints' pull was capped at 5 m/s, 14.5 while speculative points within linearSlop of their gap were kept, 21.9 before contacts became speculative; 14.4, then 11.4, on other courses of this chaotic pile)"},
    });
    caps.deviationCeilings.insert({
        {"contacts.overhang_stands", 0.065},  // m, measured 0.0292 (0.0426 before speculative contacts)
        {"planar.contacts.overhang_stands", 0.05},  // m, measured 0.0302 (0.0317 before)
        // The joint and assembly criteria's measures (contract run 2026-11-24) twice over; chains
        // that tear five times over, as their figure depends on the step the tear starts at.
        {"hard.chain40.gap", 46},  // torn: 5x the 9.12 m measured
        {"planar.hard.chain40.gap", 43},  // torn: 5x the 8.53 m measured
        {"joints.chain_gap", 179},  // torn: 5x, the figure depends on when it tore
        {"joints.chain_gap.direct", 32.1},  // torn: 5x, the figure depends on when it tore
        {"joints.chain_gap_heavy", 186},  // torn: 5x, the figure depends on when it tore
        {"joints.chain_gap_heavy.direct", 563},  // torn: 5x, the figure depends on when it tore
        {"joints.conical_pendulum", 132},  // torn: 5x, the figure depends on when it tore
        {"joints.double_pendulum_energy_fast", 0.947},
        {"joints.double_pendulum_energy_slow", 0.844},
        {"joints.double_pendulum_fast", 0.0418},
        {"joints.double_pendulum_slow", 0.0414},
        {"joints.hinge_limit", 2.3},  // in multiples of its bounds
        {"joints.wide_pendulum_energy", 0.192},
        {"joints.hinge_axis_spin", 0.35},  // in the swing's fastest turn, measured 0.177
        {"planar.joints.chain_gap", 255},  // torn: 5x, the figure depends on when it tore
        {"planar.joints.chain_gap.direct", 88.9},  // torn: 5x, the figure depends on when it tore
        {"planar.joints.chain_gap_heavy", 252},  // torn: 5x, the figure depends on when it tore
        {"planar.joints.chain_gap_heavy.direct", 144},  // torn: 5x, the figure depends on when it tore
        {"planar.joints.double_pendulum_energy_fast", 0.914},
        {"planar.joints.double_pendulum_energy_slow", 0.963},
        {"planar.joints.double_pendulum_fast", 0.0365},
        {"planar.joints.double_pendulum_slow", 0.0381},
        {"planar.joints.wide_pendulum_energy", 0.217},
        {"assemblies.ragdoll_gap", 0.45},
        {"planar.assemblies.ragdoll_gap", 0.179},
        {"planar.assemblies.ragdoll_rest", 3.0},
        {"hard.stack20.drift", 5.0},
        {"hard.column40.drift", 100},
        {"planar.hard.column40.drift", 130},
        {"planar.hard.pyramid100.drift", 0.3},
        {"hard.arch.displacement", 0.08},
        {"planar.hard.arch.displacement", 0.08},
        {"hard.heavy_plank.displacement", 0.04},
        {"planar.hard.heavy_plank.displacement", 0.04},
        {"hard.heavy_on_light.displacement", 3.5},          // m, through: twice the 1.75 measured (1.65 now)
        {"planar.hard.heavy_on_light.displacement", 4.4},   // m, through: twice the 2.2 measured
        {"hard.overlap25.speed", 8.0},
        {"planar.hard.overlap25.speed", 8.0},
        {"hard.ragdoll_pile.joint_gap", 0.3},
        {"planar.hard.ragdoll_pile.joint_gap", 0.35},
    });
    return backend;
}

}  // namespace anyphys

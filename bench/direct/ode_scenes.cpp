// The 3D benchmark scenes written directly against ODE 0.16, configured as backends/ode
// configures its world, so that anyphys on "ode" and this program differ by the layer alone:
//   raw/<scene>/ode        drop1000, drop10000, pyramid20, pyramid3d
//   overhead/<scene>/ode   drop1000, pyramid20 (see raw_benchmarks.hpp)
// What a plain ODE user does: a hash space, contact joints made in the near callback, quickstep,
// no contact events (so no joint feedback) and no continuous sweep (the backend's own ray sweep,
// ode_continuous.cpp, is part of what the layer costs). One change to ODE's physics is repeated,
// so both sides simulate the same pile: the first friction direction along the slip
// (backends/ode/ode_slip_friction.hpp).
#include <ode/ode.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "../bench_main.hpp"
#include "anyphys/world_settings.hpp"
#include "ode_slip_friction.hpp"  // backends/ode: part of the physics
#include "raw_benchmarks.hpp"

namespace anyphys::bench {
namespace {

// The backend's values (backends/ode/ode_tuning.hpp, ode_world.cpp, ode_collide.cpp), repeated
// here because raw ODE must be driven the same way: change both together.
constexpr int kIterations = 50;                // kDefaultIterations (quickstep)
constexpr double kQuickStepW = 1.3;            // kQuickStepW (over-relaxation)
constexpr double kCfm = 1e-6;                  // kDefaultCfm (absolute)
constexpr double kSurfaceLayerPerSlop = 0.2;   // kSurfaceLayerPerSlop x settings.linearSlop
constexpr int kMaxContactsPerPair = 4;         // kMaxContactsPerPair
constexpr int kHashMinLevel = -3, kHashMaxLevel = 10;

class OdeSimulation final : public Simulation {
public:
    explicit OdeSimulation(const ScenePlan& plan) {
        const WorldSettings defaults;  // the backend reads ERP, slop and push speed from the settings
        dInitODE2(0);                  // reference counted: the backend's own call is not undone
        dAllocateODEDataForThread(dAllocateMaskAll);
        dRandSetSeed(0);  // where the backend's per-world stream starts
        world_ = dWorldCreate();
        space_ = dHashSpaceCreate(nullptr);
        dHashSpaceSetLevels(space_, kHashMinLevel, kHashMaxLevel);
        contacts_ = dJointGroupCreate(0);
        dWorldSetGravity(world_, 0, kGravity, 0);
        dWorldSetERP(world_, defaults.baumgarte);
        dWorldSetCFM(world_, kCfm);
        dWorldSetQuickStepNumIterations(world_, kIterations);
        dWorldSetQuickStepW(world_, kQuickStepW);
        dWorldSetContactSurfaceLayer(world_, kSurfaceLayerPerSlop * defaults.linearSlop);
        dWorldSetContactMaxCorrectingVel(world_, defaults.contactPushMaxVelocity);
        dWorldSetAutoDisableFlag(world_, 0);  // sleeping off

        const Vec3 g = 2.0 * plan.groundHalf;
        const dGeomID ground = dCreateBox(space_, g.x(), g.y(), g.z());  // static: a geom without a body
        dGeomSetPosition(ground, 0, -1, 0);

        const double side = 2.0 * kHalf, mass = plan.mass();
        const Vec3 inertia = plan.inertia();
        for (const Vec3& p : plan.starts) {
            const dBodyID body = dBodyCreate(world_);
            dBodySetPosition(body, p.x(), p.y(), p.z());
            dBodySetFiniteRotationMode(body, 1);
            dMass m;
            dMassSetParameters(&m, mass, 0, 0, 0, inertia.x(), inertia.y(), inertia.z(), 0, 0, 0);
            dBodySetMass(body, &m);
            dBodySetGyroscopicMode(body, 0);  // cubes: the term vanishes (the backend skips it too)
            dBodySetAutoDisableFlag(body, 0);
            const dGeomID geom = dCreateBox(space_, side, side, side);
            dGeomSetBody(geom, body);
            bodies_.push_back(body);
        }
    }

    ~OdeSimulation() override {
        dJointGroupDestroy(contacts_);
        dSpaceDestroy(space_);  // and its geoms
        dWorldDestroy(world_);  // and its bodies
    }

    void step() override {
        dSpaceCollide(space_, this, &OdeSimulation::nearCallback);
        dWorldQuickStep(world_, kTimeStep);
        dJointGroupEmpty(contacts_);
    }

    void readBoxes(std::vector<BoxState>& out) const override {
        out.resize(bodies_.size());
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            const dReal* p = dBodyGetPosition(bodies_[i]);
            const dReal* q = dBodyGetQuaternion(bodies_[i]);
            const dReal* v = dBodyGetLinearVel(bodies_[i]);
            out[i] = {Vec3(p[0], p[1], p[2]), Quat(q[0], q[1], q[2], q[3]), Vec3(v[0], v[1], v[2])};
        }
    }

    std::string describe() const override { return "quickstep, 1 step x " + std::to_string(kIterations) + " it"; }

private:
    static void nearCallback(void* self, dGeomID o1, dGeomID o2) {
        static_cast<OdeSimulation*>(self)->collide(o1, o2);
    }

    void collide(dGeomID o1, dGeomID o2) {
        dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
        if (!b1 && !b2) return;  // static against static
        if (!b1) {               // the dynamic body first, as the backend orders them
            std::swap(o1, o2);
            std::swap(b1, b2);
        }
        dContact contact[kMaxContactsPerPair];
        const int n = dCollide(o1, o2, kMaxContactsPerPair, &contact[0].geom, sizeof(dContact));
        for (int i = 0; i < n; ++i) {
            contact[i].surface = {};
            contact[i].surface.mode = dContactApprox1;  // Coulomb friction on two tangents
            contact[i].surface.mu = kFriction;
            const Vec3 point(contact[i].geom.pos[0], contact[i].geom.pos[1], contact[i].geom.pos[2]);
            const Vec3 gravity(0, kGravity, 0);
            ode::alignFrictionWithSlip(contact[i], ode::predictedPointVelocity(b1, point, gravity, kTimeStep) -
                                                       ode::predictedPointVelocity(b2, point, gravity, kTimeStep));
            const dJointID joint = dJointCreateContact(world_, contacts_, &contact[i]);
            dJointAttach(joint, b1, b2);
        }
    }

    dWorldID world_ = nullptr;
    dSpaceID space_ = nullptr;
    dJointGroupID contacts_ = nullptr;
    std::vector<dBodyID> bodies_;
};

void registerAll() {
    registerRaw({"ode",
                 {"drop1000", "drop10000", "pyramid20", "pyramid3d"},
                 {"drop1000", "pyramid20"},
                 [](const ScenePlan& plan) { return std::make_unique<OdeSimulation>(plan); }});
}

}  // namespace
}  // namespace anyphys::bench

int main(int argc, char** argv) { return anyphys::bench::benchMain(argc, argv, &anyphys::bench::registerAll); }

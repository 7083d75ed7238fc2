// The 3D benchmark scenes written directly against Bullet 3.24 (double build), configured as
// backends/bullet configures its world, so that anyphys on "bullet" and this program differ by
// the layer alone:
//   raw/<scene>/bullet        drop1000, drop10000, pyramid20, pyramid3d
//   overhead/<scene>/bullet   drop1000, pyramid20 (see raw_benchmarks.hpp)
// A plain btDiscreteDynamicsWorld with the backend's solver subclass (bullet_solver.hpp), box-box
// algorithm (bullet_box_box.hpp) and dispatcher (bullet_touching.hpp): they change the physics, so
// both sides must run them to simulate the same pile. No contact events, one
// internal step per step. Friction 0.6 on
// every body, mixed by Bullet's friction callback set to the minimum: exactly the 0.6 the backend
// writes into each contact point (Bullet's default product of sqrt(0.6) twice is one ulp off, and
// a pile is chaotic enough for one ulp to give another pile).
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "../bench_main.hpp"
#include "anyphys/world_settings.hpp"
#include "bullet_box_box.hpp"  // backends/bullet: the backend's box pairs, part of the physics
#include "bullet_solver.hpp"   // backends/bullet: the backend's solver, part of the physics
#include "bullet_touching.hpp"  // backends/bullet: the backend's contact reach, part of the physics
#include "raw_benchmarks.hpp"

namespace anyphys::bench {
namespace {

// The backend's values (backends/bullet/bullet_world.cpp, bullet_shapes.cpp, bullet_body.cpp,
// bullet_backend.cpp), repeated here because raw Bullet must be driven the same way: change both
// together.
constexpr int kIterations = 30;                 // capabilities.defaultIterations (sequential impulses)
constexpr int kPoolSize = 256;                  // manifold and collision-algorithm pools (makeCollisionConfiguration)
constexpr double kBoxMargin = 0.04;             // at most a tenth of the thinnest half extent
constexpr double kSplitImpulseDepth = 0.04;     // split impulse beyond this overlap
constexpr double kCcdMotionPerCore = 0.5;       // CCD when moving more than half the inner radius,
constexpr double kCcdSpherePerCore = 0.9;       // sweeping a sphere of 0.9 x the inner radius

btScalar minimumFriction(const btCollisionObject* a, const btCollisionObject* b) {
    return std::min(a->getFriction(), b->getFriction());
}

btVector3 bt(const Vec3& v) {
    return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z())};
}

std::unique_ptr<btDefaultCollisionConfiguration> makeConfiguration() {
    btDefaultCollisionConstructionInfo info;
    info.m_defaultMaxPersistentManifoldPoolSize = kPoolSize;
    info.m_defaultMaxCollisionAlgorithmPoolSize = kPoolSize;
    return std::make_unique<btDefaultCollisionConfiguration>(info);
}

class BulletSimulation final : public Simulation {
public:
    explicit BulletSimulation(const ScenePlan& plan)
        : configuration_(makeConfiguration()),
          dispatcher_(std::make_unique<bullet::TouchingDispatcher>(configuration_.get(),
                                                                   static_cast<btScalar>(2 * WorldSettings{}.linearSlop))),
          broadphase_(std::make_unique<btDbvtBroadphase>()),
          solver_(std::make_unique<bullet::AnyphysSequentialImpulseSolver>(
              static_cast<btScalar>(WorldSettings{}.contactPushMaxVelocity))),
          world_(std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                           configuration_.get())) {
        dispatcher_->registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, &boxBox_);
        const WorldSettings defaults;  // what the backend reads from the settings
        world_->setGravity(btVector3(0, 0, 0));  // per body, as the backend does
        world_->setForceUpdateAllAabbs(false);
        world_->getDispatchInfo().m_useContinuous = true;  // continuous collision is derived on
        btContactSolverInfo& info = world_->getSolverInfo();
        info.m_numIterations = kIterations;
        info.m_erp = info.m_erp2 = defaults.baumgarte;
        info.m_splitImpulse = true;
        info.m_splitImpulsePenetrationThreshold = -kSplitImpulseDepth;
        info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
        info.m_linearSlop = 0;
        info.m_restitutionVelocityThreshold = defaults.restitutionThreshold;

        previousFrictionRule_ = gCalculateCombinedFrictionCallback;  // a process global: restored on exit
        gCalculateCombinedFrictionCallback = &minimumFriction;
        const btScalar friction = kFriction;
        add(plan.groundHalf, 0.0, Vec3(0, -1, 0), friction);
        for (const Vec3& start : plan.starts) {
            btRigidBody& body = add(Vec3::Constant(kHalf), plan.mass(), start, friction, plan.inertia());
            // Cubes: the gyroscopic term vanishes, and the backend applies none (bullet_body.cpp).
            body.setFlags(BT_DISABLE_WORLD_GRAVITY);
            body.setGravity(btVector3(0, kGravity, 0));
            body.setCcdMotionThreshold(kCcdMotionPerCore * kHalf);
            body.setCcdSweptSphereRadius(kCcdSpherePerCore * kHalf);
            body.forceActivationState(DISABLE_DEACTIVATION);  // sleeping off
            boxes_.push_back(&body);
        }
    }

    ~BulletSimulation() override {
        for (const auto& body : bodies_) world_->removeRigidBody(body.get());
        gCalculateCombinedFrictionCallback = previousFrictionRule_;
    }

    void step() override { world_->stepSimulation(kTimeStep, 1, kTimeStep); }

    void readBoxes(std::vector<BoxState>& out) const override {
        out.resize(boxes_.size());
        for (std::size_t i = 0; i < boxes_.size(); ++i) {
            const btTransform& xf = boxes_[i]->getWorldTransform();
            btQuaternion q;
            xf.getBasis().getRotation(q);
            const btVector3& p = xf.getOrigin();
            const btVector3& v = boxes_[i]->getLinearVelocity();
            out[i] = {Vec3(p.x(), p.y(), p.z()), Quat(q.w(), q.x(), q.y(), q.z()), Vec3(v.x(), v.y(), v.z())};
        }
    }

    std::string describe() const override {
        return "sequential impulses, 1 step x " + std::to_string(kIterations) + " it";
    }

private:
    btRigidBody& add(const Vec3& half, double mass, const Vec3& position, btScalar friction,
                     const Vec3& inertia = Vec3::Zero()) {
        auto shape = std::make_unique<btBoxShape>(bt(half));
        shape->setMargin(std::min(kBoxMargin, 0.1 * half.minCoeff()));
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape.get(), bt(inertia));
        info.m_startWorldTransform.setIdentity();
        info.m_startWorldTransform.setOrigin(bt(position));
        info.m_friction = friction;
        info.m_restitution = 0;
        shapes_.push_back(std::move(shape));
        bodies_.push_back(std::make_unique<btRigidBody>(info));
        btRigidBody& body = *bodies_.back();
        world_->addRigidBody(&body, btBroadphaseProxy::AllFilter, btBroadphaseProxy::AllFilter);
        return body;
    }

    std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
    bullet::BoxBoxAlgorithm::CreateFunc boxBox_{static_cast<btScalar>(WorldSettings{}.linearSlop)};  // the dispatcher uses it
    std::unique_ptr<bullet::TouchingDispatcher> dispatcher_;
    std::unique_ptr<btDbvtBroadphase> broadphase_;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
    std::unique_ptr<btDiscreteDynamicsWorld> world_;
    std::vector<std::unique_ptr<btBoxShape>> shapes_;
    std::vector<std::unique_ptr<btRigidBody>> bodies_;
    std::vector<btRigidBody*> boxes_;  ///< the dynamic ones, in plan order
    CalculateCombinedCallback previousFrictionRule_ = nullptr;
};

void registerAll() {
    registerRaw({"bullet",
                 {"drop1000", "drop10000", "pyramid20", "pyramid3d"},
                 {"drop1000", "pyramid20"},
                 [](const ScenePlan& plan) { return std::make_unique<BulletSimulation>(plan); }});
}

}  // namespace
}  // namespace anyphys::bench

int main(int argc, char** argv) { return anyphys::bench::benchMain(argc, argv, &anyphys::bench::registerAll); }

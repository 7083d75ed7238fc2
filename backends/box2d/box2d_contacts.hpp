#pragma once
// The layer's rules inside Box2D's contact pipeline: which pairs may touch (layersCollide on the
// 32-bit layers, where b2Filter has 16 bits), and the resolved friction, restitution and
// restitution threshold of each pair (replacing Box2D's own mixing): friction when a contact
// begins, restitution in pre-solve, per impact.
#include <array>
#include <vector>
#include <box2d/box2d.h>

#include "anyphys/effects.hpp"
#include "anyphys/peers/world_peer.hpp"

namespace anyphys::box2d {

class Box2dBody;

/// The body a fixture belongs to (every fixture of this backend carries a FixtureInfo).
Box2dBody& bodyOf(const b2Fixture* fixture);
/// Whether two fixtures may touch by the layer's filter (ContactRules::ShouldCollide's test).
bool fixturesCollide(const b2Fixture* a, const b2Fixture* b);

/// The closest points of two bodies' solid fixtures, for a pair Box2D no longer lists (it lists
/// one only while the skinned shapes overlap): true with the pair's normal (from a to b), the
/// point midway between the true surfaces and its gap, when that gap is under `reach`.
bool nearestSurfaces(const b2Body& a, const b2Body& b, double reach, b2Vec2& normal, b2Vec2& point, double& gap);

/// One per world (no globals): Box2D asks it about each new pair and each touching contact.
class ContactRules final : public b2ContactFilter, public b2ContactListener {
public:
    void setEffects(Effects effects) {
        effects_ = effects;
        updateBounces();
    }
    void setMaterials(const MaterialTable& table) {
        materials_ = table;
        updateBounces();
    }
    void setRestitutionThreshold(double v) { restitutionThreshold_ = static_cast<float>(v); }
    /// Bodies whose planes lie over basements (box2d_shapes.hpp) came (+1) or went (-1): without
    /// any, pre-solve skips its basement test.
    void countBasements(int change) { basementBodies_ += change; }
    /// Before each b2World::Step: its duration and the world's gravity (for restitution).
    void beginStep(float h, const b2Vec2& gravity) {
        h_ = h;
        gravity_ = gravity;
        solved_ = false;
        timeOfImpact_ = false;
    }

    bool ShouldCollide(b2Fixture* fixtureA, b2Fixture* fixtureB) override;
    /// A contact's friction is its pair's, set once when it begins touching (Box2D keeps it).
    void BeginContact(b2Contact* contact) override { applyMaterial(contact); }
    /// Restitution per impact, where something can bounce (see impactRestitution).
    void PreSolve(b2Contact* contact, const b2Manifold* oldManifold) override;
    void PostSolve(b2Contact* contact, const b2ContactImpulse* impulse) override;

    /// Every normal impulse a solve applied since the last clear, one entry per contact and
    /// solve, in the order of the solves: the main solve's, and time of impact's, whose impulses
    /// Box2D does not store in the manifold (a fast body turned around there would otherwise
    /// report none).
    struct SolvedImpulses {
        const b2Contact* contact;
        std::array<float, b2_maxManifoldPoints> normal;
    };
    std::vector<SolvedImpulses>& solvedImpulses() { return solvedImpulses_; }
    /// Before an anyphys step's first b2World::Step. With substeps every contact's impulse is a
    /// sum over solves; without, only those of contacts a time-of-impact solve reported.
    void clearSolvedImpulses(bool substeps) {
        solvedImpulses_.clear();
        firstSummed_ = substeps ? 0 : kNone;
    }
    /// The contacts whose step impulse is not what their manifold holds are those of the
    /// entries from this one on (none when it is past the end): the manifold keeps the last main
    /// solve's impulses, and misses time of impact's.
    std::size_t firstSummedEntry() const { return firstSummed_; }

    /// Sets the pair's friction, and no bounce until pre-solve gives one; again for every contact
    /// when the table or the effects change (Box2dWorld).
    void applyMaterial(b2Contact* contact) const;

private:
    void updateBounces();

    /// The restitution to give Box2D so that the pair leaves with e times its speed at the
    /// instant of impact, in the way a semi-implicit Euler flight then rises (see the .cpp).
    float impactRestitution(b2Contact* contact, float e) const;
    /// Whether Box2D's time of impact catches a pair found `depth` deep (true surfaces) at once.
    bool pushedOutByTimeOfImpact(const b2Contact& contact, float depth) const;
    /// The rebound speed for a bounce in a time-of-impact solve; -1 under the threshold.
    float timeOfImpactRebound(const b2Contact* contact, const b2Vec2& normal, float e, float closing, float depth, float g) const;

    float h_ = 1.0f / 60.0f;
    b2Vec2 gravity_{0.0f, 0.0f};
    bool bounces_ = false;  // restitution is on and some pair of materials has some
    bool solved_ = false;  // the step's main solve is done: pre-solve calls now come from time of impact
    bool timeOfImpact_ = false;  // this substep's time-of-impact phase has begun
    static constexpr std::size_t kNone = ~std::size_t(0);
    std::size_t firstSummed_ = kNone;
    std::vector<SolvedImpulses> solvedImpulses_;
    Effects effects_;
    MaterialTable materials_;
    float restitutionThreshold_ = 1.0f;
    int basementBodies_ = 0;
};

}  // namespace anyphys::box2d

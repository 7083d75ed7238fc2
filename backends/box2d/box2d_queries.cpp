// Ray casts and overlap queries. Both answer about the user's geometry (each fixture's exact
// outline, without the contact skin). A query that leaves the XY plane never gets here: the layer
// refuses it in every planar world (World::raycast, World::overlap), whichever the backend.
#include <algorithm>

#include "box2d_world.hpp"

namespace anyphys::box2d {
namespace {

bool skipped(const b2Fixture* f, std::uint32_t mask) { return f->IsSensor() || (fixtureInfo(f).layer & mask) == 0; }

// Visits the broad phase's proxies along the ray and casts against each fixture's exact shape
// (b2World::RayCast would cast against the skinned collision shapes).
class RayCollector {
public:
    RayCollector(const b2BroadPhase& bp, const Vec3& origin, const Vec3& direction, double maxDistance, bool closestOnly,
                 std::uint32_t mask)
        : broadPhase_(bp), origin_(origin), direction_(direction), maxDistance_(maxDistance), closestOnly_(closestOnly), mask_(mask) {}

    float RayCastCallback(const b2RayCastInput& input, int32 proxyId) {
        const auto* proxy = static_cast<const b2FixtureProxy*>(broadPhase_.GetUserData(proxyId));
        const b2Fixture* f = proxy->fixture;
        // A ray meets a plane's surface, its edges; the basements lie under them.
        if (skipped(f, mask_) || fixtureInfo(f).piece.basement) return input.maxFraction;
        // A plane is solid below its surface: a ray starting there does not hit it, as a ray
        // starting inside a circle or polygon does not (Box2D's edges answer from either side).
        if (startsBelow(fixtureInfo(f).piece, f->GetBody()->GetTransform())) return input.maxFraction;
        b2RayCastOutput out;
        if (!fixtureInfo(f).piece.exact->RayCast(&out, input, f->GetBody()->GetTransform(), 0)) return input.maxFraction;
        const double distance = static_cast<double>(out.fraction) * maxDistance_;
        PeerRayHit hit{bodyOf(f).userData(), origin_ + distance * direction_, fromB2(out.normal), distance};
        if (!closestOnly_) {
            hits.push_back(hit);
            shapes.push_back(fixtureInfo(f).shape);
            return input.maxFraction;
        }
        hits.assign(1, hit);
        return out.fraction;  // only nearer hits matter from now on
    }

    /// One shape may be several fixtures (a capsule's three pieces, a plane's run of edges), each
    /// answering the ray: keeps each shape's nearest hit, nearest first.
    void keepNearestPerShape() {
        std::vector<std::size_t> order(hits.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
            if (hits[x].body != hits[y].body) return hits[x].body < hits[y].body;
            if (shapes[x] != shapes[y]) return shapes[x] < shapes[y];
            return hits[x].distance < hits[y].distance;
        });
        std::vector<PeerRayHit> kept;
        for (std::size_t k = 0; k < order.size(); ++k) {
            const std::size_t i = order[k], before = k > 0 ? order[k - 1] : i;
            if (k == 0 || hits[i].body != hits[before].body || shapes[i] != shapes[before]) kept.push_back(hits[i]);
        }
        hits.swap(kept);
    }

    std::vector<PeerRayHit> hits;
    std::vector<std::uint32_t> shapes;  // per hit, its fixture's shape (all hits only)

private:
    bool startsBelow(const Piece& piece, const b2Transform& xf) const {
        if (!piece.plane) return false;
        const b2Vec2 n = piece.plane->worldNormal(xf), point = piece.plane->worldPoint(xf);
        return n.x * (origin_.x() - point.x) + n.y * (origin_.y() - point.y) < 0.0;
    }

    const b2BroadPhase& broadPhase_;
    Vec3 origin_, direction_;
    double maxDistance_;
    bool closestOnly_;
    std::uint32_t mask_;
};

class OverlapCollector final : public b2QueryCallback {
public:
    OverlapCollector(const Piece& query, const b2Transform& xf, std::uint32_t mask, std::vector<std::uint64_t>& found)
        : query_(query), xf_(xf), mask_(mask), found_(found) {}

    bool ReportFixture(b2Fixture* f) override {
        if (skipped(f, mask_)) return true;
        const Piece& piece = fixtureInfo(f).piece;
        const b2Transform& bodyXf = f->GetBody()->GetTransform();
        bool hit;
        // A plane is a half-plane, not its edge: anything reaching below it overlaps. The broad
        // phase finds a shape deep under a collision plane through the basements' boxes.
        if (piece.plane) {
            const b2Vec2 n = piece.plane->worldNormal(bodyXf);
            hit = lowest(*query_.exact, xf_, n) < piece.plane->offset + b2Dot(n, bodyXf.p);
        } else {
            hit = b2TestOverlap(query_.exact.get(), 0, piece.exact.get(), 0, xf_, bodyXf);
        }
        if (hit) found_.push_back(bodyOf(f).userData());
        return true;
    }

private:
    const Piece& query_;
    b2Transform xf_;
    std::uint32_t mask_;
    std::vector<std::uint64_t>& found_;
};

}  // namespace

std::vector<PeerRayHit> Box2dWorld::raycast(const Vec3& origin, const Vec3& direction, double maxDistance, bool closestOnly,
                                            std::uint32_t mask) {
    // Box2D worlds are planar: World::raycast has refused a ray that leaves the plane.
    if (maxDistance <= 0.0) return {};  // Box2D casts segments of non-zero length
    const Vec3 dir(direction.x(), direction.y(), 0.0);
    b2RayCastInput input;
    input.p1 = toB2(origin);
    input.p2 = toB2(origin + maxDistance * dir);
    input.maxFraction = 1.0f;
    const b2BroadPhase& bp = world_->GetContactManager().m_broadPhase;
    RayCollector collector(bp, Vec3(origin.x(), origin.y(), 0.0), dir, maxDistance, closestOnly, mask);
    bp.RayCast(&collector, input);
    if (!closestOnly) collector.keepNearestPerShape();
    sortAndMergeSeamHits(collector.hits);  // nearest first; a compound's seam once
    return std::move(collector.hits);
}

std::vector<std::uint64_t> Box2dWorld::overlap(const std::vector<PeerShape>& shapes, const Transform& pose, std::uint32_t mask) {
    // World::overlap has refused a pose out of the plane or turned about another axis.
    double angle = 0.0;
    const Embedding embedding = Embedding::of(pose, angle);
    const b2Transform xf(toB2(pose.position), b2Rot(static_cast<float>(angle)));
    const b2Vec2 originInQuery = b2MulT(xf, b2Vec2(0.0f, 0.0f));
    std::vector<std::uint64_t> found;
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const std::string path = shapes.size() > 1 ? "World.overlap.shape.shapes[" + std::to_string(i) + "]" : "World.overlap.shape";
        for (const Piece& piece : makePieces(shapes[i], embedding.toBody(shapes[i].local), originInQuery, path)) {
            b2AABB box;
            piece.exact->ComputeAABB(&box, xf, 0);
            OverlapCollector collector(piece, xf, mask, found);
            world_->QueryAABB(&collector, box);
        }
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
}

}  // namespace anyphys::box2d

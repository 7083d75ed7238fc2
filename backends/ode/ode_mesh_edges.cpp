#include "ode_mesh_edges.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "ode_math.hpp"
#include "ode_near_pairs.hpp"
#include "ode_shapes.hpp"

namespace anyphys::ode {
namespace {

// An edge folding outwards by less than this is flat: a flat floor's rounding stays inside it,
// while any fold a body could catch on (a ridge, a step, a cube's edge) stays real.
const double kFlatEdgeSine = std::sin(1.0 * std::numbers::pi / 180.0);
// A contact normal within this of its triangle's face normal is a face contact: left as ODE gave it.
const double kOnFaceCosine = std::cos(0.5 * std::numbers::pi / 180.0);
// Below this the normal's tilt from the face no longer widens the band kept around real edges.
const double kLeastTiltSine = std::sin(0.5 * std::numbers::pi / 180.0);
// m: the band kept around a real edge or corner is at least this wide (rounding in ODE's clipping).
constexpr double kEdgeBand = 1e-4;
// Room for ODE's contacts of a shape against a mesh, before they are culled to a pair's
// (kMaxContactsPerPair): a box face over six triangles gives about twenty clipped points.
constexpr int kMeshContacts = 24;
// m: boxes and capsules meet a mesh grown by this (their depths measured back to the true surface).
constexpr double kSkin = 1e-4;
// m: the ray measuring a corrected depth starts this far beyond the shape's bounding sphere.
constexpr double kRayClearance = 1e-3;

// One triangle's use of an edge: from its corner `corner` to the next.
struct EdgeUse {
    std::uint32_t low, high;  // the edge's vertex indices, sorted: equal for every use of one edge
    int triangle, corner;
};

double distanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

}  // namespace

MeshEdges::MeshEdges(const std::vector<Vec3>& vertices, const std::vector<std::uint32_t>& indices) {
    const std::size_t triangles = indices.size() / 3;
    real_.assign(triangles, 0);
    const auto vertex = [&](int t, int k) -> const Vec3& { return vertices[indices[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(k % 3)]]; };
    const auto index = [&](int t, int k) { return indices[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(k % 3)]; };
    std::vector<EdgeUse> uses;
    uses.reserve(indices.size());
    for (int t = 0; t < static_cast<int>(triangles); ++t)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = index(t, k), b = index(t, k + 1);
            uses.push_back({std::min(a, b), std::max(a, b), t, k});
        }
    // Sorted by edge, then triangle: each edge's uses side by side, in an order that depends on the mesh only.
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
        return std::tie(x.low, x.high, x.triangle, x.corner) < std::tie(y.low, y.high, y.triangle, y.corner);
    });
    // Whether the edge `e` of one triangle, shared with `f` of another, is flat or folds inwards:
    // the other triangle's far corner lies no lower than kFlatEdgeSine of its distance from the
    // edge below the first triangle's plane.
    const auto internal = [&](const EdgeUse& e, const EdgeUse& f) {
        if (e.triangle == f.triangle || index(e.triangle, e.corner) == index(f.triangle, f.corner))
            return false;  // a triangle folded onto itself, or two wound against each other
        const Vec3& a = vertex(e.triangle, e.corner);
        const Vec3 along = vertex(e.triangle, e.corner + 1) - a;
        const Vec3 normal = along.cross(vertex(e.triangle, e.corner + 2) - a);
        const Vec3 far = vertex(f.triangle, f.corner + 2) - a;
        const Vec3 across = far - (far.dot(along) / along.squaredNorm()) * along;  // from the edge, square to it
        if (!(normal.norm() > 0.0) || !(across.norm() > 0.0)) return false;  // degenerate: keep it real
        return normal.normalized().dot(across) >= -kFlatEdgeSine * across.norm();
    };
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i + 1;
        while (j < uses.size() && uses[j].low == uses[i].low && uses[j].high == uses[i].high) ++j;
        if (j - i == 2 && internal(uses[i], uses[i + 1])) {
            hasInternal_ = true;
        } else {  // a border, a seam of three or more triangles, or a fold outwards
            for (std::size_t k = i; k < j; ++k)
                real_[static_cast<std::size_t>(uses[k].triangle)] |= static_cast<std::uint8_t>(1u << uses[k].corner);
        }
        i = j;
    }
    // A corner ending a real edge is real in every triangle around it.
    std::vector<bool> realVertex(vertices.size(), false);
    for (int t = 0; t < static_cast<int>(triangles); ++t)
        for (int k = 0; k < 3; ++k)
            if (real_[static_cast<std::size_t>(t)] & (1u << k)) realVertex[index(t, k)] = realVertex[index(t, k + 1)] = true;
    for (int t = 0; t < static_cast<int>(triangles); ++t)
        for (int k = 0; k < 3; ++k)
            if (realVertex[index(t, k)]) real_[static_cast<std::size_t>(t)] |= static_cast<std::uint8_t>(1u << (3 + k));
}

int collideWithMesh(dGeomID o1, dGeomID o2, const OdeShape& shape, const OdeShape& mesh, NearProbe& probe, dContact* out,
                    int capacity) {
    const MeshEdges* edges = mesh.meshEdges();
    // Boxes and capsules: ODE's colliders for them test each triangle alone. Its sphere-trimesh
    // collider keeps a sphere on the face already (a ball slid over the floor above exactly).
    if ((shape.type() != ShapeType::Box && shape.type() != ShapeType::Capsule) || !edges)
        return dCollide(o1, o2, capacity, &out[0].geom, sizeof(dContact));
    // The shape grown by a skin, its depths measured back to the true surface: a face resting
    // on the mesh at depth 0, where ODE's collider keeps a corner or not by rounding, keeps them all.
    std::array<dContactGeom, kMeshContacts> found;
    const int count = probe.collide(shape, mesh, kSkin, found.data(), kMeshContacts);
    const Vec3 center = toVec3(dGeomGetPosition(o1));
    dReal box[6];
    dGeomGetAABB(o1, box);
    const double reach = 0.5 * Vec3(box[1] - box[0], box[3] - box[2], box[5] - box[4]).norm();

    // Whether contact `g` stays (false: dropped), corrected where it lies away from real features.
    const auto correct = [&](dContactGeom& g) {
        const Vec3 p = toVec3(g.pos), out = toVec3(g.normal);  // the normal points into o1: out of the mesh
        if (!p.allFinite() || !out.allFinite() || g.side2 < 0 || g.side2 >= edges->triangleCount()) return true;
        if (!edges->hasInternalEdges()) return true;
        dVector3 v[3];
        dGeomTriMeshGetTriangle(o2, g.side2, &v[0], &v[1], &v[2]);
        const std::array<Vec3, 3> corner{toVec3(v[0]), toVec3(v[1]), toVec3(v[2])};
        const Vec3 area = (corner[1] - corner[0]).cross(corner[2] - corner[0]);
        if (!(area.norm() > 0.0)) return true;
        const Vec3 face = area.normalized();
        if (out.dot(face) >= kOnFaceCosine) {  // the face's but for ODE's rounding: made exactly the face's
            for (int k = 0; k < 3; ++k) g.normal[k] = face[k];
            return true;
        }
        const double above = (center - corner[0]).dot(face);  // the shape's centre over the face
        if (!(above > 0.0)) return true;  // behind the triangle: not a body resting on it
        const Vec3 onFace = p - (p - corner[0]).dot(face) * face;
        // Kept as ODE gave it near a real edge or corner, which a normal tilted off the face may
        // meet. The band: how far from an edge a body that overlaps it by the contact's depth
        // along the tilted normal reaches over the face (depth / sin(tilt)).
        const double tiltSine = std::max(out.cross(face).norm(), kLeastTiltSine);
        const double band = std::max(g.depth, 0.0) / tiltSine + kEdgeBand;
        const std::uint8_t real = edges->realFeatures(g.side2);
        for (std::size_t k = 0; k < 3; ++k) {
            if ((real & (1u << k)) && distanceToSegment(onFace, corner[k], corner[(k + 1) % 3]) <= band) return true;
            if ((real & (1u << (3 + k))) && (onFace - corner[k]).norm() <= band) return true;
        }
        // Onto the face: cast a ray up along the face normal from below the shape's bounding
        // sphere to the face; where it enters the shape is the contact, and its depth how far
        // below the face that lies. A shape not below the face there does not touch it.
        const double start = above - reach - kRayClearance;  // height of the ray's origin over the face
        if (!(start < 0.0)) return false;
        const Vec3 origin = onFace + start * face;
        const dGeomID ray = mesh.probeRay();
        dGeomRaySet(ray, origin.x(), origin.y(), origin.z(), face.x(), face.y(), face.z());
        dGeomRaySetLength(ray, -start);
        dContactGeom hit;
        if (dCollide(ray, o1, 1, &hit, sizeof(dContactGeom)) < 1) return false;
        const double depth = -(start + hit.depth);
        if (!(depth > 0.0)) return false;
        const Vec3 point = origin + hit.depth * face;
        for (int k = 0; k < 3; ++k) {
            g.pos[k] = point[k];
            g.normal[k] = face[k];
        }
        g.depth = depth;
        return true;
    };

    int kept = 0;
    for (int i = 0; i < count; ++i) {
        if (!correct(found[static_cast<std::size_t>(i)])) continue;
        found[static_cast<std::size_t>(kept++)] = found[static_cast<std::size_t>(i)];
    }
    // Only a pair that touches: a shape held within the skin above a flat mesh would hover there
    // until ODE's broad phase, whose bounds do not grow, missed the pair and it fell a whole step
    // (0.16 m/s) onto it.
    bool touching = false;
    for (int i = 0; i < kept; ++i) touching = touching || found[static_cast<std::size_t>(i)].depth >= 0.0;
    if (!touching) return 0;

    // The most spread-out `capacity` points: the deepest, then each time the one farthest from
    // those taken, measured across the deepest one's normal (as ODE culls a box-box manifold to
    // spread-out points). A box on a floor of triangles keeps its corners.
    int deepest = 0;
    for (int i = 1; i < kept; ++i)
        if (found[static_cast<std::size_t>(i)].depth > found[static_cast<std::size_t>(deepest)].depth) deepest = i;
    const Vec3 normal = toVec3(found[static_cast<std::size_t>(deepest)].normal);
    std::array<Vec3, kMeshContacts> across;
    for (int i = 0; i < kept; ++i) {
        const Vec3 p = toVec3(found[static_cast<std::size_t>(i)].pos);
        across[static_cast<std::size_t>(i)] = p - normal.dot(p) * normal;
    }
    std::array<bool, kMeshContacts> taken{};
    std::array<double, kMeshContacts> nearest;
    nearest.fill(std::numeric_limits<double>::infinity());
    int n = 0;
    for (int next = deepest; next >= 0 && n < capacity;) {
        taken[static_cast<std::size_t>(next)] = true;
        dContactGeom& g = out[n++].geom;
        g = found[static_cast<std::size_t>(next)];
        g.g1 = o1;  // not the grown scratch geom
        g.g2 = o2;
        const Vec3 at = across[static_cast<std::size_t>(next)];
        next = -1;
        double farthest = 0.0;
        for (int i = 0; i < kept; ++i) {
            auto& d = nearest[static_cast<std::size_t>(i)];
            d = std::min(d, (across[static_cast<std::size_t>(i)] - at).norm());
            if (!taken[static_cast<std::size_t>(i)] && d > farthest) {
                farthest = d;
                next = i;
            }
        }
    }
    return n;
}

}  // namespace anyphys::ode

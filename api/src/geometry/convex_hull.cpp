// Quickhull (Barber, Dobkin, Huhdanpaa 1996) on triangles, then coplanar triangles merged into
// polygon faces, then mass properties by decomposition into tetrahedra; a hull that fails the
// soundness check is built again at a coarser tolerance.
#include "convex_hull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>

#include "anyphys/error.hpp"

namespace anyphys {
namespace {

// Distances within kBuildTolerance x extent of a plane count as on it: such points never become
// hull vertices. Triangles within kMergeTolerance x extent of a common plane are one face. A hull
// that comes out unsound is built again with both a hundred and then ten thousand times coarser.
constexpr double kBuildTolerance = 1e-10;
constexpr double kMergeTolerance = 1e-9;

[[noreturn]] void throwDegenerate(std::size_t count) {
    throw Error::invalid("ShapeDef.points", std::to_string(count) + " points",
                         "must span a volume (at least 4 points, not all in one plane)");
}

struct Triangle {
    std::array<int, 3> v{};    // point indices, counter-clockwise seen from outside
    std::array<int, 3> adj{};  // adj[k]: the triangle across edge v[k] -> v[k+1]
    Vec3 normal = Vec3::Zero();
    double offset = 0.0;
    std::vector<int> outside;  // points above this triangle that may still extend the hull
    bool alive = true;
};

class QuickHull {
public:
    QuickHull(const std::vector<Vec3>& points, double eps) : p_(points), eps_(eps), mark_(0) {}

    void run() {
        buildSimplex();
        std::vector<int> work;
        for (int f = 0; f < static_cast<int>(tris_.size()); ++f)
            if (!tris_[f].outside.empty()) work.push_back(f);
        while (!work.empty()) {
            const int f = work.back();
            work.pop_back();
            if (!tris_[f].alive || tris_[f].outside.empty()) continue;
            addFarthestPoint(f, work);
        }
    }

    const std::vector<Triangle>& triangles() const { return tris_; }

private:
    struct HorizonEdge {
        int a, b;      // directed as in the visible triangle that is removed
        int neighbor;  // the triangle that stays
    };

    double distance(int tri, int point) const { return tris_[tri].normal.dot(p_[point]) - tris_[tri].offset; }

    int addTriangle(int a, int b, int c) {
        Triangle t;
        t.v = {a, b, c};
        const Vec3 n = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
        const double len = n.norm();
        t.normal = len > 0 ? Vec3(n / len) : Vec3::Zero();
        t.offset = t.normal.dot((p_[a] + p_[b] + p_[c]) / 3.0);
        tris_.push_back(std::move(t));
        return static_cast<int>(tris_.size()) - 1;
    }

    // The largest tetrahedron we can cheaply find: extreme points along the axes, the point
    // farthest from their line, the point farthest from that plane.
    void buildSimplex() {
        const int n = static_cast<int>(p_.size());
        std::array<int, 6> extremes{};
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < n; ++i) {
                if (p_[i][k] < p_[extremes[2 * k]][k]) extremes[2 * k] = i;
                if (p_[i][k] > p_[extremes[2 * k + 1]][k]) extremes[2 * k + 1] = i;
            }
        int i0 = 0, i1 = 0;
        double best = 0;
        for (int a = 0; a < 6; ++a)
            for (int b = a + 1; b < 6; ++b)
                if (const double d = (p_[extremes[a]] - p_[extremes[b]]).norm(); d > best) {
                    best = d;
                    i0 = extremes[a];
                    i1 = extremes[b];
                }
        if (best <= eps_) throwDegenerate(p_.size());

        const Vec3 axis = (p_[i1] - p_[i0]).normalized();
        int i2 = -1;
        best = eps_;
        for (int i = 0; i < n; ++i)
            if (const double d = axis.cross(p_[i] - p_[i0]).norm(); d > best) {
                best = d;
                i2 = i;
            }
        if (i2 < 0) throwDegenerate(p_.size());

        const Vec3 normal = (p_[i1] - p_[i0]).cross(p_[i2] - p_[i0]).normalized();
        int i3 = -1;
        best = eps_;
        for (int i = 0; i < n; ++i)
            if (const double d = std::abs(normal.dot(p_[i] - p_[i0])); d > best) {
                best = d;
                i3 = i;
            }
        if (i3 < 0) throwDegenerate(p_.size());

        // Base (a, b, c) faces away from d; each side traverses a base edge the other way.
        if (normal.dot(p_[i3] - p_[i0]) > 0) std::swap(i1, i2);
        const int a = i0, b = i1, c = i2, d = i3;
        addTriangle(a, b, c);
        addTriangle(b, a, d);
        addTriangle(c, b, d);
        addTriangle(a, c, d);
        for (int f = 0; f < 4; ++f)
            for (int k = 0; k < 3; ++k) tris_[f].adj[k] = findNeighbor(f, k, 4);

        for (int i = 0; i < n; ++i) {
            if (i == a || i == b || i == c || i == d) continue;
            assign(i, 0, 4);
        }
    }

    // The triangle among the first `count` that traverses edge k of triangle f the other way.
    int findNeighbor(int f, int k, int count) const {
        const int from = tris_[f].v[k], to = tris_[f].v[(k + 1) % 3];
        for (int g = 0; g < count; ++g)
            for (int j = 0; j < 3; ++j)
                if (g != f && tris_[g].v[j] == to && tris_[g].v[(j + 1) % 3] == from) return g;
        return -1;
    }

    // Puts the point in the outside set of the triangle in [first, end) it is farthest above;
    // returns that triangle, or -1 if the point is above none of them.
    int assign(int point, int first, int end) {
        int best = -1;
        double bestDistance = eps_;
        for (int f = first; f < end; ++f) {
            if (!tris_[f].alive) continue;
            if (const double d = distance(f, point); d > bestDistance) {
                bestDistance = d;
                best = f;
            }
        }
        if (best >= 0) tris_[best].outside.push_back(point);
        return best;
    }

    void addFarthestPoint(int start, std::vector<int>& work) {
        std::vector<int>& candidates = tris_[start].outside;
        const auto farthest = std::max_element(candidates.begin(), candidates.end(),
                                               [&](int x, int y) { return distance(start, x) < distance(start, y); });
        const int eye = *farthest;

        // Triangles the eye sees, reached from `start` across shared edges.
        ++mark_;
        if (visibleMark_.size() < tris_.size()) visibleMark_.resize(tris_.size(), 0);
        std::vector<int> visible{start}, stack{start};
        std::vector<HorizonEdge> horizon;
        visibleMark_[start] = mark_;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k) {
                const int g = tris_[f].adj[k];
                if (visibleMark_[g] == mark_) continue;
                if (distance(g, eye) > eps_) {
                    visibleMark_[g] = mark_;
                    visible.push_back(g);
                    stack.push_back(g);
                } else {
                    horizon.push_back({tris_[f].v[k], tris_[f].v[(k + 1) % 3], g});
                }
            }
        }

        std::vector<int> cycle = orderHorizon(horizon);
        if (cycle.empty()) {
            // Rounding made the visible region not a disk: the eye is within noise of the
            // hull, so leaving it out changes the hull by no more than the tolerance.
            candidates.erase(farthest);
            work.push_back(start);
            return;
        }

        std::vector<int> orphans;
        for (int f : visible) {
            for (int q : tris_[f].outside)
                if (q != eye) orphans.push_back(q);
            tris_[f].outside.clear();
            tris_[f].alive = false;
        }

        const int first = static_cast<int>(tris_.size());
        const int count = static_cast<int>(cycle.size());
        for (int i = 0; i < count; ++i) {
            const HorizonEdge& e = horizon[cycle[i]];
            const int t = addTriangle(e.a, e.b, eye);
            tris_[t].adj[0] = e.neighbor;
            for (int k = 0; k < 3; ++k)
                if (tris_[e.neighbor].v[k] == e.b && tris_[e.neighbor].v[(k + 1) % 3] == e.a) tris_[e.neighbor].adj[k] = t;
        }
        // Consecutive horizon edges share a vertex: their triangles share the edge to the eye.
        for (int i = 0; i < count; ++i) {
            const int t = first + i, next = first + (i + 1) % count;
            tris_[t].adj[1] = next;
            tris_[next].adj[2] = t;
        }
        visibleMark_.resize(tris_.size(), 0);

        const int end = static_cast<int>(tris_.size());
        for (int q : orphans) {
            // New triangles first; the fallback over the older ones keeps every point that is
            // still outside, whatever rounding did to the visible region. A point above none
            // is inside the hull for good.
            if (assign(q, first, end) < 0)
                if (const int f = assign(q, 0, first); f >= 0) work.push_back(f);
        }
        for (int f = first; f < end; ++f)
            if (!tris_[f].outside.empty()) work.push_back(f);
    }

    // Indices of `edges` in loop order, or empty if they do not form one simple loop.
    std::vector<int> orderHorizon(const std::vector<HorizonEdge>& edges) {
        if (edges.size() < 3) return {};
        // startOf_ is all -1 between calls: only the entries of this horizon are set, and reset
        // on the way out (a fresh array per point made a hull of n points cost n^2).
        startOf_.resize(p_.size(), -1);
        std::vector<int> cycle;
        bool simple = true;
        for (int i = 0; i < static_cast<int>(edges.size()) && simple; ++i) {
            simple = startOf_[edges[i].a] < 0;
            if (simple) startOf_[edges[i].a] = i;
        }
        if (simple) {
            int e = 0;
            do {
                cycle.push_back(e);
                e = startOf_[edges[e].b];
            } while (e >= 0 && e != 0 && cycle.size() <= edges.size());
            simple = e == 0 && cycle.size() == edges.size();
        }
        for (const HorizonEdge& edge : edges) startOf_[edge.a] = -1;
        if (!simple) cycle.clear();
        return cycle;
    }

    const std::vector<Vec3>& p_;
    double eps_;
    std::vector<Triangle> tris_;
    std::vector<int> visibleMark_;
    std::vector<int> startOf_;  // orderHorizon's scratch: the horizon edge leaving each point
    int mark_;
};

// ---- faces: coplanar triangles merged into polygons ----

// Groups of live triangles lying on one plane (within tol of the plane of the group's first
// triangle, so slightly curved surfaces do not chain into one bent face). A triangle facing the
// other way joins too when all its corners are on the plane: rounding can fold triangles over a
// face where a point within the tolerance was taken as a vertex, and the group's outer boundary
// is then the face without the fold.
std::vector<std::vector<int>> coplanarGroups(const std::vector<Triangle>& tris, const std::vector<Vec3>& p, double tol,
                                             std::vector<int>& groupOf) {
    groupOf.assign(tris.size(), -1);
    std::vector<std::vector<int>> groups;
    for (int seed = 0; seed < static_cast<int>(tris.size()); ++seed) {
        if (!tris[seed].alive || groupOf[seed] >= 0) continue;
        const int g = static_cast<int>(groups.size());
        groups.push_back({seed});
        groupOf[seed] = g;
        const Vec3& n = tris[seed].normal;
        const double d = tris[seed].offset;
        for (std::size_t i = 0; i < groups[g].size(); ++i) {
            for (int h : tris[groups[g][i]].adj) {
                if (groupOf[h] >= 0) continue;
                const bool onPlane = std::all_of(tris[h].v.begin(), tris[h].v.end(),
                                                 [&](int v) { return std::abs(n.dot(p[v]) - d) <= tol; });
                if (!onPlane) continue;
                groupOf[h] = g;
                groups[g].push_back(h);
            }
        }
    }
    return groups;
}

// The boundary of a group of triangles as one vertex loop, or empty if it is not one loop.
std::vector<int> boundaryLoop(const std::vector<Triangle>& tris, const std::vector<int>& group, const std::vector<int>& groupOf) {
    const int g = groupOf[group.front()];
    // The group's outer edges (from, to), sorted by `from` to walk them: a handful per face, so
    // no array over all the points (one per face made a hull of n points cost n^2).
    std::vector<std::pair<int, int>> edges;
    for (int t : group)
        for (int k = 0; k < 3; ++k)
            if (groupOf[tris[t].adj[k]] != g) edges.emplace_back(tris[t].v[k], tris[t].v[(k + 1) % 3]);
    if (edges.empty()) return {};
    const int start = edges.back().first;  // the walk starts where it always did: same vertex order
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 1; i < edges.size(); ++i)
        if (edges[i].first == edges[i - 1].first) return {};  // two edges leave one vertex: not one loop
    const auto next = [&](int from) {
        const auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(from, std::numeric_limits<int>::min()));
        return it != edges.end() && it->first == from ? it->second : -1;
    };
    std::vector<int> loop;
    int v = start;
    do {
        loop.push_back(v);
        v = next(v);
        if (v < 0 || loop.size() > edges.size()) return {};
    } while (v != start);
    if (loop.size() != edges.size()) return {};
    return loop;
}

// The loop turned to start at its smallest vertex: equal for two loops that walk the same
// vertices in the same direction.
std::vector<int> canonical(std::vector<int> loop) {
    std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    return loop;
}

// Drops pairs of faces that are one flat polygon seen from both sides: quickhull can leave such
// a flap where a point within the tolerance of a face was taken as a vertex. It encloses nothing,
// and without it the faces around its rim pair their edges with each other. Loops are looked up
// by their canonical form, so a hull of many faces is not compared pair by pair.
/// True if it dropped any.
bool removeFlaps(std::vector<std::vector<int>>& loops) {
    std::map<std::vector<int>, std::size_t> loopIndex;
    for (std::size_t i = 0; i < loops.size(); ++i) loopIndex.emplace(canonical(loops[i]), i);
    for (std::size_t i = 0; i < loops.size(); ++i) {
        const auto twin = loopIndex.find(canonical({loops[i].rbegin(), loops[i].rend()}));
        if (twin == loopIndex.end() || twin->second == i) continue;
        const std::size_t j = twin->second;
        loops.erase(loops.begin() + static_cast<std::ptrdiff_t>(std::max(i, j)));
        loops.erase(loops.begin() + static_cast<std::ptrdiff_t>(std::min(i, j)));
        return true;
    }
    return false;
}

// Whether the vertex at `i` of `loop` lies within tol of the straight line through its neighbours.
bool onLineOfNeighbours(const std::vector<int>& loop, std::size_t i, const std::vector<Vec3>& p, double tol) {
    const Vec3& u = p[loop[(i + loop.size() - 1) % loop.size()]];
    const Vec3& v = p[loop[i]];
    const Vec3& w = p[loop[(i + 1) % loop.size()]];
    const double base = (w - u).norm();
    return base > 0 && (v - u).cross(w - u).norm() / base <= tol;
}

// Drops the vertices that are not corners of the polyhedron: a vertex of exactly two faces that
// lies on the straight line through its neighbours in both sits on the edge between them. It
// leaves both loops at once, and one vertex goes at a time (each removal moves its neighbours'
// lines), so every edge stays walked once each way. Deciding per loop instead let the two faces
// of an edge drop different vertices of a nearly straight chain, or one face drop a vertex other
// faces keep: edges with a face on one side only (input jittered by 1e-9 of its size gave 185
// such hulls in 3 000).
void removeEdgeVertices(std::vector<std::vector<int>>& loops, const std::vector<Vec3>& p, double tol) {
    struct Place {
        std::size_t loop, index;
    };
    std::vector<std::vector<Place>> places(p.size());
    for (bool removed = true; removed;) {
        removed = false;
        for (std::vector<Place>& at : places) at.clear();
        for (std::size_t l = 0; l < loops.size(); ++l)
            for (std::size_t i = 0; i < loops[l].size(); ++i) places[static_cast<std::size_t>(loops[l][i])].push_back({l, i});
        for (const std::vector<Place>& at : places) {
            if (at.size() != 2) continue;
            const bool onEdge = std::all_of(at.begin(), at.end(), [&](const Place& pl) {
                return loops[pl.loop].size() > 3 && onLineOfNeighbours(loops[pl.loop], pl.index, p, tol);
            });
            if (!onEdge) continue;
            for (const Place& pl : at) loops[pl.loop].erase(loops[pl.loop].begin() + static_cast<std::ptrdiff_t>(pl.index));
            removed = true;
            break;  // the places are stale now
        }
    }
}

// Unit normal of a planar polygon (Newell's method: robust for nearly collinear corners).
Vec3 polygonNormal(const std::vector<int>& loop, const std::vector<Vec3>& p) {
    Vec3 c = Vec3::Zero();
    for (int v : loop) c += p[v];
    c /= static_cast<double>(loop.size());
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < loop.size(); ++i) n += (p[loop[i]] - c).cross(p[loop[(i + 1) % loop.size()]] - c);
    return n.normalized();
}

// ---- mass properties ----

// Volume, centroid and inertia per unit mass: each face fanned into tetrahedra with an interior
// point o. A tetrahedron (0, a, b, c) has volume V = a.(b x c) / 6 and second moment
// integral(x x^T) = V / 20 (a a^T + b b^T + c c^T + s s^T) with s = a + b + c.
void computeMassProperties(HullData& h) {
    Vec3 o = Vec3::Zero();
    for (const Vec3& v : h.vertices) o += v;
    o /= static_cast<double>(h.vertices.size());

    double volume = 0;
    Vec3 moment = Vec3::Zero();
    Mat3 second = Mat3::Zero();
    for (const std::vector<int>& face : h.faces) {
        const Vec3 a = h.vertices[face[0]] - o;
        for (std::size_t i = 1; i + 1 < face.size(); ++i) {
            const Vec3 b = h.vertices[face[i]] - o, c = h.vertices[face[i + 1]] - o;
            const double v = a.dot(b.cross(c)) / 6.0;
            const Vec3 s = a + b + c;
            volume += v;
            moment += v * s / 4.0;
            second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
        }
    }
    const Vec3 r = moment / volume;  // centroid relative to o
    const Mat3 central = second - volume * r * r.transpose();
    h.volume = volume;
    h.centroid = o + r;
    h.inertiaPerMass = (central.trace() * Mat3::Identity() - central) / volume;
}

// Each edge once (lower vertex first) with the faces on its left and right: the face walking it
// from its first vertex, and the face walking it back. Collision's edge tests use these.
void computeEdges(HullData& h) {
    std::map<std::pair<int, int>, int> index;
    for (const std::vector<int>& loop : h.faces)
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const int a = loop[i], b = loop[(i + 1) % loop.size()];
            if (a < b) {
                index[{a, b}] = static_cast<int>(h.edges.size());
                h.edges.push_back({a, b});
            }
        }
    h.edgeFaces.assign(h.edges.size(), {-1, -1});
    for (int f = 0; f < static_cast<int>(h.faces.size()); ++f) {
        const std::vector<int>& loop = h.faces[f];
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const int a = loop[i], b = loop[(i + 1) % loop.size()];
            const auto it = index.find({std::min(a, b), std::max(a, b)});
            if (it != index.end()) h.edgeFaces[it->second][a < b ? 0 : 1] = f;
        }
    }
    // An edge only one face walks: no valid topology to hand on (collision then derives and checks its own).
    for (const auto& faces : h.edgeFaces)
        if (faces[0] < 0 || faces[1] < 0) {
            h.edgeFaces.clear();
            return;
        }
}

// One quickhull at build tolerance `eps` (merging at `mergeTol`), faces merged and cleaned.
std::shared_ptr<HullData> hullAtTolerance(const std::vector<Vec3>& points, double eps, double mergeTol) {
    QuickHull quickHull(points, eps);
    quickHull.run();
    const std::vector<Triangle>& tris = quickHull.triangles();

    std::vector<int> groupOf;
    std::vector<std::vector<int>> loops;
    for (const std::vector<int>& group : coplanarGroups(tris, points, mergeTol, groupOf)) {
        std::vector<int> loop = boundaryLoop(tris, group, groupOf);
        if (loop.empty()) {  // not expected for a convex group; keep its triangles as they are
            for (int t : group) loops.push_back({tris[t].v.begin(), tris[t].v.end()});
            continue;
        }
        loops.push_back(std::move(loop));
    }
    // Dropping edge vertices can close a flap, and dropping a flap leaves edge vertices.
    do removeEdgeVertices(loops, points, mergeTol);
    while (removeFlaps(loops));

    // Keep only points that are corners of some face, renumbered in first-use order.
    auto hull = std::make_shared<HullData>();
    std::vector<int> index(points.size(), -1);
    for (std::vector<int>& loop : loops)
        for (int& v : loop) {
            if (index[v] < 0) {
                index[v] = static_cast<int>(hull->vertices.size());
                hull->vertices.push_back(points[v]);
            }
            v = index[v];
        }
    for (std::vector<int>& loop : loops) {
        const Vec3 n = polygonNormal(loop, hull->vertices);
        double offset = 0;
        for (int v : loop) offset += n.dot(hull->vertices[v]);
        hull->faceNormals.push_back(n);
        hull->faceOffsets.push_back(offset / static_cast<double>(loop.size()));
        hull->faces.push_back(std::move(loop));
    }
    computeMassProperties(*hull);
    computeEdges(*hull);
    return hull;
}

// The points in clusters of nearby ones with their bounding boxes, so that a plane can pass
// over a whole cluster with one test: a grid of about kPerCell points per occupied cell.
struct PointClusters {
    static constexpr double kPerCell = 32;
    std::vector<Vec3> points;  // sorted by cell
    struct Cluster {
        std::size_t first, end;
        Vec3 center, half;  // bounding box
    };
    std::vector<Cluster> clusters;

    PointClusters(const std::vector<Vec3>& input, const Vec3& lo, double extent) {
        const double cells = std::max(1.0, std::cbrt(static_cast<double>(input.size()) / kPerCell));
        const double cellSize = extent / cells;
        const auto cellOf = [&](const Vec3& q) {
            const auto at = [&](int k) {
                const double cell = std::floor((q[k] - lo[k]) / cellSize);  // 0 .. cells (validated input)
                return static_cast<std::uint64_t>(cell >= 0 ? std::min(cell, cells) : 0.0);
            };
            return (at(0) << 42) | (at(1) << 21) | at(2);
        };
        std::vector<std::pair<std::uint64_t, std::size_t>> keyed;
        keyed.reserve(input.size());
        for (std::size_t i = 0; i < input.size(); ++i) keyed.emplace_back(cellOf(input[i]), i);
        std::sort(keyed.begin(), keyed.end());
        for (std::size_t i = 0; i < keyed.size();) {
            std::size_t j = i;
            Vec3 min = input[keyed[i].second], max = min;
            for (; j < keyed.size() && keyed[j].first == keyed[i].first; ++j) {
                const Vec3& q = input[keyed[j].second];
                min = min.cwiseMin(q);
                max = max.cwiseMax(q);
                points.push_back(q);
            }
            clusters.push_back({i, j, (min + max) / 2, (max - min) / 2});
            i = j;
        }
    }

    /// Whether some point lies farther than `slack` above the plane n.x = offset.
    bool anyAbove(const Vec3& n, double offset, double slack) const {
        for (const Cluster& c : clusters) {
            if (n.dot(c.center) + n.cwiseAbs().dot(c.half) - offset <= slack) continue;
            for (std::size_t i = c.first; i < c.end; ++i)
                if (n.dot(points[i]) - offset > slack) return true;
        }
        return false;
    }
};

// Whether `hull` is a closed convex polyhedron holding every input point: positive volume, every
// edge walked once each way with Euler's V - E + F = 2, and no point farther than `slack` outside
// any face.
bool isSound(const HullData& hull, const PointClusters& points, double slack) {
    if (!(hull.volume > 0) || hull.edgeFaces.empty()) return false;
    const auto v = static_cast<long>(hull.vertices.size()), e = static_cast<long>(hull.edges.size()),
               f = static_cast<long>(hull.faces.size());
    if (v - e + f != 2) return false;
    for (std::size_t face = 0; face < hull.faces.size(); ++face)
        if (points.anyAbove(hull.faceNormals[face], hull.faceOffsets[face], slack)) return false;
    return true;
}

}  // namespace

std::shared_ptr<const HullData> buildConvexHull(const std::vector<Vec3>& points) {
    if (points.size() < 4) throwDegenerate(points.size());
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& q : points) {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    const double extent = (hi - lo).maxCoeff();
    const double magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    if (!(extent > 0)) throwDegenerate(points.size());
    // Points within the build tolerance of a face never become vertices, but a point that was
    // outside a face of the growing hull can end within the tolerance of the final one, and
    // rounding then leaves a fold or a cone of triangles through the solid: input points up to
    // the hull's size outside a face. A hull that fails isSound is built again at a coarser
    // tolerance, under which such points are on the face. Of 3 000 clouds jittered by 1e-4 to
    // 1e-13 of their size, 47 need the second tolerance and 1 the third (folds merged in
    // coplanarGroups; 81 without that); the coarsest result is kept whatever the check says.
    const PointClusters clusters(points, lo, extent);
    std::shared_ptr<HullData> hull;
    for (const double relative : {kBuildTolerance, 100 * kBuildTolerance, 1e4 * kBuildTolerance}) {
        // Relative to the size, plus rounding of coordinates far from the origin.
        const double eps = relative * extent + 16 * std::numeric_limits<double>::epsilon() * magnitude;
        const double mergeTol = std::max(kMergeTolerance / kBuildTolerance * relative * extent, 10 * eps);
        hull = hullAtTolerance(points, eps, mergeTol);
        if (isSound(*hull, clusters, 10 * mergeTol)) break;
    }
    if (!(hull->volume > 0)) throwDegenerate(points.size());
    return hull;
}

HullData makeBoxHull(const Vec3& halfExtents) {
    HullData h;
    for (int i = 0; i < 8; ++i)
        h.vertices.emplace_back((i & 1) ? halfExtents.x() : -halfExtents.x(), (i & 2) ? halfExtents.y() : -halfExtents.y(),
                                (i & 4) ? halfExtents.z() : -halfExtents.z());
    // Face 2k has normal +e_k, face 2k + 1 has -e_k; corners counter-clockwise from outside.
    h.faces = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
    for (int k = 0; k < 3; ++k) {
        const Vec3 axis = Vec3::Unit(k);
        h.faceNormals.push_back(axis);
        h.faceOffsets.push_back(halfExtents[k]);
        h.faceNormals.push_back(-axis);
        h.faceOffsets.push_back(halfExtents[k]);
    }
    const Vec3 sq = halfExtents.cwiseProduct(halfExtents);
    h.volume = 8.0 * halfExtents.prod();
    h.centroid = Vec3::Zero();
    h.inertiaPerMass = Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()).asDiagonal();
    h.inertiaPerMass /= 3.0;
    computeEdges(h);
    return h;
}

}  // namespace anyphys

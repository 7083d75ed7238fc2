#pragma once
// Broad phase: a dynamic AABB tree (surface-area heuristic, rotations to keep it balanced) over
// fattened bounds, and pair finding for proxies that moved. Cost is O(n log n) per step for n
// moving proxies, nothing for proxies at rest.
#include <cstdint>
#include <utility>
#include <vector>

#include "anyphys/task_system.hpp"
#include "collision/shape.hpp"
#include "function_ref.hpp"
#include "large_pages.hpp"
#include "per_worker_lists.hpp"

namespace anyphys::native {

/// Bounding-volume tree of boxes. Leaves go where they add the least surface area (branch and
/// bound over the whole tree), then AVL rotations on the way up keep the height logarithmic.
/// Nodes live in one pool with a free list; a proxy id is its leaf's index and stays valid
/// until destroyProxy.
class DynamicTree {
public:
    static constexpr int kNull = -1;

    int createProxy(const Aabb& fatAabb, std::uint64_t userData);
    void destroyProxy(int proxy);
    /// Re-inserts the proxy with a new fat box.
    void moveProxy(int proxy, const Aabb& fatAabb);
    const Aabb& fatAabb(int proxy) const;
    std::uint64_t userData(int proxy) const;

    /// Calls visit(proxy) for each proxy whose fat box overlaps `box`; stop when visit returns false.
    void query(const Aabb& box, FunctionRef<bool(int)> visit) const;
    /// Ray origin + t dir, 0 <= t <= maxDistance. visit(proxy, maxDistance) returns the new
    /// clip distance (<= 0 stops, the same value continues, smaller clips).
    void rayCast(const Vec3& origin, const Vec3& dir, double maxDistance,
                 FunctionRef<double(int, double)> visit) const;

    int height() const;
    int proxyCount() const;
    /// Checks the tree's invariants (parent links, bounds containment, heights); for tests.
    bool isValid() const;

    /// Bounds of everything in the tree (zero box when empty).
    Aabb rootAabb() const;
    /// Sum of the perimeters of internal nodes over the root's: the SAH quality measure (tests, tuning).
    double areaRatio() const;
    /// How many nodes query(box) examines: its cost, independent of timing (tests, tuning).
    int queryCost(const Aabb& box) const;

private:
    struct Node {
        Aabb box;
        std::uint64_t userData = 0;
        int parent = kNull;  // also the next free node while the node is on the free list
        int child1 = kNull;  // kNull for leaves
        int child2 = kNull;
        int height = -1;     // 0 for leaves, -1 while free

        bool isLeaf() const { return child1 == kNull; }
    };

    int allocateNode();
    void freeNode(int node);
    void insertLeaf(int leaf);
    void removeLeaf(int leaf);
    int findBestSibling(const Aabb& box);
    /// Recomputes box and height of each ancestor of `node`, rotating where unbalanced.
    void refitAncestors(int node);
    /// AVL rotation at `a` if its children's heights differ by more than one; returns the subtree root.
    int balance(int a);
    void replaceChild(int parent, int oldChild, int newChild);
    bool isProxy(int proxy) const;
    int validateSubtree(int node, int& leafCount) const;  // height, or -2 on a broken invariant

    LargeVector<Node> nodes_;
    int root_ = kNull;
    int freeList_ = kNull;
    int proxyCount_ = 0;
    struct Candidate {  // of the sibling search
        int node;
        double inherited;  // growth of the node's ancestors if the new leaf goes below them
    };
    std::vector<Candidate> searchStack_;  // reused: insertion does not allocate once warm
};

/// Proxies of shapes; finds new overlapping pairs among proxies that moved out of their fat box.
class BroadPhase {
public:
    /// `margin`: how much fat boxes exceed the tight ones (m).
    explicit BroadPhase(double margin = 0.1);

    int createProxy(const Aabb& tight, std::uint64_t key, bool isStatic);
    void destroyProxy(int proxy);
    /// Updates a proxy's tight box; if it left its fat box the proxy is re-inserted, enlarged
    /// along `displacement` (predicted motion), and marked moved.
    void moveProxy(int proxy, const Aabb& tight, const Vec3& displacement);
    /// moveProxy in two halves, so workers can share the first: the new fat box if the proxy
    /// must move (reads only), then the move itself (changes the tree: one thread).
    bool needsMove(int proxy, const Aabb& tight, const Vec3& displacement, Aabb& fat) const;
    void setFatAabb(int proxy, const Aabb& fat);
    /// Reports the proxy's pairs again at the next updatePairs (pairs that were refused before).
    void touchProxy(int proxy) { markMoved(proxy); }
    /// Calls onPair(keyA, keyB) once for each pair of overlapping fat boxes where at least one
    /// proxy moved since the last call (static-static pairs never), then clears the moved set.
    /// The moved proxies' queries run on the workers of `tasks`; pairs come sorted, so the
    /// order does not depend on the workers.
    void updatePairs(FunctionRef<void(std::uint64_t, std::uint64_t)> onPair, TaskSystem* tasks = nullptr);
    bool testOverlap(int proxyA, int proxyB) const;
    const Aabb& fatAabb(int proxy) const;

    void query(const Aabb& box, FunctionRef<bool(std::uint64_t key)> visit) const;
    void rayCast(const Vec3& origin, const Vec3& dir, double maxDistance,
                 FunctionRef<double(std::uint64_t key, double maxDistance)> visit) const;

    std::uint64_t key(int proxy) const;
    bool isStatic(int proxy) const;
    int proxyCount() const { return proxyCount_; }
    double margin() const { return margin_; }
    /// The two trees (static proxies, the others); for tests and statistics.
    const DynamicTree& staticTree() const { return staticTree_; }
    const DynamicTree& dynamicTree() const { return dynamicTree_; }

private:
    struct Proxy {
        int treeProxy = DynamicTree::kNull;  // kNull while the slot is free
        std::uint64_t key = 0;
        bool isStatic = false;
        bool moved = false;  // in the move buffer since the last updatePairs
        int nextFree = DynamicTree::kNull;
    };

    const Proxy& proxy(int id) const;
    DynamicTree& treeOf(const Proxy& p) { return p.isStatic ? staticTree_ : dynamicTree_; }
    const DynamicTree& treeOf(const Proxy& p) const { return p.isStatic ? staticTree_ : dynamicTree_; }
    void markMoved(int id);

    double margin_;
    // Two trees: static proxies never query each other, and a dynamic proxy's query skips no
    // static geometry. Tree user data is the broad-phase proxy id.
    DynamicTree staticTree_;
    DynamicTree dynamicTree_;
    LargeVector<Proxy> proxies_;
    int freeProxy_ = DynamicTree::kNull;
    int proxyCount_ = 0;
    std::vector<int> moveBuffer_;
    PerWorkerLists<std::pair<std::uint64_t, std::uint64_t>> workerPairs_;  // (min key, max key)
};

}  // namespace anyphys::native

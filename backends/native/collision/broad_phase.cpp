// Dynamic AABB tree (in the spirit of Box2D's b2DynamicTree, in 3D) and the broad phase on top.
#include "collision/broad_phase.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <stdexcept>

namespace anyphys::native {
namespace {

/// Depth-first traversal stack: fixed storage for any sane tree, a vector beyond that, so that
/// queries (one per moved proxy per step) do not allocate.
class NodeStack {
public:
    void push(int node) {
        if (size_ < fixed_.size()) {
            fixed_[size_++] = node;
        } else {
            overflow_.push_back(node);
        }
    }
    int pop() {
        if (!overflow_.empty()) {
            const int node = overflow_.back();
            overflow_.pop_back();
            return node;
        }
        return fixed_[--size_];
    }
    bool empty() const { return size_ == 0 && overflow_.empty(); }

private:
    std::array<int, 128> fixed_{};
    std::size_t size_ = 0;
    std::vector<int> overflow_;
};

/// Does origin + t dir meet the box for some t in [0, maxT]? Axis-parallel rays are tested
/// against the slab directly (no 0 * inf).
bool rayOverlapsBox(const Vec3& origin, const Vec3& invDir, const std::array<bool, 3>& parallel, double maxT,
                    const Aabb& box) {
    double tMin = 0.0;
    double tMax = maxT;
    for (int i = 0; i < 3; ++i) {
        if (parallel[i]) {
            if (origin[i] < box.min[i] || origin[i] > box.max[i]) return false;
            continue;
        }
        double t1 = (box.min[i] - origin[i]) * invDir[i];
        double t2 = (box.max[i] - origin[i]) * invDir[i];
        if (t1 > t2) std::swap(t1, t2);
        tMin = std::max(tMin, t1);
        tMax = std::min(tMax, t2);
        if (tMin > tMax) return false;
    }
    return true;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// DynamicTree: node pool

int DynamicTree::allocateNode() {
    if (freeList_ == kNull) {
        nodes_.emplace_back();
        nodes_.back().height = 0;
        return static_cast<int>(nodes_.size()) - 1;
    }
    const int node = freeList_;
    freeList_ = nodes_[node].parent;
    nodes_[node] = Node{};
    nodes_[node].height = 0;
    return node;
}

void DynamicTree::freeNode(int node) {
    nodes_[node] = Node{};  // height -1 marks it free
    nodes_[node].parent = freeList_;
    freeList_ = node;
}

bool DynamicTree::isProxy(int proxy) const {
    return proxy >= 0 && proxy < static_cast<int>(nodes_.size()) && nodes_[proxy].height == 0;
}

// ---------------------------------------------------------------------------------------------
// DynamicTree: proxies

int DynamicTree::createProxy(const Aabb& fatAabb, std::uint64_t userData) {
    const int leaf = allocateNode();
    nodes_[leaf].box = fatAabb;
    nodes_[leaf].userData = userData;
    insertLeaf(leaf);
    ++proxyCount_;
    return leaf;
}

void DynamicTree::destroyProxy(int proxy) {
    if (!isProxy(proxy)) throw std::out_of_range("DynamicTree::destroyProxy: not a proxy");
    removeLeaf(proxy);
    freeNode(proxy);
    --proxyCount_;
}

void DynamicTree::moveProxy(int proxy, const Aabb& fatAabb) {
    if (!isProxy(proxy)) throw std::out_of_range("DynamicTree::moveProxy: not a proxy");
    removeLeaf(proxy);
    nodes_[proxy].box = fatAabb;
    insertLeaf(proxy);
}

const Aabb& DynamicTree::fatAabb(int proxy) const {
    assert(isProxy(proxy));
    return nodes_[proxy].box;
}

std::uint64_t DynamicTree::userData(int proxy) const {
    assert(isProxy(proxy));
    return nodes_[proxy].userData;
}

int DynamicTree::height() const { return root_ == kNull ? 0 : nodes_[root_].height; }

int DynamicTree::proxyCount() const { return proxyCount_; }

Aabb DynamicTree::rootAabb() const { return root_ == kNull ? Aabb{} : nodes_[root_].box; }

double DynamicTree::areaRatio() const {
    if (root_ == kNull) return 0.0;
    double internalArea = 0.0;
    for (const Node& n : nodes_)
        if (n.height > 0) internalArea += n.box.perimeter();
    const double rootArea = nodes_[root_].box.perimeter();
    return rootArea > 0.0 ? internalArea / rootArea : 0.0;
}

int DynamicTree::queryCost(const Aabb& box) const {
    if (root_ == kNull) return 0;
    // query() examines the root and both children of every internal node whose box overlaps.
    int examined = 1;
    for (const Node& n : nodes_)
        if (n.height > 0 && n.box.overlaps(box)) examined += 2;
    return examined;
}

// ---------------------------------------------------------------------------------------------
// DynamicTree: insertion and removal

// Surface-area heuristic: making the leaf L a sibling of node S costs area(S + L) plus the
// growth of every ancestor of S. Branch and bound over the tree finds the cheapest S: below a
// node, no choice costs less than area(L) + the growth inherited so far, so such subtrees are
// skipped once a cheaper sibling is known.
int DynamicTree::findBestSibling(const Aabb& box) {
    const double leafArea = box.perimeter();
    int best = root_;
    double bestCost = nodes_[root_].box.merged(box).perimeter();
    std::vector<Candidate>& stack = searchStack_;
    stack.clear();
    stack.push_back({root_, 0.0});
    while (!stack.empty()) {
        const Candidate c = stack.back();
        stack.pop_back();
        const Node& node = nodes_[c.node];
        const double combined = node.box.merged(box).perimeter();
        const double cost = combined + c.inherited;
        if (cost < bestCost) {
            bestCost = cost;
            best = c.node;
        }
        if (node.isLeaf()) continue;
        const double inherited = c.inherited + combined - node.box.perimeter();
        if (leafArea + inherited >= bestCost) continue;
        // Visit the child that grows less first: it usually holds the best sibling, which
        // tightens the bound early.
        const double grow1 = nodes_[node.child1].box.merged(box).perimeter() - nodes_[node.child1].box.perimeter();
        const double grow2 = nodes_[node.child2].box.merged(box).perimeter() - nodes_[node.child2].box.perimeter();
        stack.push_back({grow1 < grow2 ? node.child2 : node.child1, inherited});
        stack.push_back({grow1 < grow2 ? node.child1 : node.child2, inherited});
    }
    return best;
}

void DynamicTree::insertLeaf(int leaf) {
    if (root_ == kNull) {
        root_ = leaf;
        nodes_[leaf].parent = kNull;
        return;
    }
    const int sibling = findBestSibling(nodes_[leaf].box);
    const int oldParent = nodes_[sibling].parent;
    const int newParent = allocateNode();  // may reallocate nodes_: no references held here
    nodes_[newParent].parent = oldParent;
    nodes_[newParent].box = nodes_[leaf].box.merged(nodes_[sibling].box);
    nodes_[newParent].height = nodes_[sibling].height + 1;
    nodes_[newParent].child1 = sibling;
    nodes_[newParent].child2 = leaf;
    if (oldParent == kNull) {
        root_ = newParent;
    } else {
        replaceChild(oldParent, sibling, newParent);
    }
    nodes_[sibling].parent = newParent;
    nodes_[leaf].parent = newParent;
    refitAncestors(newParent);
}

void DynamicTree::removeLeaf(int leaf) {
    if (leaf == root_) {
        root_ = kNull;
        return;
    }
    const int parent = nodes_[leaf].parent;
    const int grandParent = nodes_[parent].parent;
    const int sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
    nodes_[sibling].parent = grandParent;
    if (grandParent == kNull) {
        root_ = sibling;
    } else {
        replaceChild(grandParent, parent, sibling);
    }
    freeNode(parent);
    nodes_[leaf].parent = kNull;
    if (grandParent != kNull) refitAncestors(grandParent);
}

void DynamicTree::replaceChild(int parent, int oldChild, int newChild) {
    if (nodes_[parent].child1 == oldChild) {
        nodes_[parent].child1 = newChild;
    } else {
        nodes_[parent].child2 = newChild;
    }
}

void DynamicTree::refitAncestors(int node) {
    while (node != kNull) {
        node = balance(node);
        Node& n = nodes_[node];
        n.height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
        n.box = nodes_[n.child1].box.merged(nodes_[n.child2].box);
        node = n.parent;
    }
}

// AVL-style rotation. If one child ("high") is more than one level taller than the other
// ("low"), `high` takes a's place, a becomes high's child, and a adopts high's shorter child.
int DynamicTree::balance(int a) {
    if (nodes_[a].isLeaf() || nodes_[a].height < 2) return a;
    const int b = nodes_[a].child1;
    const int c = nodes_[a].child2;
    const int diff = nodes_[c].height - nodes_[b].height;
    if (diff >= -1 && diff <= 1) return a;
    const int high = diff > 1 ? c : b;
    const int low = diff > 1 ? b : c;

    const int f = nodes_[high].child1;
    const int g = nodes_[high].child2;
    const int keep = nodes_[f].height > nodes_[g].height ? f : g;
    const int give = keep == f ? g : f;

    const int aParent = nodes_[a].parent;
    nodes_[high].parent = aParent;
    if (aParent == kNull) {
        root_ = high;
    } else {
        replaceChild(aParent, a, high);
    }
    nodes_[a].parent = high;
    nodes_[high].child1 = a;
    nodes_[high].child2 = keep;

    replaceChild(a, high, give);
    nodes_[give].parent = a;
    nodes_[a].box = nodes_[low].box.merged(nodes_[give].box);
    nodes_[a].height = 1 + std::max(nodes_[low].height, nodes_[give].height);
    nodes_[high].box = nodes_[a].box.merged(nodes_[keep].box);
    nodes_[high].height = 1 + std::max(nodes_[a].height, nodes_[keep].height);
    return high;
}

// ---------------------------------------------------------------------------------------------
// DynamicTree: traversal

void DynamicTree::query(const Aabb& box, FunctionRef<bool(int)> visit) const {
    if (root_ == kNull) return;
    NodeStack stack;
    stack.push(root_);
    while (!stack.empty()) {
        const Node& node = nodes_[stack.pop()];
        if (!node.box.overlaps(box)) continue;
        if (node.isLeaf()) {
            if (!visit(static_cast<int>(&node - nodes_.data()))) return;
        } else {
            stack.push(node.child1);
            stack.push(node.child2);
        }
    }
}

void DynamicTree::rayCast(const Vec3& origin, const Vec3& dir, double maxDistance,
                          FunctionRef<double(int, double)> visit) const {
    if (root_ == kNull || !(maxDistance > 0.0)) return;
    std::array<bool, 3> parallel{};
    Vec3 invDir = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
        parallel[i] = std::abs(dir[i]) < 1e-300;
        if (!parallel[i]) invDir[i] = 1.0 / dir[i];
    }
    double maxT = maxDistance;
    NodeStack stack;
    stack.push(root_);
    while (!stack.empty()) {
        const int index = stack.pop();
        const Node& node = nodes_[index];
        if (!rayOverlapsBox(origin, invDir, parallel, maxT, node.box)) continue;
        if (node.isLeaf()) {
            const double value = visit(index, maxT);
            if (value <= 0.0) return;
            maxT = std::min(maxT, value);
        } else {
            stack.push(node.child1);
            stack.push(node.child2);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// DynamicTree: validation

int DynamicTree::validateSubtree(int index, int& leafCount) const {
    const Node& node = nodes_[index];
    if (node.isLeaf()) {
        if (node.child2 != kNull || node.height != 0) return -2;
        ++leafCount;
        return 0;
    }
    const int c1 = node.child1;
    const int c2 = node.child2;
    const int size = static_cast<int>(nodes_.size());
    if (c1 < 0 || c1 >= size || c2 < 0 || c2 >= size || c1 == c2) return -2;
    if (nodes_[c1].parent != index || nodes_[c2].parent != index) return -2;
    if (!node.box.contains(nodes_[c1].box) || !node.box.contains(nodes_[c2].box)) return -2;
    const int h1 = validateSubtree(c1, leafCount);
    const int h2 = validateSubtree(c2, leafCount);
    if (h1 < 0 || h2 < 0) return -2;
    const int h = 1 + std::max(h1, h2);
    return h == node.height ? h : -2;
}

bool DynamicTree::isValid() const {
    int freeCount = 0;
    for (int i = freeList_; i != kNull; i = nodes_[i].parent) {
        if (i < 0 || i >= static_cast<int>(nodes_.size()) || nodes_[i].height != -1) return false;
        if (++freeCount > static_cast<int>(nodes_.size())) return false;  // a cycle
    }
    if (root_ == kNull) return proxyCount_ == 0 && freeCount == static_cast<int>(nodes_.size());
    if (nodes_[root_].parent != kNull) return false;
    int leafCount = 0;
    if (validateSubtree(root_, leafCount) < 0) return false;
    // A binary tree with L leaves has 2L - 1 nodes; every other node must be free.
    return leafCount == proxyCount_ && 2 * leafCount - 1 + freeCount == static_cast<int>(nodes_.size());
}

// ---------------------------------------------------------------------------------------------
// BroadPhase

BroadPhase::BroadPhase(double margin) : margin_(margin) {
    if (!(margin >= 0.0)) throw std::invalid_argument("BroadPhase: margin must be >= 0");
}

const BroadPhase::Proxy& BroadPhase::proxy(int id) const {
    if (id < 0 || id >= static_cast<int>(proxies_.size()) || proxies_[id].treeProxy == DynamicTree::kNull)
        throw std::out_of_range("BroadPhase: not a proxy id");
    return proxies_[id];
}

void BroadPhase::markMoved(int id) {
    if (proxies_[id].moved) return;
    proxies_[id].moved = true;
    moveBuffer_.push_back(id);
}

int BroadPhase::createProxy(const Aabb& tight, std::uint64_t key, bool isStatic) {
    int id;
    if (freeProxy_ != DynamicTree::kNull) {
        id = freeProxy_;
        freeProxy_ = proxies_[id].nextFree;
    } else {
        id = static_cast<int>(proxies_.size());
        proxies_.emplace_back();
    }
    Proxy& p = proxies_[id];
    p = Proxy{};
    p.key = key;
    p.isStatic = isStatic;
    p.treeProxy = treeOf(p).createProxy(tight.fattened(margin_), static_cast<std::uint64_t>(id));
    ++proxyCount_;
    markMoved(id);  // a new proxy looks for its pairs at the next updatePairs
    return id;
}

void BroadPhase::destroyProxy(int id) {
    const Proxy& p = proxy(id);
    treeOf(p).destroyProxy(p.treeProxy);
    // Its move-buffer entry (if any) goes stale: updatePairs skips free or unmarked proxies.
    proxies_[id] = Proxy{};
    proxies_[id].nextFree = freeProxy_;
    freeProxy_ = id;
    --proxyCount_;
}

bool BroadPhase::needsMove(int id, const Aabb& tight, const Vec3& displacement, Aabb& fat) const {
    const Proxy& p = proxy(id);
    fat = tight.fattened(margin_);
    // Stretch along the predicted motion so a steadily moving proxy is re-inserted rarely.
    for (int i = 0; i < 3; ++i) {
        if (displacement[i] < 0.0) {
            fat.min[i] += displacement[i];
        } else {
            fat.max[i] += displacement[i];
        }
    }
    const Aabb& old = treeOf(p).fatAabb(p.treeProxy);
    // Still inside: keep the old box unless it is much larger than needed (after a fast move
    // that stopped), which would report needless pairs.
    return !(old.contains(tight) && fat.fattened(4.0 * margin_).contains(old));
}

void BroadPhase::setFatAabb(int id, const Aabb& fat) {
    const Proxy& p = proxy(id);
    treeOf(p).moveProxy(p.treeProxy, fat);
    markMoved(id);
}

void BroadPhase::moveProxy(int id, const Aabb& tight, const Vec3& displacement) {
    Aabb fat;
    if (needsMove(id, tight, displacement, fat)) setFatAabb(id, fat);
}

void BroadPhase::updatePairs(FunctionRef<void(std::uint64_t, std::uint64_t)> onPair, TaskSystem* tasks) {
    // A proxy destroyed and re-created in the same slot may be listed twice.
    std::sort(moveBuffer_.begin(), moveBuffer_.end());
    moveBuffer_.erase(std::unique(moveBuffer_.begin(), moveBuffer_.end()), moveBuffer_.end());

    const int workers = tasks ? tasks->workerCount() : 1;
    workerPairs_.reset(workers);
    // Each moved proxy's queries read the trees only; pairs go to the worker's own buffer.
    const auto findPairs = [&](int begin, int end, int worker) {
        auto& out = workerPairs_.of(worker);
        for (int k = begin; k < end; ++k) {
            const int id = moveBuffer_[static_cast<std::size_t>(k)];
            const Proxy& p = proxies_[id];
            if (p.treeProxy == DynamicTree::kNull || !p.moved) continue;  // destroyed since it moved
            const Aabb& box = treeOf(p).fatAabb(p.treeProxy);
            const auto collect = [&](const DynamicTree& tree) {
                tree.query(box, [&](int treeProxy) {
                    const int other = static_cast<int>(tree.userData(treeProxy));
                    if (other == id) return true;
                    const Proxy& q = proxies_[other];
                    // Both moved: both queries find the pair; only the larger id's query keeps it.
                    if (q.moved && other > id) return true;
                    if (q.key == p.key) return true;  // shapes sharing a key never pair with themselves
                    out.emplace_back(std::min(p.key, q.key), std::max(p.key, q.key));
                    return true;
                });
            };
            collect(dynamicTree_);
            if (!p.isStatic) collect(staticTree_);  // static-static pairs are never reported
        }
    };
    constexpr int kMinProxiesPerRange = 64;
    parallelFor(tasks, static_cast<int>(moveBuffer_.size()), kMinProxiesPerRange, findPairs);
    for (const int id : moveBuffer_) proxies_[id].moved = false;
    moveBuffer_.clear();

    auto& found = workerPairs_.joined();
    // Sorted: callers see a deterministic order whatever the workers did; unique: two proxies
    // with the same key pair (several proxies of one key) are reported once.
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    // Taken out first: the callback may create, move or destroy proxies.
    std::vector<std::pair<std::uint64_t, std::uint64_t>> pairs = std::move(found);
    for (const auto& [a, b] : pairs) onPair(a, b);
    pairs.clear();
    found = std::move(pairs);  // keep the storage for the next call
}

bool BroadPhase::testOverlap(int proxyA, int proxyB) const { return fatAabb(proxyA).overlaps(fatAabb(proxyB)); }

const Aabb& BroadPhase::fatAabb(int id) const {
    const Proxy& p = proxy(id);
    return treeOf(p).fatAabb(p.treeProxy);
}

std::uint64_t BroadPhase::key(int id) const { return proxy(id).key; }

bool BroadPhase::isStatic(int id) const { return proxy(id).isStatic; }

void BroadPhase::query(const Aabb& box, FunctionRef<bool(std::uint64_t key)> visit) const {
    bool stopped = false;
    for (const DynamicTree* tree : {&staticTree_, &dynamicTree_}) {
        tree->query(box, [&](int treeProxy) {
            stopped = !visit(proxies_[tree->userData(treeProxy)].key);
            return !stopped;
        });
        if (stopped) return;
    }
}

void BroadPhase::rayCast(const Vec3& origin, const Vec3& dir, double maxDistance,
                         FunctionRef<double(std::uint64_t key, double maxDistance)> visit) const {
    double clip = maxDistance;
    bool stopped = false;
    for (const DynamicTree* tree : {&staticTree_, &dynamicTree_}) {
        tree->rayCast(origin, dir, clip, [&](int treeProxy, double maxT) {
            const double value = visit(proxies_[tree->userData(treeProxy)].key, maxT);
            if (value <= 0.0) {
                stopped = true;
            } else {
                clip = std::min(clip, value);
            }
            return value;
        });
        if (stopped) return;
    }
}

}  // namespace anyphys::native

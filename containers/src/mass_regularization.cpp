#include "anyphys/containers/mass_regularization.hpp"

#include <cmath>
#include <map>
#include <numeric>
#include <vector>

#include "anyphys/error.hpp"
#include "anyphys/mass_properties.hpp"

namespace anyphys {
namespace {

struct Link {
    std::size_t parent, child;  // indices into scene.bodies
};

/// The scene's joints between two dynamic bodies, as body indices.
std::vector<Link> dynamicLinks(const Scene& scene) {
    std::map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) index.emplace(scene.bodies[i].name, i);
    std::vector<Link> links;
    for (const SceneJoint& j : scene.joints) {
        const auto a = index.find(j.bodyA), b = index.find(j.bodyB);
        if (a == index.end() || b == index.end()) continue;  // joined to the world
        if (scene.bodies[a->second].type != BodyType::Dynamic || scene.bodies[b->second].type != BodyType::Dynamic) continue;
        links.push_back({a->second, b->second});
    }
    return links;
}

/// The mass the world will give this body; throws if it depends on geometry built in the layer.
double resolvedMass(const Scene& scene, const BodyDef& body) {
    if (body.mass) return *body.mass;
    const double volume = shapeVolume(body.shape);
    if (volume <= 0.0)
        throw Error("mass regularisation: body \"" + body.name + "\" (shape " + std::string(toString(body.shape.type)) +
                    ") needs an explicit mass");
    const double density = body.density                                                  ? *body.density
                           : !body.material.empty() && scene.materials.contains(body.material) ? scene.materials.get(body.material).density
                                                                                          : 1000.0;
    return density * volume;
}

Vec3 resolvedInertia(const BodyDef& body, double mass) {
    if (body.inertia) return *body.inertia;
    if (shapeVolume(body.shape) <= 0.0)
        throw Error("mass regularisation: body \"" + body.name + "\" (shape " + std::string(toString(body.shape.type)) +
                    ") needs an explicit inertia");
    return mass * unitInertia(body.shape);
}

/// Connected groups of the link graph, as a group number per body (bodies in no link: none).
std::vector<int> groupsOf(std::size_t bodyCount, const std::vector<Link>& links) {
    std::vector<std::size_t> root(bodyCount);
    std::iota(root.begin(), root.end(), 0);
    const auto find = [&root](std::size_t i) {
        while (root[i] != i) i = root[i] = root[root[i]];
        return i;
    };
    for (const Link& l : links) root[find(l.parent)] = find(l.child);
    std::vector<int> group(bodyCount, -1);
    for (const Link& l : links) group[l.parent] = group[l.child] = static_cast<int>(find(l.parent));
    return group;
}

void boundMassRatios(std::vector<double>& mass, const std::vector<Link>& links, const std::vector<int>& group,
                     double maxRatio) {
    std::map<int, double> total;
    for (std::size_t i = 0; i < mass.size(); ++i)
        if (group[i] >= 0) total[group[i]] += mass[i];
    // Raising only the lighter side never lowers a mass, and no mass rises above the heaviest:
    // the sweep converges; each sweep settles at least one more body, so `links` sweeps suffice.
    for (std::size_t sweep = 0; sweep <= links.size(); ++sweep) {
        bool changed = false;
        for (const Link& l : links) {
            double& light = mass[l.parent] < mass[l.child] ? mass[l.parent] : mass[l.child];
            const double heavy = std::max(mass[l.parent], mass[l.child]);
            if (heavy > maxRatio * light * (1.0 + 1e-12)) {
                light = heavy / maxRatio;
                changed = true;
            }
        }
        if (!changed) break;
    }
    std::map<int, double> raised;
    for (std::size_t i = 0; i < mass.size(); ++i)
        if (group[i] >= 0) raised[group[i]] += mass[i];
    for (std::size_t i = 0; i < mass.size(); ++i)
        if (group[i] >= 0) mass[i] *= total[group[i]] / raised[group[i]];
}

bool raiseParents(std::vector<Vec3>& inertia, const std::vector<Link>& links) {
    bool any = false;
    for (std::size_t sweep = 0; sweep <= links.size(); ++sweep) {  // up a tree of depth <= links
        bool changed = false;
        for (const Link& l : links) {
            const double floor = inertia[l.child].maxCoeff();
            Vec3& parent = inertia[l.parent];
            for (int axis = 0; axis < 3; ++axis)
                if (parent[axis] < floor) {
                    parent[axis] = floor;
                    changed = true;
                }
        }
        any = any || changed;
        if (!changed) break;
    }
    return any;
}

}  // namespace

void validate(const MassRegularization& options, const std::string& path) {
    if (!(std::isfinite(options.maxMassRatio) && (options.maxMassRatio == 0.0 || options.maxMassRatio >= 1.0)))
        throw Error::invalid(path + "maxMassRatio", options.maxMassRatio, "must be >= 1 (0 leaves masses alone)");
}

void regularizeMasses(Scene& scene, const MassRegularization& options) {
    validate(options, "");
    if (!options.enabled()) return;
    const std::vector<Link> links = dynamicLinks(scene);
    const std::vector<int> group = groupsOf(scene.bodies.size(), links);
    // Resolve everything first, so a refusal leaves the scene unchanged.
    std::vector<double> mass(scene.bodies.size(), 0.0);
    std::vector<Vec3> inertia(scene.bodies.size(), Vec3::Zero());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        if (group[i] < 0) continue;
        mass[i] = resolvedMass(scene, scene.bodies[i]);
        inertia[i] = resolvedInertia(scene.bodies[i], mass[i]);
    }
    std::vector<double> before = mass;
    if (options.maxMassRatio > 0.0) boundMassRatios(mass, links, group, options.maxMassRatio);
    for (std::size_t i = 0; i < mass.size(); ++i)
        if (group[i] >= 0) inertia[i] *= mass[i] / before[i];  // same shape, new mass
    std::vector<Vec3> unraised = inertia;
    if (options.raiseParentInertia) raiseParents(inertia, links);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        if (group[i] < 0) continue;
        BodyDef& body = scene.bodies[i];
        if (mass[i] != before[i]) body.mass = mass[i];
        // An explicit inertia stays explicit (scaled); a raised one becomes explicit.
        if (body.inertia || inertia[i] != unraised[i]) body.inertia = inertia[i];
    }
}

}  // namespace anyphys

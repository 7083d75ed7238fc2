#pragma once
// How engines are named and ordered in the report.
#include <algorithm>
#include <string>
#include <vector>

#include "results.hpp"

namespace anyphys::bench::report {

/// The backends in the usual order (native, ode, bullet, box2d), then any other found.
inline std::vector<std::string> engineOrder(const Results& results) {
    std::vector<std::string> order = {"native", "ode", "bullet", "box2d"};
    for (const Record& r : results.all())
        if (std::find(order.begin(), order.end(), r.engine) == order.end()) order.push_back(r.engine);
    return order;
}

/// The records of one kind, engines in engineOrder() and scenes as run.
inline std::vector<const Record*> inEngineOrder(const Results& results, const std::string& kind) {
    std::vector<const Record*> out;
    for (const std::string& engine : engineOrder(results))
        for (const Record& r : results.all())
            if (r.kind == kind && r.engine == engine) out.push_back(&r);
    return out;
}

/// "raw ODE", "raw Bullet", "raw Box2D": the engine driven directly.
inline std::string rawName(const std::string& engine) {
    if (engine == "ode") return "raw ODE";
    if (engine == "bullet") return "raw Bullet";
    if (engine == "box2d") return "raw Box2D";
    return "raw " + engine;
}

/// A row's engine as the tables show it.
inline std::string engineName(const Record& r) {
    if (r.kind == "raw") return rawName(r.engine);
    if (r.kind == "overhead") return r.engine;
    return "anyphys " + r.engine + (r.workers > 1 ? ", " + std::to_string(r.workers) + " workers" : "");
}

}  // namespace anyphys::bench::report

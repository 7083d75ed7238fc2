// The registration list: the one place below api/ that knows the concrete backends.
#include "anyphys/error.hpp"
#include "anyphys/peers/backend.hpp"
#include "anyphys/schema/parameters.hpp"

namespace anyphys {

#if ANYPHYS_HAS_NATIVE
Backend makeNativeBackend();
#endif
#if ANYPHYS_HAS_ODE
Backend makeOdeBackend();
#endif
#if ANYPHYS_HAS_BULLET
Backend makeBulletBackend();
#endif
#if ANYPHYS_HAS_BOX2D
Backend makeBox2dBackend();
#endif

const std::vector<Backend>& registeredBackends() {
    static const std::vector<Backend> backends = [] {
        std::vector<Backend> list;
#if ANYPHYS_HAS_NATIVE
        list.push_back(makeNativeBackend());
#endif
#if ANYPHYS_HAS_ODE
        list.push_back(makeOdeBackend());
#endif
#if ANYPHYS_HAS_BULLET
        list.push_back(makeBulletBackend());
#endif
#if ANYPHYS_HAS_BOX2D
        list.push_back(makeBox2dBackend());
#endif
        // The fields the layer makes hold on every backend (maxSpeed, divergencePolicy, a body's
        // name, ... and planar where the engine can) are listed here once, from the field table.
        for (Backend& backend : list) backend.capabilities.parameters.merge(schema::layerParameters(backend.capabilities));
        return list;
    }();
    return backends;
}

const Backend& findBackend(const std::string& name) {
    std::string known;
    for (const Backend& backend : registeredBackends()) {
        if (backend.name == name) return backend;
        known += (known.empty() ? "" : ", ") + backend.name;
    }
    throw Error::invalid("backend", "\"" + name + "\"", "must be one of the built backends (" + known + ")");
}

}  // namespace anyphys

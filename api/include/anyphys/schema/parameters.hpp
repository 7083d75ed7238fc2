#pragma once
// The capability parameters the layer honours itself, whatever the engine: added to every
// backend's Capabilities::parameters where the registry builds them (peers/src/registry.cpp), so
// a backend lists only what depends on its engine.
#include <set>
#include <string>

#include "anyphys/capabilities.hpp"
#include "anyphys/schema/body_fields.hpp"
#include "anyphys/schema/material_fields.hpp"
#include "anyphys/schema/settings_fields.hpp"

namespace anyphys::schema {

namespace detail {
template <class Def>
void addLayerRows(const std::vector<Field<Def>>& rows, const Capabilities& caps, std::set<std::string>& out) {
    for (const Field<Def>& f : rows)
        if (f.honour == Honour::Layer || (f.honour == Honour::LayerIfPlanar && caps.planar)) out.emplace(f.path);
}
}  // namespace detail

/// The parameters the layer makes hold on a backend with these capabilities.
inline std::set<std::string> layerParameters(const Capabilities& caps) {
    std::set<std::string> out;
    detail::addLayerRows(settingsFields(), caps, out);
    detail::addLayerRows(bodyFields(), caps, out);
    detail::addLayerRows(shapeFields(), caps, out);
    detail::addLayerRows(materialFields(), caps, out);
    return out;
}

/// Every row's parameter path, for checking that a backend lists only described fields.
inline std::set<std::string> describedParameters() {
    std::set<std::string> out;
    const auto add = [&out](const auto& rows) {
        for (const auto& f : rows) out.emplace(f.path);
    };
    add(settingsFields());
    add(bodyFields());
    add(shapeFields());
    add(materialFields());
    return out;
}

}  // namespace anyphys::schema

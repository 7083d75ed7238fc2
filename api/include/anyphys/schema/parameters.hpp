#pragma once
// The capability parameters the layer honours itself, whatever the engine: added to every
// backend's Capabilities::parameters where the registry builds them (peers/src/registry.cpp), so
// a backend lists only what depends on its engine.
#include <set>
#include <string>
#include <type_traits>

#include "anyphys/capabilities.hpp"
#include "anyphys/schema/body_fields.hpp"
#include "anyphys/schema/joint_fields.hpp"
#include "anyphys/schema/material_fields.hpp"
#include "anyphys/schema/settings_fields.hpp"

namespace anyphys::schema {

namespace detail {
/// The parameter names of a row: its path, or for a JointDef row whose path has a `*`, one name
/// per joint type that uses it ("joint.*.limits" -> "joint.hinge.limits", ...).
template <class Def>
std::set<std::string> rowParameters(const Field<Def>& f) {
    const std::string path(f.path);
    const auto star = path.find('*');
    if constexpr (std::is_same_v<Def, JointDef>) {
        if (star != std::string::npos) {
            std::set<std::string> out;
            for (const auto& [type, name] : EnumNames<JointType>::values)
                if (f.types & bit(type)) out.emplace(path.substr(0, star) + std::string(name) + path.substr(star + 1));
            return out;
        }
    }
    return {path};
}

template <class Def>
void addLayerRows(const std::vector<Field<Def>>& rows, const Capabilities& caps, std::set<std::string>& out) {
    for (const Field<Def>& f : rows)
        if (f.honour == Honour::Layer || (f.honour == Honour::LayerIfPlanar && caps.planar)) out.merge(rowParameters(f));
}
}  // namespace detail

/// The parameters the layer makes hold on a backend with these capabilities.
inline std::set<std::string> layerParameters(const Capabilities& caps) {
    std::set<std::string> out;
    detail::addLayerRows(settingsFields(), caps, out);
    detail::addLayerRows(bodyFields(), caps, out);
    detail::addLayerRows(shapeFields(), caps, out);
    detail::addLayerRows(materialFields(), caps, out);
    detail::addLayerRows(jointDefFields(), caps, out);
    return out;
}

/// Every row's parameter path, for checking that a backend lists only described fields.
inline std::set<std::string> describedParameters() {
    std::set<std::string> out;
    const auto add = [&out](const auto& rows) {
        for (const auto& f : rows) out.merge(detail::rowParameters(f));
    };
    add(settingsFields());
    add(bodyFields());
    add(shapeFields());
    add(materialFields());
    add(jointDefFields());
    add(jointLimitsFields());
    add(jointMotorFields());
    add(jointSpringFields());
    return out;
}

}  // namespace anyphys::schema

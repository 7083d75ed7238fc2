#include "anyphys/containers/material_library.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "anyphys/error.hpp"
#include "anyphys/schema/material_fields.hpp"

namespace anyphys {

namespace {

constexpr std::array<std::pair<CombineRule, std::string_view>, 5> kRuleNames{{
    {CombineRule::Average, "average"},
    {CombineRule::Min, "min"},
    {CombineRule::Max, "max"},
    {CombineRule::Multiply, "multiply"},
    {CombineRule::GeometricMean, "geometric_mean"},
}};

std::string quoted(std::string_view name) {
    // Built by append: GCC 12 at -O3 warns falsely (-Wrestrict) on "literal" + std::string.
    std::string out(1, '"');
    out.append(name);
    out += '"';
    return out;
}

// Overrides are stored once per unordered pair, under (smaller, larger) name.
std::pair<std::string, std::string> pairKey(std::string_view a, std::string_view b) {
    if (b < a) std::swap(a, b);
    return {std::string(a), std::string(b)};
}

// The path of a material in error messages: the scene file's "materials.<name>".
std::string materialPath(std::string_view name) { return "materials." + (name.empty() ? quoted(name) : std::string(name)); }

}  // namespace

std::string_view toString(CombineRule rule) {
    for (const auto& [r, name] : kRuleNames)
        if (r == rule) return name;
    return "unknown";
}

std::optional<CombineRule> combineRuleFromString(std::string_view name) {
    for (const auto& [r, n] : kRuleNames)
        if (n == name) return r;
    return std::nullopt;
}

std::string combineRuleNames() {
    std::string out;
    for (const auto& [r, n] : kRuleNames) {
        if (!out.empty()) out += ", ";
        out += n;
    }
    return out;
}

double combine(CombineRule rule, double a, double b) {
    switch (rule) {
        case CombineRule::Average: return 0.5 * (a + b);
        case CombineRule::Min: return std::min(a, b);
        case CombineRule::Max: return std::max(a, b);
        case CombineRule::Multiply: return a * b;
        case CombineRule::GeometricMean: return std::sqrt(a * b);
    }
    return a;  // unreachable: every rule is handled above
}

void validate(const Material& m, const std::string& path) {
    schema::checkFields(schema::materialFields(), m, path, [](const auto&) { return true; });
}

void validate(const PairOverride& values, const std::string& path) {
    // A pair's values follow the rules of the material fields of the same name.
    const auto& rows = schema::materialFields();
    if (values.friction) schema::checkValue(*schema::findField(rows, "friction"), *values.friction, path + ".friction");
    if (values.restitution)
        schema::checkValue(*schema::findField(rows, "restitution"), *values.restitution, path + ".restitution");
}

MaterialLibrary::MaterialLibrary() { materials_.emplace(std::string(kDefaultName), Material{}); }

void MaterialLibrary::add(const std::string& name, const Material& material) {
    validate(material, materialPath(name));
    materials_[name] = material;
}

bool MaterialLibrary::contains(std::string_view name) const { return materials_.find(name) != materials_.end(); }

const Material& MaterialLibrary::get(std::string_view name) const {
    const auto it = materials_.find(name);
    if (it == materials_.end())
        throw Error::invalid("material", quoted(name), "must be a known material (" + knownNames() + ")");
    return it->second;
}

std::vector<std::string> MaterialLibrary::names() const {
    std::vector<std::string> out;
    for (const auto& [name, m] : materials_)
        if (name != kDefaultName) out.push_back(name);
    return out;  // std::map keeps them sorted
}

std::string MaterialLibrary::knownNames() const {
    std::string out = "\"\" (the default)";
    for (const auto& name : names()) out += ", " + name;
    return out;
}

void MaterialLibrary::setPairOverride(const std::string& a, const std::string& b, const PairOverride& values) {
    // Check everything before touching the table: a rejected call changes nothing.
    for (const auto* name : {&a, &b})
        if (!contains(*name))
            throw Error::invalid("material pair (" + a + ", " + b + ")", quoted(*name),
                                 "both names must be known materials (" + knownNames() + ")");
    const auto key = pairKey(a, b);
    validate(values, "materials.pair(" + key.first + ", " + key.second + ")");
    overrides_[key] = values;
}

std::optional<PairOverride> MaterialLibrary::pairOverride(std::string_view a, std::string_view b) const {
    const auto it = overrides_.find(pairKey(a, b));
    if (it == overrides_.end()) return std::nullopt;
    return it->second;
}

MixedMaterial MaterialLibrary::resolve(std::string_view a, std::string_view b) const {
    const Material& ma = get(a);
    const Material& mb = get(b);
    MixedMaterial mixed{combine(frictionRule_, ma.friction, mb.friction),
                        combine(restitutionRule_, ma.restitution, mb.restitution)};
    if (const auto o = pairOverride(a, b)) {
        if (o->friction) mixed.friction = *o->friction;
        if (o->restitution) mixed.restitution = *o->restitution;
    }
    return mixed;
}

}  // namespace anyphys

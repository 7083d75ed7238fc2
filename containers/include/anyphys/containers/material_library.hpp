#pragma once
// Named materials and the rules that mix two of them into the values a contact uses.
// The layer resolves every pair here; backends only apply the result.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace anyphys {

struct Material {
    double friction = 0.6;     ///< Coulomb coefficient, >= 0; default 0.6 (as Box2D)
    double restitution = 0.0;  ///< coefficient of restitution in [0, 1]; default 0
    double density = 1000.0;   ///< kg/m^3, > 0; default 1000 (water)
};

enum class CombineRule { Average, Min, Max, Multiply, GeometricMean };

std::string_view toString(CombineRule rule);
std::optional<CombineRule> combineRuleFromString(std::string_view name);
/// Applies the rule to two values.
double combine(CombineRule rule, double a, double b);
/// "average, min, max, multiply, geometric_mean": the allowed names, for error messages.
std::string combineRuleNames();

/// The friction and restitution a pair of materials uses.
struct MixedMaterial {
    double friction = 0.0;
    double restitution = 0.0;
};

/// Optional per-pair values; an unset value falls back to the combine rule.
struct PairOverride {
    std::optional<double> friction;
    std::optional<double> restitution;
};

/// Checks a material's ranges; errors name `path` + ".friction" etc. Shared by the library and
/// the scene loader so both state the same rule in the same words.
void validate(const Material& material, const std::string& path);
/// Checks the values an override sets (friction >= 0, restitution in [0, 1]).
void validate(const PairOverride& values, const std::string& path);

class MaterialLibrary {
public:
    /// The material used for bodies that name none (""). Its values are Material's defaults.
    static constexpr std::string_view kDefaultName = "";

    MaterialLibrary();

    /// Adds or replaces a material. Throws anyphys::Error naming the field when a value is out of range.
    void add(const std::string& name, const Material& material);
    bool contains(std::string_view name) const;
    /// Throws anyphys::Error listing the known names when unknown.
    const Material& get(std::string_view name) const;
    /// Names in sorted order, without the default material.
    std::vector<std::string> names() const;
    /// "\"\" (the default), ice, rubber": every known name, for error messages.
    std::string knownNames() const;

    CombineRule frictionRule() const { return frictionRule_; }
    CombineRule restitutionRule() const { return restitutionRule_; }
    /// Defaults: friction geometric mean, restitution max (as Box2D and Jolt).
    void setFrictionRule(CombineRule rule) { frictionRule_ = rule; }
    void setRestitutionRule(CombineRule rule) { restitutionRule_ = rule; }

    /// Overrides the values of one pair (order does not matter). Both names must be known.
    void setPairOverride(const std::string& a, const std::string& b, const PairOverride& values);
    /// The override of that pair, if any (order does not matter).
    std::optional<PairOverride> pairOverride(std::string_view a, std::string_view b) const;
    const std::map<std::pair<std::string, std::string>, PairOverride>& pairOverrides() const { return overrides_; }

    /// Mixed values for a pair: override values first, combine rules for the rest. Symmetric.
    MixedMaterial resolve(std::string_view a, std::string_view b) const;

private:
    std::map<std::string, Material, std::less<>> materials_;
    std::map<std::pair<std::string, std::string>, PairOverride> overrides_;  // key: (min, max) name
    CombineRule frictionRule_ = CombineRule::GeometricMean;
    CombineRule restitutionRule_ = CombineRule::Max;
};

}  // namespace anyphys

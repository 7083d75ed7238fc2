#pragma once
// One description per field. Each settings and def field is described once, in a table of
// Field rows (schema/*_fields.hpp): its scene-file key, unit, default, rule and who honours it.
// The rows drive validation (validation.hpp), scene files (containers/src/scene_json.cpp), the
// key tables of docs/scene-format.md (`anyphys schema --markdown`) and the capability parameter
// list (schema/parameters.hpp), so these cannot disagree about a field.
// The rows themselves are defined out of line (api/src/schema/*.cpp): a row's accessors are
// std::function objects, and building them in every file that validates a def cost minutes of
// compile time. Headers declare the tables; schema/rows.hpp has the helpers that build them.
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "anyphys/checks.hpp"
#include "anyphys/enums.hpp"
#include "anyphys/error.hpp"
#include "anyphys/math.hpp"

namespace anyphys::schema {

/// The value's JSON spelling. Object: read and written by the scene loader's own code.
enum class Type { Number, Count, Bits, Vec3, Quat, Bool, Enum, String, Object };

/// The rule a value must meet; `Field::bound` and `Field::words` complete it. Scalar rules on a
/// Vec3 field hold for each component, named `key[i]` in messages.
enum class Check {
    None,
    Finite,          ///< finite
    Positive,        ///< > 0
    NonNegative,     ///< >= 0
    UnitInterval,    ///< finite, in [0, 1] (Material::restitution, WorldSettings::baumgarte)
    Within,          ///< finite, |v| <= bound
    Coordinate,      ///< finite, each coordinate within +-kMaxCoordinate
    Length,          ///< a size: in [kMinLength, kMaxCoordinate]
    LengthOrZero,    ///< a size that may be 0: in [0, kMaxCoordinate]
    Magnitude,       ///< finite vector, norm <= bound
    PositiveAtMost,  ///< > 0 and <= bound
    TimeStep,        ///< in [kMinTimeStep, kMaxTimeStep]
    CountIn,         ///< integer in [1, bound]
    UnitQuaternion,  ///< norm 1 within kUnitQuaternionTolerance
    Direction,       ///< finite, non-zero vector
    NonEmpty,        ///< non-empty string; `words` is the whole rule
    Threshold,       ///< > 0, infinity allowed (a joint's break force: infinite never breaks)
};

/// Who makes a field take effect, which decides where it is listed as a capability parameter.
enum class Honour {
    Layer,          ///< the layer, on every backend: added to every backend's parameters
    LayerIfPlanar,  ///< the layer, on every backend whose capabilities say planar
    Backend,        ///< the engine: each backend that honours it lists it itself
    Parent,         ///< part of an enclosing parameter (a shape's radius is `body.shape`): not listed
};

/// When a scene file written by sceneToJson carries the field.
enum class Save { Always, WhenSet, WhenNotDefault };

/// A field's value, type-erased so that code can read, write and check any row alike. Enums are
/// their scene-file names; an unset optional is monostate.
using Value = std::variant<std::monostate, double, int, std::uint32_t, bool, Vec3, Quat, std::string>;

template <class Def>
struct Field {
    std::string_view key{};          ///< scene-file key in its object, e.g. "timeStep"
    std::string_view path{};         ///< capability parameter path, e.g. "settings.timeStep"
    Type type = Type::Number;
    std::string_view unit{};         ///< docs: unit and frame, e.g. "m/s^2, world frame"
    Value value{};                   ///< default of a default-constructed Def (monostate: none fixed)
    std::string_view defaultText{};  ///< docs: the default in words, when `value` alone does not say it
    bool required = false;           ///< must be given: no default (a shape's sizes, a body's name)
    Check check = Check::None;
    double bound = 0;                ///< the ceiling of Within, Magnitude, PositiveAtMost, CountIn
    std::string_view words{};        ///< messages: what follows the bound ("s (anyphys::kMaxTimeStep)")
    std::string_view note{};         ///< docs: what the field does, after its rule
    Honour honour = Honour::Backend;
    Save save = Save::Always;
    std::uint32_t types = ~0u;       ///< ShapeDef: the shape types that have it (bit 1 << ShapeType)
    bool childOnly = false;          ///< ShapeDef: only on a compound's children
    /// The scene loader reads and writes it with code of its own (a required key, an object, a
    /// name to resolve); the row still gives its key, docs and capability path.
    bool ownCode = false;
    std::function<Value(const Def&)> get{};
    /// Writes the value; false when an enum has no such name.
    std::function<bool(Def&, const Value&)> set{};
    std::string (*allowed)() = nullptr;  ///< Enum: the allowed names, "a, b, c"
};

/// Number as the docs print it: 1e7 rather than 1e+07.
inline std::string docNumber(double v) {
    std::string s = anyphys::detail::ceilingText(v);
    for (const char* from : {"e+0", "e+"})
        if (const auto at = s.find(from); at != std::string::npos) s.replace(at, std::string_view(from).size(), "e");
    return s;
}

/// The rule of a row in the docs' words, e.g. "> 0 and <= 1 s (`kMaxTimeStep`)".
template <class Def>
std::string ruleText(const Field<Def>& f) {
    const std::string each = f.type == Type::Vec3 ? "each " : "";
    const std::string bound = docNumber(f.bound);
    switch (f.check) {
        case Check::None: break;
        case Check::Finite: return "finite";
        case Check::Positive: return each + "> 0";
        case Check::NonNegative: return each + ">= 0";
        case Check::UnitInterval: return "in [0, 1]";
        case Check::Within: return "within +-" + bound;
        case Check::Coordinate: return (each.empty() ? "" : "finite, each coordinate ") + std::string("within +-1e7 (`kMaxCoordinate`)");
        case Check::Length: return each + "in [1e-6, 1e7] (`kMinLength`, `kMaxCoordinate`)";
        case Check::LengthOrZero: return each + ">= 0, <= 1e7 (`kMaxCoordinate`)";
        case Check::Magnitude: return "finite, magnitude <= " + bound + std::string(f.words);
        case Check::PositiveAtMost: return "> 0 and <= " + bound + std::string(f.words);
        case Check::TimeStep: return ">= 1e-9 and <= 1 s (`kMinTimeStep`, `kMaxTimeStep`)";
        case Check::CountIn: return "integer in [1, " + bound + "]" + std::string(f.words);
        case Check::UnitQuaternion: return "unit quaternion (norm 1 within 1e-4)";
        case Check::Direction: return "finite, non-zero";
        case Check::NonEmpty: return "non-empty";
        case Check::Threshold: return "> 0" + std::string(f.words);
    }
    switch (f.type) {
        case Type::Bool: return f.note.empty() ? "`true` or `false`" : "";
        case Type::Bits: return "integer in [0, 4294967295]";
        case Type::Enum: {
            if (!f.allowed) return "";
            std::string names = f.allowed(), out = "`";
            for (char c : names) out += c == ',' ? std::string("`,") : std::string(1, c);
            for (std::size_t at = 0; (at = out.find(", ", at)) != std::string::npos; at += 3) out.replace(at, 2, ", `");
            return "one of " + out + "`";
        }
        default: return "";
    }
}

/// Checks one value against a rule; `field` names it in messages ("settings.timeStep"). Unset
/// optionals pass (absent means the default). Out of line: api/src/schema/check_value.cpp.
void checkValue(Check check, double bound, std::string_view words, const Value& value, const std::string& field);

/// Checks one value of a row.
template <class Def>
void checkValue(const Field<Def>& f, const Value& value, const std::string& field) {
    checkValue(f.check, f.bound, f.words, value, field);
}

/// Checks every row of `rows` that `keep` selects on `def`; `path` prefixes the keys.
template <class Def, class Keep>
void checkFields(const std::vector<Field<Def>>& rows, const Def& def, const std::string& path, Keep keep) {
    for (const Field<Def>& f : rows)
        if (f.get && f.check != Check::None && keep(f)) checkValue(f, f.get(def), path + "." + std::string(f.key));
}

/// The row of `key` in `rows`, or null.
template <class Def>
const Field<Def>* findField(const std::vector<Field<Def>>& rows, std::string_view key) {
    for (const Field<Def>& f : rows)
        if (f.key == key) return &f;
    return nullptr;
}

/// The rule of the row `key` of `rows` on `def`, the field named `path.key` (for rules checked in
/// an order or under conditions of their own).
template <class Def>
void checkRow(const std::vector<Field<Def>>& rows, std::string_view key, const Def& def, const std::string& path) {
    const Field<Def>& f = *findField(rows, key);
    checkValue(f, f.get(def), path + "." + std::string(key));
}

/// Bit of a shape type in Field::types.
constexpr std::uint32_t bit(ShapeType t) { return 1u << static_cast<unsigned>(t); }

}  // namespace anyphys::schema

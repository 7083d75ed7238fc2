#pragma once
// One description per field. Each settings and def field is described once, in a table of
// Field rows (schema/*_fields.hpp): its scene-file key, unit, default, rule and who honours it.
// The rows drive validation (validation.hpp), scene files (containers/src/scene_json.cpp), the
// key tables of docs/scene-format.md (`anyphys schema --markdown`) and the capability parameter
// list (schema/parameters.hpp), so these cannot disagree about a field.
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
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
    Fraction,        ///< in [0, 1]; below 0 worded as ">= 0" (WorldSettings::baumgarte)
    UnitInterval,    ///< in [0, 1], one wording (Material::restitution)
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

/// Getter and setter of a member, for the `get` and `set` of a row.
template <class Def>
struct Access {
    std::function<Value(const Def&)> get;
    std::function<bool(Def&, const Value&)> set;
};

namespace detail {
template <class T> struct IsOptional : std::false_type {};
template <class T> struct IsOptional<std::optional<T>> : std::true_type { using type = T; };

template <class T>
Value toValue(const T& v) {
    if constexpr (std::is_enum_v<T>) return std::string(toString(v));
    else return v;
}
template <class T>
bool fromValue(const Value& v, T& out) {
    if constexpr (std::is_enum_v<T>) {
        const auto e = fromString<T>(std::get<std::string>(v));
        if (e) out = *e;
        return e.has_value();
    } else {
        out = std::get<T>(v);
        return true;
    }
}
}  // namespace detail

/// The accessors of a plain or optional member (enums through their names).
template <class Def, class M>
Access<Def> member(M Def::*m) {
    if constexpr (detail::IsOptional<M>::value) {
        using T = typename detail::IsOptional<M>::type;
        return {[m](const Def& d) -> Value { return d.*m ? detail::toValue(*(d.*m)) : Value{}; },
                [m](Def& d, const Value& v) {
                    if (std::holds_alternative<std::monostate>(v)) return (d.*m).reset(), true;
                    T out{};
                    if (!detail::fromValue(v, out)) return false;
                    d.*m = out;
                    return true;
                }};
    } else {
        return {[m](const Def& d) -> Value { return detail::toValue(d.*m); },
                [m](Def& d, const Value& v) { return detail::fromValue(v, d.*m); }};
    }
}

/// A row with the accessors of `access` (a designated-initialiser row cannot take them from a helper).
template <class Def>
Field<Def> with(Field<Def> row, Access<Def> access, std::string (*allowed)() = nullptr) {
    row.get = std::move(access.get);
    row.set = std::move(access.set);
    row.allowed = allowed;
    return row;
}

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
        case Check::Fraction:
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

namespace detail {
/// One scalar against a scalar rule, with the wording of validation.hpp.
inline void checkNumber(Check check, double bound, std::string_view words, const std::string& field, double v) {
    using namespace anyphys::detail;
    switch (check) {
        case Check::Finite: requireFinite(field, v); break;
        case Check::Positive: requirePositive(field, v); break;
        case Check::NonNegative: requireNonNegative(field, v); break;
        case Check::Fraction:
            requireNonNegative(field, v);
            if (v > 1) throw Error::invalid(field, v, "must be in [0, 1]");
            break;
        case Check::UnitInterval:
            if (!(std::isfinite(v) && v >= 0 && v <= 1)) throw Error::invalid(field, v, "must be in [0, 1]");
            break;
        case Check::Within:
            requireFinite(field, v);
            if (std::abs(v) > bound) throw Error::invalid(field, v, "must be within +-" + ceilingText(bound));
            break;
        case Check::Coordinate: requireCoordinate(field, v); break;
        case Check::Length: requireLength(field, v); break;
        case Check::LengthOrZero: requireLength(field, v, true); break;
        case Check::TimeStep: requireTimeStep(field, v); break;
        case Check::PositiveAtMost:
            requirePositive(field, v);
            if (v > bound) throw Error::invalid(field, v, "must be <= " + ceilingText(bound) + std::string(words));
            break;
        default: break;
    }
}
}  // namespace detail

/// Checks one value of a row; `field` names it in messages ("settings.timeStep"). Unset
/// optionals pass (absent means the default).
template <class Def>
void checkValue(const Field<Def>& f, const Value& value, const std::string& field) {
    using namespace anyphys::detail;
    if (const double* d = std::get_if<double>(&value)) return detail::checkNumber(f.check, f.bound, f.words, field, *d);
    if (const int* n = std::get_if<int>(&value)) {
        if (f.check == Check::CountIn && (*n < 1 || *n > f.bound))
            throw Error::invalid(field, *n, "must be in [1, " + std::to_string(static_cast<int>(f.bound)) + "]" + std::string(f.words));
        return;
    }
    if (const Vec3* v = std::get_if<Vec3>(&value)) {
        switch (f.check) {
            case Check::Finite: return requireFinite(field, *v);
            case Check::Coordinate: return requireCoordinate(field, *v);
            case Check::Magnitude:
                requireFinite(field, *v);
                if (v->norm() > f.bound)
                    throw Error::invalid(field, formatVec3(*v), "magnitude must be <= " + ceilingText(f.bound) + std::string(f.words));
                return;
            case Check::Direction:
                requireFinite(field, *v);
                if (v->norm() < 1e-12) throw Error::invalid(field, formatVec3(*v), "must be non-zero");
                return;
            default:
                for (int i = 0; i < 3; ++i) detail::checkNumber(f.check, f.bound, f.words, field + "[" + std::to_string(i) + "]", (*v)[i]);
                return;
        }
    }
    if (const Quat* q = std::get_if<Quat>(&value)) {
        if (f.check == Check::UnitQuaternion &&
            (!q->coeffs().allFinite() || std::abs(q->norm() - 1.0) > kUnitQuaternionTolerance))
            throw Error::invalid(field, formatQuat(*q), "must be a unit quaternion [w, x, y, z] (norm 1 within 1e-4)");
        return;
    }
    if (const std::string* s = std::get_if<std::string>(&value))
        if (f.check == Check::NonEmpty && s->empty()) throw Error::invalid(field, "\"\"", std::string(f.words));
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

/// Bit of a shape type in Field::types.
constexpr std::uint32_t bit(ShapeType t) { return 1u << static_cast<unsigned>(t); }

}  // namespace anyphys::schema

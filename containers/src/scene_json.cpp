// Scene files: JSON <-> Scene. Every error names the JSON path, the offending value and the rule
// ("bodies[3].shape.radius: must be > 0, got -1"); unknown and duplicate keys are errors too, so
// a typo never silently falls back to a default.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "anyphys/containers/assembly.hpp"
#include "anyphys/containers/mass_regularization.hpp"
#include "anyphys/containers/scene.hpp"
#include "anyphys/effects.hpp"
#include "anyphys/enums.hpp"
#include "anyphys/error.hpp"
#include "anyphys/fields/field_def.hpp"
#include "anyphys/fields/particle_defs.hpp"
#include "anyphys/joint_validation.hpp"
#include "anyphys/fields/schema_fields.hpp"
#include "anyphys/schema/body_fields.hpp"
#include "anyphys/schema/joint_fields.hpp"
#include "anyphys/schema/material_fields.hpp"
#include "anyphys/schema/settings_fields.hpp"
#include "anyphys/validation.hpp"

namespace anyphys {

namespace {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;  // keeps the written key order readable

// The name of the document itself in error messages (loadScene replaces it with the file path).
constexpr std::string_view kRoot = "scene";


std::string join(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}
std::string at(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }
std::string label(const std::string& path) { return path.empty() ? std::string(kRoot) : path; }

// A value as the user wrote it, shortened so one error stays one line.
std::string show(const json& v) {
    std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return s;
}

[[noreturn]] void fail(const std::string& path, const json& value, const std::string& rule) {
    throw Error::invalid(label(path), show(value), rule);
}

// The document's shape is wrong (a string where a number belongs, an unknown key): a parse error.
[[noreturn]] void malformed(const std::string& path, const json& value, const std::string& rule) {
    throw Error::invalid(label(path), show(value), rule, ErrorKind::Parse);
}

std::string list(const std::vector<std::string_view>& names) {
    std::string out;
    for (auto n : names) out += (out.empty() ? "" : ", ") + std::string(n);
    return out;
}

std::string effectNames() {
    std::string out;
    for (const auto& e : kEffectNames) out += (out.empty() ? "" : ", ") + std::string(e.name);
    return out;
}

void requireObject(const json& v, const std::string& path, const std::string& what = "a JSON object") {
    if (!v.is_object()) malformed(path, v, "must be " + what);
}

void checkKeys(const json& obj, const std::string& path, const std::vector<std::string_view>& allowed,
               const std::string& context = "") {
    for (const auto& [key, value] : obj.items()) {
        bool known = false;
        for (auto a : allowed) known = known || key == a;
        if (!known)
            throw Error(ErrorKind::Parse, join(path, key),
                        join(path, key) + ": unknown key" + context + "; allowed keys are " + list(allowed));
    }
}

[[noreturn]] void missing(const std::string& path, const std::string& why) {
    throw Error(ErrorKind::Parse, path, path + ": required key is missing; " + why);
}

// Every optional key is read the same way: absent leaves the def's default in place.
const json* find(const json& obj, std::string_view key) {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
}

double readNumber(const json& v, const std::string& path) {
    if (!v.is_number()) malformed(path, v, "must be a number");
    return v.get<double>();
}

int readCount(const json& v, const std::string& path) {
    // Accepts 3 and 3.0 alike; anything fractional, negative or beyond int is refused.
    const bool integral = v.is_number() && std::floor(v.get<double>()) == v.get<double>();
    if (!integral || v.get<double>() < 1 || v.get<double>() > std::numeric_limits<int>::max())
        fail(path, v, "must be an integer >= 1");
    return static_cast<int>(v.get<double>());
}

// Vertex indices, layer and mask bits. Accepts 3 and 3.0 alike, as counts do.
std::uint32_t readUint32(const json& v, const std::string& path, const std::string& rule) {
    const bool integral = v.is_number() && std::floor(v.get<double>()) == v.get<double>();
    if (!integral || v.get<double>() < 0 || v.get<double>() > std::numeric_limits<std::uint32_t>::max())
        fail(path, v, rule + " in [0, 4294967295]");
    return static_cast<std::uint32_t>(v.get<double>());
}

bool readBool(const json& v, const std::string& path) {
    if (!v.is_boolean()) malformed(path, v, "must be true or false");
    return v.get<bool>();
}

// Names, references and paths: none holds a control character. A name is written into the
// tools' CSV and reports as it is, where a NUL or an escape sequence would corrupt the output.
std::string readString(const json& v, const std::string& path) {
    if (!v.is_string()) malformed(path, v, "must be a string");
    std::string text = v.get<std::string>();
    const auto control = std::find_if(text.begin(), text.end(), [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return u < 0x20 || u == 0x7F;
    });
    if (control != text.end()) {
        char code[8];
        std::snprintf(code, sizeof code, "U+%04X", static_cast<unsigned>(static_cast<unsigned char>(*control)));
        fail(path, v, "must not hold control characters (found " + std::string(code) + " at byte " +
                          std::to_string(control - text.begin()) + ")");
    }
    return text;
}

Vec3 readVec3(const json& v, const std::string& path) {
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
        malformed(path, v, "must be an array of 3 numbers");
    return Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
}

Quat readQuat(const json& v, const std::string& path) {
    bool ok = v.is_array() && v.size() == 4;
    for (std::size_t i = 0; ok && i < 4; ++i) ok = v[i].is_number();
    if (!ok) malformed(path, v, "must be an array of 4 numbers [w, x, y, z]");
    // Kept as written (not normalised here) so that save/load reproduces the exact bits.
    return Quat(v[0].get<double>(), v[1].get<double>(), v[2].get<double>(), v[3].get<double>());
}

template <class E>
E readEnum(const json& v, const std::string& path) {
    const auto e = v.is_string() ? fromString<E>(v.get<std::string>()) : std::nullopt;
    if (!e) fail(path, v, "must be one of " + allowedNames<E>());
    return *e;
}

CombineRule readRule(const json& v, const std::string& path) {
    const auto r = v.is_string() ? combineRuleFromString(v.get<std::string>()) : std::nullopt;
    if (!r) fail(path, v, "must be one of " + combineRuleNames());
    return *r;
}

// ---- fields described by the table (anyphys/schema) ---------------------------------------------
// Keys, reading and writing of the rows of WorldSettings, BodyDef, ShapeDef and Material come
// from their rows; the rows marked ownCode (required keys, objects, names to resolve) are read
// and written by the code of their def below.

template <class Def, class Keep>
std::vector<std::string_view> rowKeys(const std::vector<schema::Field<Def>>& rows, Keep keep) {
    std::vector<std::string_view> keys;
    for (const auto& f : rows)
        if (keep(f)) keys.push_back(f.key);
    return keys;
}

template <class Def>
std::vector<std::string_view> rowKeys(const std::vector<schema::Field<Def>>& rows) {
    return rowKeys(rows, [](const auto&) { return true; });
}

// One value in the JSON spelling of its row's type.
template <class Def>
schema::Value readValue(const schema::Field<Def>& f, const json& v, const std::string& path) {
    using schema::Type;
    switch (f.type) {
        case Type::Number: return readNumber(v, path);
        case Type::Count: return readCount(v, path);
        case Type::Bits: return readUint32(v, path, "must be an unsigned 32-bit integer");
        case Type::Vec3: return readVec3(v, path);
        case Type::Quat: return readQuat(v, path);
        case Type::Bool: return readBool(v, path);
        case Type::String: return readString(v, path);
        case Type::Enum:
            if (!v.is_string()) fail(path, v, "must be one of " + f.allowed());
            return v.get<std::string>();
        case Type::Object: break;
    }
    malformed(path, v, "has no generic reader");  // unreachable: Object rows are ownCode
}

// Reads the rows `keep` selects that `v` carries into `def`; absent keys keep the def's default.
template <class Def, class Keep>
void readFields(const json& v, const std::string& path, const std::vector<schema::Field<Def>>& rows, Def& def,
                Keep keep) {
    for (const auto& f : rows) {
        if (f.ownCode || !f.set || !keep(f)) continue;
        if (const auto* x = find(v, f.key)) {
            const std::string p = join(path, f.key);
            if (!f.set(def, readValue(f, *x, p))) fail(p, *x, "must be one of " + f.allowed());
        }
    }
}

ojson toJson(const schema::Value& value);

// Bitwise equal (so -0.0 differs from 0.0 and is written).
bool sameBits(const schema::Value& a, const schema::Value& b);

// Writes the rows `keep` selects, each as its Save rule says; `own(key)` writes an ownCode row.
template <class Def, class Keep, class Own>
void writeFields(ojson& j, const std::vector<schema::Field<Def>>& rows, const Def& def, Keep keep, Own own) {
    for (const auto& f : rows) {
        if (!keep(f)) continue;
        if (f.ownCode) {
            own(f.key);
            continue;
        }
        const schema::Value value = f.get(def);
        const bool write = f.save == schema::Save::Always ||
                           (f.save == schema::Save::WhenSet && !std::holds_alternative<std::monostate>(value)) ||
                           (f.save == schema::Save::WhenNotDefault && !sameBits(value, f.value));
        if (write) j[std::string(f.key)] = toJson(value);
    }
}

WorldSettings readSettings(const json& v, const std::string& path) {
    requireObject(v, path);
    const auto& rows = schema::settingsFields();
    checkKeys(v, path, rowKeys(rows));
    WorldSettings s;
    readFields(v, path, rows, s, [](const auto&) { return true; });
    if (auto* x = find(v, "effects")) {
        const std::string p = join(path, "effects");
        if (!x->is_array()) fail(p, *x, "must be an array of effect names (" + effectNames() + ")");
        Effects effects;  // an empty array is meaningful: simulate nothing
        for (std::size_t i = 0; i < x->size(); ++i) {
            const auto& e = (*x)[i];
            const auto effect = e.is_string() ? effectFromString(e.get<std::string>()) : std::nullopt;
            if (!effect) fail(at(p, i), e, "must be one of " + effectNames());
            effects.add(*effect);
        }
        s.effects = effects;
    }
    if (auto* x = find(v, "backendOptions")) {
        const std::string p = join(path, "backendOptions");
        requireObject(*x, p, "an object of option names to numbers");
        for (const auto& [name, value] : x->items()) s.backendOptions[name] = readNumber(value, join(p, name));
    }
    validate(s, path);
    return s;
}

Material readMaterial(const json& v, const std::string& path) {
    requireObject(v, path);
    const auto& rows = schema::materialFields();
    checkKeys(v, path, rowKeys(rows));
    Material m;
    readFields(v, path, rows, m, [](const auto&) { return true; });
    return m;
}

std::string readMaterialName(const json& v, const std::string& path, const MaterialLibrary& lib) {
    const std::string name = readString(v, path);
    if (!lib.contains(name)) fail(path, v, "must name a material defined in \"materials\" (known: " + lib.knownNames() + ")");
    return name;
}

void readMaterials(const json& doc, MaterialLibrary& lib) {
    if (auto* v = find(doc, "materials")) {
        requireObject(*v, "materials", "an object of material names to {friction, restitution, density}");
        for (const auto& [name, value] : v->items()) {
            // The key "" redefines the default material; the path shows it as materials."".
            const std::string path = "materials." + (name.empty() ? std::string("\"\"") : name);
            lib.add(name, readMaterial(value, path));  // add() checks ranges under this same path
        }
    }
    if (auto* v = find(doc, "materialRules")) {
        requireObject(*v, "materialRules");
        checkKeys(*v, "materialRules", {"friction", "restitution"});
        if (auto* x = find(*v, "friction")) lib.setFrictionRule(readRule(*x, "materialRules.friction"));
        if (auto* x = find(*v, "restitution")) lib.setRestitutionRule(readRule(*x, "materialRules.restitution"));
    }
    if (auto* v = find(doc, "materialPairs")) {
        if (!v->is_array()) fail("materialPairs", *v, "must be an array of {a, b, friction, restitution} objects");
        std::map<std::pair<std::string, std::string>, std::size_t> seen;
        for (std::size_t i = 0; i < v->size(); ++i) {
            const json& pair = (*v)[i];
            const std::string path = at("materialPairs", i);
            requireObject(pair, path);
            checkKeys(pair, path, {"a", "b", "friction", "restitution"});
            for (const char* key : {"a", "b"})
                if (!find(pair, key)) missing(join(path, key), "a pair names two materials \"a\" and \"b\"");
            const std::string a = readMaterialName(pair["a"], join(path, "a"), lib);
            const std::string b = readMaterialName(pair["b"], join(path, "b"), lib);
            const auto key = a < b ? std::pair(a, b) : std::pair(b, a);
            if (const auto it = seen.find(key); it != seen.end())
                throw Error(ErrorKind::InvalidArgument, path, path + ": duplicate pair (\"" + a + "\", \"" + b + "\"); already given at " +
                            at("materialPairs", it->second));
            seen.emplace(key, i);
            PairOverride o;
            if (auto* x = find(pair, "friction")) o.friction = readNumber(*x, join(path, "friction"));
            if (auto* x = find(pair, "restitution")) o.restitution = readNumber(*x, join(path, "restitution"));
            validate(o, path);
            lib.setPairOverride(a, b, o);
        }
    }
}

// The rows a shape of this type has (its own keys, then placement), children's rows aside.
auto shapeRow(ShapeType type) {
    return [type](const schema::Field<ShapeDef>& f) { return !f.childOnly && (f.types & schema::bit(type)) != 0; };
}

std::vector<Vec3> readPoints(const json& v, const std::string& path) {
    if (!v.is_array()) fail(path, v, "must be an array of [x, y, z] points");
    std::vector<Vec3> points;
    points.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) points.push_back(readVec3(v[i], at(path, i)));
    return points;
}

std::vector<std::uint32_t> readIndices(const json& v, const std::string& path) {
    if (!v.is_array()) fail(path, v, "must be a flat array of vertex indices, three per triangle");
    std::vector<std::uint32_t> indices;
    indices.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
        indices.push_back(readUint32(v[i], at(path, i), "must be a non-negative integer (a vertex index)"));
    return indices;
}

// A child's surface overrides; `lib` checks the material name as a body's is checked.
void readChildSurface(const json& v, const std::string& path, const MaterialLibrary& lib, ShapeDef& s) {
    readFields(v, path, schema::shapeFields(), s, [](const auto& f) { return f.childOnly; });
    if (auto* x = find(v, "material")) s.material = readMaterialName(*x, join(path, "material"), lib);
}

// `child`: an element of a compound's "shapes", which may also carry its own density and surface.
ShapeDef readShape(const json& v, const std::string& path, const MaterialLibrary& lib, bool child = false) {
    requireObject(v, path);
    const auto* typeValue = find(v, "type");
    if (!typeValue) missing(join(path, "type"), "allowed types are " + allowedNames<ShapeType>());
    ShapeDef s;
    s.type = readEnum<ShapeType>(*typeValue, join(path, "type"));
    // Each shape type has its own keys; a key of another type is a mistake worth reporting.
    const auto& rows = schema::shapeFields();
    const auto own = shapeRow(s.type);
    std::vector<std::string_view> allowed = rowKeys(rows, own);
    const auto childKeys = rowKeys(rows, [](const auto& f) { return f.childOnly; });
    if (child) allowed.insert(allowed.end(), childKeys.begin(), childKeys.end());
    if (!child)
        for (std::string_view key : childKeys)
            if (find(v, key)) {
                const std::string field = join(path, std::string(key));
                throw Error(ErrorKind::Parse, field, field + ": allowed only on the children of a compound shape; the body's \"" +
                                                         std::string(key) + "\" applies to its whole shape");
            }
    checkKeys(v, path, allowed, " for a " + std::string(toString(s.type)) + " shape");
    // The sizes (and a hull's points, ...) have no default: a box without halfExtents is a
    // mistake to report, not a 1 m cube. A plane has no size: its normal defaults to up (+Y,
    // against the default gravity) and its offset to 0.
    for (const auto& f : rows)
        if (f.required && f.key != "type" && own(f) && !find(v, f.key))
            missing(join(path, std::string(f.key)),
                    "a " + std::string(toString(s.type)) + " shape needs it (there is no default)");

    readFields(v, path, rows, s, own);
    if (auto* x = find(v, "points")) s.points = readPoints(*x, join(path, "points"));
    if (auto* x = find(v, "vertices")) s.vertices = readPoints(*x, join(path, "vertices"));
    if (auto* x = find(v, "indices")) s.indices = readIndices(*x, join(path, "indices"));
    if (auto* x = find(v, "shapes")) {
        const std::string p = join(path, "shapes");
        if (!x->is_array()) fail(p, *x, "must be an array of child shape objects");
        for (std::size_t i = 0; i < x->size(); ++i) s.shapes.push_back(readShape((*x)[i], at(p, i), lib, true));
    }
    if (child) readChildSurface(v, path, lib, s);
    // Ranges (radius > 0, hull not flat, indices in range, ...) are checked by validate(BodyDef).
    return s;
}

BodyDef readBody(const json& v, const std::string& path, const MaterialLibrary& lib) {
    requireObject(v, path);
    const auto& rows = schema::bodyFields();
    checkKeys(v, path, rowKeys(rows));
    BodyDef b;
    const auto* name = find(v, "name");
    if (!name) missing(join(path, "name"), "every body needs a non-empty, unique name");
    b.name = readString(*name, join(path, "name"));
    if (b.name.empty()) fail(join(path, "name"), *name, "must be a non-empty string");
    const auto* shape = find(v, "shape");
    if (!shape) missing(join(path, "shape"), "every body needs a shape, e.g. {\"type\": \"sphere\", \"radius\": 0.5}");
    readFields(v, path, rows, b, [](const auto&) { return true; });
    b.shape = readShape(*shape, join(path, "shape"), lib);
    if (auto* x = find(v, "material")) b.material = readMaterialName(*x, join(path, "material"), lib);
    // userData is read by the scene, which keeps its JSON text by body name.
    validate(b, path);  // the same range rules, in the same words, as World::createBody
    return b;
}

// ---- fields -----------------------------------------------------------------------------------

// The rows of a field of this type (the others keep their defaults, and are neither read nor written).
auto ofFieldType(FieldType type) {
    return [type](const schema::Field<FieldDef>& f) { return (f.types & schema::bit(type)) != 0; };
}

FieldDef readField(const json& v, const std::string& path, bool planar) {
    requireObject(v, path);
    const auto* typeValue = find(v, "type");
    if (!typeValue) missing(join(path, "type"), "allowed types are " + fieldTypeNames());
    const auto type = typeValue->is_string() ? fieldTypeFromString(typeValue->get<std::string>()) : std::nullopt;
    if (!type) fail(join(path, "type"), *typeValue, "must be one of " + fieldTypeNames());
    const auto& rows = schema::fieldDefFields();
    checkKeys(v, path, rowKeys(rows, ofFieldType(*type)), " for a " + std::string(toString(*type)) + " field");
    FieldDef f;
    f.type = *type;
    for (const auto& row : rows) {
        if (!row.ownCode) {
            readFields(v, path, rows, f, [&row](const auto& g) { return &g == &row; });
        } else if (const auto* x = row.key == "surface" ? find(v, "surface") : nullptr) {
            const std::string p = join(path, "surface");
            requireObject(*x, p, "an object {\"normal\": [x, y, z], \"offset\": d}");
            checkKeys(*x, p, rowKeys(schema::fieldSurfaceFields()));
            readFields(*x, p, schema::fieldSurfaceFields(), f, [](const auto&) { return true; });
        }
    }
    validate(f, path);  // the same range rules, in the same words, as World::addField
    if (planar) {
        const auto inPlane = [&](const std::string& key, const Vec3& value) {
            if (std::abs(value.z()) > 1e-9 * std::max(1.0, value.norm()))
                throw Error::invalid(join(path, key), formatVec3(value), "must lie in the XY plane (z = 0) in a planar world");
        };
        if (f.type == FieldType::Buoyancy) inPlane("surface.normal", f.surfaceNormal);
        if (f.type == FieldType::Wind) inPlane("velocity", f.velocity);
        if (f.type == FieldType::Explosion) inPlane("center", f.center);
    }
    return f;
}

// ---- fluids and cloths --------------------------------------------------------------------------

FluidDef readFluid(const json& v, const std::string& path, bool planar) {
    requireObject(v, path);
    const auto& rows = schema::fluidDefFields();
    checkKeys(v, path, rowKeys(rows), " for a fluid");
    FluidDef f;
    readFields(v, path, rows, f, [](const auto& row) { return row.key == "name"; });
    const auto* box = find(v, "box");
    if (!box) missing(join(path, "box"), "a fluid fills a box {\"min\": [x, y, z], \"max\": [x, y, z]}");
    const std::string p = join(path, "box");
    requireObject(*box, p, "an object {\"min\": [x, y, z], \"max\": [x, y, z]}");
    checkKeys(*box, p, rowKeys(schema::fluidBoxFields()));
    if (!find(*box, "min") || !find(*box, "max")) missing(p, "a box needs both \"min\" and \"max\"");
    readFields(*box, p, schema::fluidBoxFields(), f, [](const auto&) { return true; });
    readFields(v, path, rows, f, [](const auto& row) { return row.key != "name"; });
    validate(f, path);  // the same rules, in the same words, as World::addFluid
    (void)planar;       // a planar fluid is the slab of its box's depth: any box will do
    return f;
}

std::array<int, 2> readIndexPair(const json& v, const std::string& path, const std::string& what) {
    const auto integral = [](const json& x) {
        return x.is_number() && std::floor(x.get<double>()) == x.get<double>() && std::abs(x.get<double>()) < 1e9;
    };
    if (!v.is_array() || v.size() != 2 || !integral(v[0]) || !integral(v[1])) malformed(path, v, "must be " + what);
    return {static_cast<int>(v[0].get<double>()), static_cast<int>(v[1].get<double>())};
}

ClothDef readCloth(const json& v, const std::string& path, bool planar) {
    requireObject(v, path);
    const auto& rows = schema::clothDefFields();
    checkKeys(v, path, rowKeys(rows), " for a cloth");
    ClothDef c;
    readFields(v, path, rows, c, [](const auto& row) { return row.key == "name" || row.key == "corner"; });
    if (auto* x = find(v, "size")) {
        if (!x->is_array() || x->size() != 2 || !(*x)[0].is_number() || !(*x)[1].is_number())
            malformed(join(path, "size"), *x, "must be an array of 2 numbers [along axisU, along axisV]");
        c.size = {(*x)[0].get<double>(), (*x)[1].get<double>()};
    }
    if (auto* x = find(v, "resolution")) c.resolution = readIndexPair(*x, join(path, "resolution"), "an array of 2 integers [cells along U, cells along V]");
    readFields(v, path, rows, c, [](const auto& row) { return row.key != "name" && row.key != "corner"; });
    if (auto* x = find(v, "pinned")) {
        if (!x->is_array()) malformed(join(path, "pinned"), *x, "must be an array of node indices [[i, j], ...]");
        for (std::size_t n = 0; n < x->size(); ++n)
            c.pinned.push_back(readIndexPair((*x)[n], at(join(path, "pinned"), n), "a node index pair [i, j]"));
    }
    validate(c, path);  // the same rules, in the same words, as World::addCloth
    if (planar) {
        const auto inPlane = [&](const char* key, const Vec3& value) {
            if (std::abs(value.z()) > 1e-9 * std::max(1.0, value.norm()))
                throw Error::invalid(join(path, key), formatVec3(value),
                                     "must lie in the XY plane (z = 0) in a planar world: the sheet then moves in the plane");
        };
        inPlane("corner", c.corner);
        inPlane("axisU", c.axisU);
        inPlane("axisV", c.axisV);
    }
    return c;
}

// ---- joints -----------------------------------------------------------------------------------

JointLimits readLimits(const json& v, const std::string& path) {
    requireObject(v, path, "an object {\"lower\": ..., \"upper\": ...}");
    const auto& rows = schema::jointLimitsFields();
    checkKeys(v, path, rowKeys(rows));
    JointLimits l;
    if (!find(v, "lower") || !find(v, "upper")) missing(path, "limits need both \"lower\" and \"upper\"");
    readFields(v, path, rows, l, [](const auto&) { return true; });
    return l;
}

JointMotor readMotor(const json& v, const std::string& path) {
    requireObject(v, path, "an object {\"speed\": ..., \"maxForce\": ...}");
    const auto& rows = schema::jointMotorFields();
    checkKeys(v, path, rowKeys(rows));
    JointMotor m;
    readFields(v, path, rows, m, [](const auto&) { return true; });
    return m;
}

JointSpring readSpring(const json& v, const std::string& path) {
    requireObject(v, path, "an object {\"stiffness\", \"damping\"} or {\"hertz\", \"dampingRatio\"}");
    const auto& rows = schema::jointSpringFields();
    checkKeys(v, path, rowKeys(rows));
    JointSpring sp;
    readFields(v, path, rows, sp, [](const auto&) { return true; });
    return sp;
}

/// A body's or joint's "userData": any JSON value, kept as text for the game and saved back; an
/// unsigned integer is also the def's userData (what Body::userData returns).
std::uint64_t readUserData(const json& v, std::string& text) {
    text = v.dump();
    return v.is_number_unsigned() ? v.get<std::uint64_t>() : 0;
}

// The userData a body or joint is saved with: its JSON text, else a non-zero def value.
void writeUserData(ojson& j, const std::string& text, std::uint64_t value) {
    if (!text.empty())
        j["userData"] = ojson::parse(text);
    else if (value != 0)
        j["userData"] = value;
}

/// One joint; its bodies must name bodies of the scene (`bodies`: name -> def).
SceneJoint readJoint(const json& v, const std::string& path, const std::map<std::string, const BodyDef*>& bodies,
                     const WorldSettings& settings) {
    const bool planar = settings.planar;
    requireObject(v, path);
    const auto& rows = schema::jointDefFields();
    checkKeys(v, path, rowKeys(rows));
    SceneJoint out;
    JointDef& d = out.def;
    // The name first: later messages may name the joint.
    readFields(v, path, rows, d, [](const auto& f) { return f.key == "name"; });
    const auto* type = find(v, "type");
    if (!type) missing(join(path, "type"), "every joint needs a type: " + allowedNames<JointType>());
    d.type = readEnum<JointType>(*type, join(path, "type"));
    const auto body = [&](std::string_view key, bool required) -> std::string {
        const std::string field = join(path, key);
        const auto* x = find(v, key);
        if (!x) {
            if (required) missing(field, "every joint needs the name of the body it holds");
            return "";
        }
        const std::string name = readString(*x, field);
        if (!required && name == "world") {
            if (bodies.contains(name))
                throw Error(ErrorKind::InvalidArgument, field,
                            field + ": \"world\" names both the static world and a body of the scene; omit " +
                                std::string(key) + " to hold the joint to the world, or rename the body");
            return "";
        }
        if (!bodies.contains(name)) throw Error(ErrorKind::InvalidArgument, field, field + ": no body named \"" + name + "\"");
        return name;
    };
    out.bodyA = body("bodyA", false);
    out.bodyB = body("bodyB", true);
    // Every key in the rows' order: those of rows by their rows, the objects by their readers.
    for (const auto& f : rows) {
        if (f.key == "name" || !f.ownCode) {
            readFields(v, path, rows, d, [&f](const auto& g) { return &g == &f && g.key != "name"; });
            continue;
        }
        const auto* x = find(v, f.key);
        if (!x) continue;
        const std::string p = join(path, f.key);
        if (f.key == "twistLimits") d.twistLimits = readLimits(*x, p);
        if (f.key == "limits") d.limits = readLimits(*x, p);
        if (f.key == "motor") d.motor = readMotor(*x, p);
        if (f.key == "spring") d.spring = readSpring(*x, p);
    }
    // The same rules, in the same words, as World::createJoint.
    validate(d, path);
    if (planar) validatePlanar(d, path);
    if (d.motor) validateJointMotorSpeed(*d.motor, d.type, settings.maxSpeed, settings.maxAngularSpeed, join(path, "motor"));
    const auto view = [&bodies](const std::string& name) {
        const BodyDef& b = *bodies.at(name);
        return JointBodyView{b.name, b.type};
    };
    validateJointBodies(out.bodyA.empty() ? std::nullopt : std::optional<JointBodyView>(view(out.bodyA)),
                        view(out.bodyB), out.bodyA == out.bodyB, path);
    return out;
}

// Objects and arrays nested deeper than this are refused as they are read. A scene's own keys nest
// six deep and userData is the game's, but each level's path names its parents, so without a
// bound a file of 200 000 nested arrays (400 KB) took tens of gigabytes before it was refused.
constexpr std::size_t kMaxJsonDepth = 256;

// The path of a deeply nested value, shortened to its start: one line of error, not a page.
std::string shortened(const std::string& path) {
    constexpr std::size_t kShown = 80;
    return path.size() <= kShown ? path : path.substr(0, kShown) + "...";
}

// nlohmann keeps the last of two equal keys silently; this callback refuses them instead,
// naming the JSON path of the repeated key. It also refuses nesting past kMaxJsonDepth.
class DuplicateKeyCheck {
public:
    bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start: push(true); break;
            case json::parse_event_t::array_start: push(false); break;
            case json::parse_event_t::key: {
                Frame& f = stack_.back();
                f.key = parsed.get<std::string>();
                if (!f.keys.insert(f.key).second)
                    throw Error(ErrorKind::Parse, join(f.path, f.key),
                                join(f.path, f.key) + ": duplicate key; each key may appear once in an object");
                break;
            }
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                stack_.pop_back();
                advance();
                break;
            case json::parse_event_t::value: advance(); break;
        }
        return true;
    }

private:
    struct Frame {
        bool object = true;
        std::string path;
        std::set<std::string> keys;
        std::string key;     // objects: the key of the value being read
        std::size_t index = 0;  // arrays: the index of the value being read
    };
    void push(bool object) {
        std::string path;
        if (!stack_.empty()) {
            const Frame& parent = stack_.back();
            // Elements of a top-level array are named "scene[0]", never a bare "[0]".
            path = parent.object ? join(parent.path, parent.key) : at(label(parent.path), parent.index);
        }
        if (stack_.size() == kMaxJsonDepth) {
            const std::string where = shortened(path);
            throw Error(ErrorKind::Parse, where,
                        where + ": objects and arrays nested more than " + std::to_string(kMaxJsonDepth) +
                            " deep; a scene file may nest at most " + std::to_string(kMaxJsonDepth) + " (userData included)");
        }
        stack_.push_back(Frame{object, path, {}, {}, 0});
    }
    void advance() {
        if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
    }
    std::vector<Frame> stack_;
};

json parseJson(const std::string& text) {
    try {
        return json::parse(text, DuplicateKeyCheck());
    } catch (const json::exception& e) {
        // e.what() is "[json.exception.parse_error.101] parse error at line 3, column 5: ..."; keep
        // the position and the reason, drop nlohmann's prefixes.
        std::string what = e.what();
        if (const auto pos = what.find("at line "); pos != std::string::npos)
            throw Error(ErrorKind::Parse, "", std::string(kRoot) + ": invalid JSON " + what.substr(pos));
        if (const auto pos = what.find("] "); pos != std::string::npos) what = what.substr(pos + 2);
        throw Error(ErrorKind::Parse, "", std::string(kRoot) + ": invalid JSON: " + what);
    }
}

// ---- writing ---------------------------------------------------------------------------------

ojson vec(const Vec3& v) { return ojson::array({v.x(), v.y(), v.z()}); }

ojson quat(const Quat& q) { return ojson::array({q.w(), q.x(), q.y(), q.z()}); }

ojson points(const std::vector<Vec3>& list) {
    ojson j = ojson::array();
    for (const Vec3& p : list) j.push_back(vec(p));
    return j;
}

// Bitwise default (so -0.0 is written, and read back as -0.0).
bool isDefault(double x, double def) { return x == def && std::signbit(x) == std::signbit(def); }

ojson toJson(const schema::Value& value) {
    return std::visit(
        [](const auto& x) -> ojson {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, std::monostate>) return nullptr;
            else if constexpr (std::is_same_v<T, Vec3>) return vec(x);
            else if constexpr (std::is_same_v<T, Quat>) return quat(x);
            else return x;
        },
        value);
}

bool sameBits(const schema::Value& a, const schema::Value& b) {
    if (a.index() != b.index()) return false;
    if (const auto* x = std::get_if<double>(&a)) return isDefault(*x, std::get<double>(b));
    if (const auto* x = std::get_if<Vec3>(&a)) {
        const Vec3& y = std::get<Vec3>(b);
        return isDefault(x->x(), y.x()) && isDefault(x->y(), y.y()) && isDefault(x->z(), y.z());
    }
    if (const auto* x = std::get_if<Quat>(&a)) {
        const Quat& y = std::get<Quat>(b);
        return isDefault(x->w(), y.w()) && isDefault(x->x(), y.x()) && isDefault(x->y(), y.y()) && isDefault(x->z(), y.z());
    }
    if (const auto* x = std::get_if<int>(&a)) return *x == std::get<int>(b);
    if (const auto* x = std::get_if<std::uint32_t>(&a)) return *x == std::get<std::uint32_t>(b);
    if (const auto* x = std::get_if<bool>(&a)) return *x == std::get<bool>(b);
    if (const auto* x = std::get_if<std::string>(&a)) return *x == std::get<std::string>(b);
    return true;  // both unset
}

// Each shape writes the keys of its type; placement, a child's density and surface as their rows say.
ojson shapeJson(const ShapeDef& s) {
    ojson j;
    const auto own = [&](std::string_view key) {
        if (key == "type") j["type"] = std::string(toString(s.type));
        if (key == "points") j["points"] = points(s.points);
        if (key == "vertices") j["vertices"] = points(s.vertices);
        if (key == "indices") j["indices"] = s.indices;
        if (key == "shapes") {
            j["shapes"] = ojson::array();
            for (const ShapeDef& child : s.shapes) j["shapes"].push_back(shapeJson(child));
        }
        if (key == "material" && s.material) j["material"] = *s.material;
    };
    writeFields(j, schema::shapeFields(), s,
                [&s](const auto& f) { return f.childOnly || (f.types & schema::bit(s.type)) != 0; }, own);
    return j;
}

ojson bodyJson(const BodyDef& b) {
    ojson j;
    const auto own = [&](std::string_view key) {
        if (key == "name") j["name"] = b.name;
        if (key == "shape") j["shape"] = shapeJson(b.shape);
        if (key == "material") j["material"] = b.material;
        // userData: written by sceneToJson, which has the body's JSON text.
    };
    writeFields(j, schema::bodyFields(), b, [](const auto&) { return true; }, own);
    return j;
}

// A field writes the keys of its type.
ojson fieldJson(const FieldDef& f) {
    ojson j;
    const auto own = [&](std::string_view key) {
        if (key == "type") j["type"] = std::string(toString(f.type));
        if (key == "surface") {
            ojson surface;
            writeFields(surface, schema::fieldSurfaceFields(), f, [](const auto&) { return true; }, [](std::string_view) {});
            j["surface"] = surface;
        }
    };
    writeFields(j, schema::fieldDefFields(), f, ofFieldType(f.type), own);
    return j;
}

ojson fluidJson(const FluidDef& f) {
    ojson j;
    const auto own = [&](std::string_view key) {
        if (key != "box") return;
        ojson box;
        writeFields(box, schema::fluidBoxFields(), f, [](const auto&) { return true; }, [](std::string_view) {});
        j["box"] = box;
    };
    writeFields(j, schema::fluidDefFields(), f, [](const auto&) { return true; }, own);
    return j;
}

ojson clothJson(const ClothDef& c) {
    ojson j;
    const auto own = [&](std::string_view key) {
        if (key == "size") j["size"] = ojson::array({c.size[0], c.size[1]});
        if (key == "resolution") j["resolution"] = ojson::array({c.resolution[0], c.resolution[1]});
        if (key == "pinned") {
            j["pinned"] = ojson::array();
            for (const auto& p : c.pinned) j["pinned"].push_back(ojson::array({p[0], p[1]}));
        }
    };
    writeFields(j, schema::clothDefFields(), c, [](const auto&) { return true; }, own);
    return j;
}

ojson limitsJson(const JointLimits& l) {
    ojson j;
    writeFields(j, schema::jointLimitsFields(), l, [](const auto&) { return true; }, [](std::string_view) {});
    return j;
}

ojson jointJson(const SceneJoint& sj) {
    const JointDef& d = sj.def;
    ojson j;
    const auto own = [&](std::string_view key) {
        if (key == "type") j["type"] = std::string(toString(d.type));
        if (key == "bodyA" && !sj.bodyA.empty()) j["bodyA"] = sj.bodyA;
        if (key == "bodyB") j["bodyB"] = sj.bodyB;
        if (key == "twistLimits" && d.twistLimits) j["twistLimits"] = limitsJson(*d.twistLimits);
        if (key == "limits" && d.limits) j["limits"] = limitsJson(*d.limits);
        if (key == "motor" && d.motor) {
            ojson m;
            writeFields(m, schema::jointMotorFields(), *d.motor, [](const auto&) { return true; }, [](std::string_view) {});
            j["motor"] = m;
        }
        // A spring is written as the pair it is given by: stiffness and damping, or hertz and dampingRatio.
        if (key == "spring" && d.spring) {
            const bool hertz = d.spring->hertz > 0;
            ojson sp;
            writeFields(sp, schema::jointSpringFields(), *d.spring,
                        [hertz](const auto& f) { return (f.key == "hertz" || f.key == "dampingRatio") == hertz; },
                        [](std::string_view) {});
            j["spring"] = sp;
        }
        if (key == "userData") writeUserData(j, sj.userData, d.userData);
    };
    // Each type writes the keys it uses (infinite break thresholds, the default, have no JSON spelling
    // and are not written).
    writeFields(j, schema::jointDefFields(), d,
                [&d](const auto& f) { return f.ownCode || (f.types & schema::bit(d.type)) != 0; }, own);
    return j;
}

ojson settingsJson(const WorldSettings& s) {
    ojson j;
    const auto own = [&](std::string_view key) {
        if (key == "effects" && s.effects) j["effects"] = s.effects->names();
        if (key == "backendOptions") {
            j["backendOptions"] = ojson::object();
            for (const auto& [name, value] : s.backendOptions) j["backendOptions"][name] = value;
        }
    };
    writeFields(j, schema::settingsFields(), s, [](const auto&) { return true; }, own);
    return j;
}

ojson materialJson(const Material& m) {
    ojson j;
    writeFields(j, schema::materialFields(), m, [](const auto&) { return true; }, [](std::string_view) {});
    return j;
}

bool sameMaterialBits(const Material& a, const Material& b) {
    for (const auto& f : schema::materialFields())
        if (!sameBits(f.get(a), f.get(b))) return false;
    return true;
}

// Like dump(2), but arrays of plain values stay on one line: "position": [0, 10, 0].
void write(std::string& out, const ojson& v, int indent) {
    const std::string pad(indent + 2, ' ');
    const bool flat = v.is_array() && std::all_of(v.begin(), v.end(), [](const ojson& e) { return e.is_primitive(); });
    if (v.is_primitive() || v.empty()) {
        out += v.dump();
    } else if (flat) {
        out += '[';
        for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + v[i].dump();
        out += ']';
    } else if (v.is_object()) {
        out += "{\n";
        bool first = true;
        for (const auto& [key, value] : v.items()) {
            out += (first ? "" : ",\n") + pad + ojson(key).dump() + ": ";
            write(out, value, indent + 2);
            first = false;
        }
        out += "\n" + std::string(indent, ' ') + "}";
    } else {
        out += "[\n";
        for (std::size_t i = 0; i < v.size(); ++i) {
            out += (i ? ",\n" : "") + pad;
            write(out, v[i], indent + 2);
        }
        out += "\n" + std::string(indent, ' ') + "]";
    }
}

}  // namespace

namespace {

// Where a scene is being read from, for its instances: the options, the files being loaded
// (outermost first, to name a cycle) and how deep the nesting is.
struct LoadContext {
    SceneLoadOptions options;
    std::vector<std::string> chain;
    int depth = 0;
};

Scene loadSceneIn(const std::string& path, const LoadContext& context);

MassRegularization readRegularization(const json& v, const std::string& path) {
    requireObject(v, path);
    checkKeys(v, path, {"maxMassRatio", "raiseParentInertia"});
    MassRegularization options;
    if (auto* x = find(v, "maxMassRatio")) options.maxMassRatio = readNumber(*x, join(path, "maxMassRatio"));
    if (auto* x = find(v, "raiseParentInertia")) options.raiseParentInertia = readBool(*x, join(path, "raiseParentInertia"));
    validate(options, path + ".");
    return options;
}

std::string chainText(const std::vector<std::string>& chain, const std::string& last) {
    std::string out;
    for (const auto& file : chain) out += std::filesystem::path(file).filename().string() + " -> ";
    return out + std::filesystem::path(last).filename().string();
}

/// The scene an instance names: a built-in assembly, or a file under the including file's
/// folder (SceneLoadOptions says what else is allowed).
Scene instanceScene(const json& v, const std::string& path, const LoadContext& context) {
    const std::string name = readString(v, path);
    if (isBuiltinAssembly(name)) return builtinAssembly(name);
    const SceneLoadOptions& o = context.options;
    std::string known;
    for (const auto& n : builtinAssemblyNames()) known += (known.empty() ? "" : ", ") + n;
    if (o.folder.empty())
        fail(path, v, "must be a built-in assembly (" + known + "); a scene given as text has no folder to load files "
                      "from (load it from a file, or set SceneLoadOptions::folder)");
    namespace fs = std::filesystem;
    const fs::path given(name);
    if (given.is_absolute() && !o.allowOutsideFolder)
        fail(path, v, "must be a built-in assembly (" + known + ") or a path relative to the including file; absolute "
                      "paths are refused unless SceneLoadOptions::allowOutsideFolder is set");
    const fs::path folder = fs::path(o.folder).lexically_normal();
    const fs::path full = (folder / given).lexically_normal();
    const fs::path inside = full.lexically_relative(folder);
    if (!o.allowOutsideFolder && (inside.empty() || *inside.begin() == ".."))
        fail(path, v, "leaves the including file's folder; refused unless SceneLoadOptions::allowOutsideFolder is set");
    std::error_code ec;
    const std::string canonical = fs::weakly_canonical(full, ec).string();
    if (std::find(context.chain.begin(), context.chain.end(), canonical) != context.chain.end())
        fail(path, v, "instances form a cycle: " + chainText(context.chain, canonical));
    if (context.depth >= o.maxDepth)
        fail(path, v, "nests instances deeper than SceneLoadOptions::maxDepth (" + std::to_string(o.maxDepth) + ")");
    LoadContext inner = context;
    inner.options.folder = full.has_parent_path() ? full.parent_path().string() : ".";
    inner.chain.push_back(canonical);
    inner.depth = context.depth + 1;
    try {
        return loadSceneIn(full.string(), inner);
    } catch (const Error& e) {
        throw e.within(path);  // "instances[0].scene: parts/arm.json: bodies[2]..."
    }
}

void readInstances(const json& v, Scene& scene, const LoadContext& context) {
    if (!v.is_array()) fail("instances", v, "must be an array of instance objects");
    for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string path = at("instances", i);
        const json& item = v[i];
        requireObject(item, path);
        checkKeys(item, path, {"scene", "position", "orientation", "prefix", "regularize"});
        const auto* sceneName = find(item, "scene");
        if (!sceneName) missing(join(path, "scene"), "every instance names a scene file or a built-in assembly");
        Transform pose;
        if (auto* x = find(item, "position")) {
            pose.position = readVec3(*x, join(path, "position"));
            detail::requireCoordinate(join(path, "position"), pose.position);
        }
        if (auto* x = find(item, "orientation")) pose.orientation = readQuat(*x, join(path, "orientation"));
        std::string prefix;
        if (auto* x = find(item, "prefix")) prefix = readString(*x, join(path, "prefix"));
        Scene assembly = instanceScene(*sceneName, join(path, "scene"), context);
        if (auto* x = find(item, "regularize")) {
            const MassRegularization options = readRegularization(*x, join(path, "regularize"));
            try {
                regularizeMasses(assembly, options);
            } catch (const Error& e) {
                throw e.within(join(path, "regularize"));
            }
        }
        const std::size_t total = scene.bodies.size() + assembly.bodies.size();
        if (total > context.options.maxBodies)
            fail(path, *sceneName, "would bring the scene to " + std::to_string(total) +
                                       " bodies, more than SceneLoadOptions::maxBodies (" +
                                       std::to_string(context.options.maxBodies) + ")");
        const std::size_t firstBody = scene.bodies.size(), firstJoint = scene.joints.size();
        try {
            appendInstance(scene, assembly, pose, prefix);
        } catch (const Error& e) {
            throw e.within(path);
        }
        // A placed body or joint meets the rules of one written in the scene (a position within
        // kMaxCoordinate may still carry a body beyond it), so what is loaded also saves and loads again.
        for (std::size_t b = firstBody; b < scene.bodies.size(); ++b) {
            const std::string bodyPath = path + " body \"" + scene.bodies[b].name + "\"";
            validate(scene.bodies[b], bodyPath);
            validateLimits(scene.bodies[b], scene.settings, bodyPath, "settings");
        }
        for (std::size_t j = firstJoint; j < scene.joints.size(); ++j)
            validate(scene.joints[j].def, path + " joint " + std::to_string(j - firstJoint));
        if (scene.settings.planar) {
            for (std::size_t b = firstBody; b < scene.bodies.size(); ++b)
                validatePlanar(scene.bodies[b], path + " body \"" + scene.bodies[b].name + "\"");
            for (std::size_t j = firstJoint; j < scene.joints.size(); ++j)
                validatePlanar(scene.joints[j].def, path + " joint " + std::to_string(j - firstJoint));
        }
    }
}

Scene parseSceneIn(const std::string& jsonText, const LoadContext& context) {
    const json doc = parseJson(jsonText);
    requireObject(doc, "", "a JSON object with \"settings\", \"materials\", \"bodies\", ...");
    checkKeys(doc, "", {"settings", "materials", "materialRules", "materialPairs", "bodies", "instances", "joints", "fields",
                    "fluids", "cloths"},
              " at the top level");

    Scene scene;
    if (auto* v = find(doc, "settings")) scene.settings = readSettings(*v, "settings");
    readMaterials(doc, scene.materials);
    if (auto* v = find(doc, "bodies")) {
        if (!v->is_array()) fail("bodies", *v, "must be an array of body objects");
        std::map<std::string, std::size_t> names;
        for (std::size_t i = 0; i < v->size(); ++i) {
            BodyDef b = readBody((*v)[i], at("bodies", i), scene.materials);
            validateLimits(b, scene.settings, at("bodies", i), "settings");
            if (scene.settings.planar) validatePlanar(b, at("bodies", i));
            if (const auto it = names.find(b.name); it != names.end())
                fail(at("bodies", i) + ".name", (*v)[i]["name"],
                     "must be unique (already used by " + at("bodies", it->second) + ")");
            names.emplace(b.name, i);
            if (auto* x = find((*v)[i], "userData")) b.userData = readUserData(*x, scene.bodyUserData[b.name]);
            scene.bodies.push_back(std::move(b));
        }
    }
    // Before the joints: the scene's own joints may hold instance bodies ("r1/hand_l").
    if (auto* v = find(doc, "instances")) readInstances(*v, scene, context);
    if (auto* v = find(doc, "joints")) {
        if (!v->is_array()) fail("joints", *v, "must be an array of joint objects");
        std::map<std::string, const BodyDef*> bodies;
        for (const BodyDef& b : scene.bodies) bodies.emplace(b.name, &b);
        std::map<std::string, std::size_t> names;
        for (const SceneJoint& j : scene.joints)
            if (!j.def.name.empty()) names.emplace(j.def.name, std::numeric_limits<std::size_t>::max());
        for (std::size_t i = 0; i < v->size(); ++i) {
            SceneJoint j = readJoint((*v)[i], at("joints", i), bodies, scene.settings);
            if (auto* x = find((*v)[i], "userData")) j.def.userData = readUserData(*x, j.userData);
            if (!j.def.name.empty()) {
                if (const auto it = names.find(j.def.name); it != names.end())
                    fail(at("joints", i) + ".name", (*v)[i]["name"],
                         "must be unique (already used by " +
                             (it->second == std::numeric_limits<std::size_t>::max() ? std::string("an instance")
                                                                                    : at("joints", it->second)) +
                             ")");
                names.emplace(j.def.name, i);
            }
            scene.joints.push_back(std::move(j));
        }
    }
    if (auto* v = find(doc, "fields")) {
        if (!v->is_array()) fail("fields", *v, "must be an array of field objects (" + fieldTypeNames() + ")");
        for (std::size_t i = 0; i < v->size(); ++i) scene.fields.push_back(readField((*v)[i], at("fields", i), scene.settings.planar));
    }
    if (auto* v = find(doc, "fluids")) {
        if (!v->is_array()) fail("fluids", *v, "must be an array of fluid objects");
        for (std::size_t i = 0; i < v->size(); ++i) scene.fluids.push_back(readFluid((*v)[i], at("fluids", i), scene.settings.planar));
    }
    if (auto* v = find(doc, "cloths")) {
        if (!v->is_array()) fail("cloths", *v, "must be an array of cloth objects");
        for (std::size_t i = 0; i < v->size(); ++i) scene.cloths.push_back(readCloth((*v)[i], at("cloths", i), scene.settings.planar));
    }
    return scene;
}

Scene loadSceneIn(const std::string& path, const LoadContext& context) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error(ErrorKind::Io, "", path + ": cannot read scene file (it is a directory)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorKind::Io, "", path + ": cannot read scene file (" + std::strerror(errno) + ")");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error(ErrorKind::Io, "", path + ": cannot read scene file (read error)");
    try {
        return parseSceneIn(text.str(), context);
    } catch (const Error& e) {
        // Name the file instead of the generic "scene" root: "scene.json: bodies[0].name: ...".
        std::string what = e.what();
        const std::string root = std::string(kRoot) + ": ";
        if (what.starts_with(root)) what.erase(0, root.size());
        throw e.reworded(path + ": " + what);
    }
}

}  // namespace

Scene parseScene(const std::string& jsonText) { return parseScene(jsonText, SceneLoadOptions{}); }

Scene parseScene(const std::string& jsonText, const SceneLoadOptions& options) {
    return parseSceneIn(jsonText, LoadContext{options, {}, 0});
}

Scene loadScene(const std::string& path) { return loadScene(path, SceneLoadOptions{}); }

Scene loadScene(const std::string& path, const SceneLoadOptions& options) {
    LoadContext context{options, {}, 0};
    context.options.folder = std::filesystem::path(path).parent_path().string();
    if (context.options.folder.empty()) context.options.folder = ".";
    std::error_code ec;
    context.chain.push_back(std::filesystem::weakly_canonical(path, ec).string());
    return loadSceneIn(path, context);
}

std::string sceneToJson(const Scene& scene) {
    ojson doc;
    doc["settings"] = settingsJson(scene.settings);
    doc["materials"] = ojson::object();
    // The default material is written only when changed, under the key "".
    const Material& fallback = scene.materials.get(MaterialLibrary::kDefaultName);
    if (!sameMaterialBits(fallback, Material{})) doc["materials"][""] = materialJson(fallback);
    for (const auto& name : scene.materials.names()) doc["materials"][name] = materialJson(scene.materials.get(name));
    doc["materialRules"] = ojson{{"friction", std::string(toString(scene.materials.frictionRule()))},
                                 {"restitution", std::string(toString(scene.materials.restitutionRule()))}};
    doc["materialPairs"] = ojson::array();
    for (const auto& [key, o] : scene.materials.pairOverrides()) {
        ojson pair{{"a", key.first}, {"b", key.second}};
        if (o.friction) pair["friction"] = *o.friction;
        if (o.restitution) pair["restitution"] = *o.restitution;
        doc["materialPairs"].push_back(pair);
    }
    doc["bodies"] = ojson::array();
    for (const auto& b : scene.bodies) {
        doc["bodies"].push_back(bodyJson(b));
        const auto text = scene.bodyUserData.find(b.name);
        writeUserData(doc["bodies"].back(), text == scene.bodyUserData.end() ? std::string() : text->second, b.userData);
    }
    doc["joints"] = ojson::array();
    for (const auto& j : scene.joints) doc["joints"].push_back(jointJson(j));
    if (!scene.fields.empty()) {
        doc["fields"] = ojson::array();
        for (const auto& f : scene.fields) doc["fields"].push_back(fieldJson(f));
    }
    if (!scene.fluids.empty()) {
        doc["fluids"] = ojson::array();
        for (const auto& f : scene.fluids) doc["fluids"].push_back(fluidJson(f));
    }
    if (!scene.cloths.empty()) {
        doc["cloths"] = ojson::array();
        for (const auto& c : scene.cloths) doc["cloths"].push_back(clothJson(c));
    }

    std::string out;
    write(out, doc, 0);
    return out + "\n";
}

void saveScene(const Scene& scene, const std::string& path) {
    const std::string text = sceneToJson(scene);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(ErrorKind::Io, "", path + ": cannot write scene file (" + std::strerror(errno) + ")");
    out << text;
    out.flush();
    if (!out) throw Error(ErrorKind::Io, "", path + ": cannot write scene file (write error)");
}

}  // namespace anyphys

#pragma once
// The key tables of docs/scene-format.md, written from the field table. Each table sits in the
// doc between the markers "<!-- schema:NAME -->" and "<!-- /schema:NAME -->";
// `anyphys schema --markdown` prints them and `anyphys schema --update FILE` rewrites them in
// place. A unit test fails when the doc's tables differ from these.
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "anyphys/schema/body_fields.hpp"
#include "anyphys/schema/joint_fields.hpp"
#include "anyphys/schema/material_fields.hpp"
#include "anyphys/schema/settings_fields.hpp"

namespace anyphys::schema {

namespace detail {
inline std::string cell(std::string_view text) {
    std::string out;
    for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

inline std::string valueText(const Value& v) {
    const auto vec = [](std::initializer_list<double> xs) {
        std::string out = "[";
        for (double x : xs) out += (out.size() > 1 ? ", " : "") + docNumber(x);
        return out + "]";
    };
    if (const auto* d = std::get_if<double>(&v)) return docNumber(*d);
    if (const auto* n = std::get_if<int>(&v)) return std::to_string(*n);
    if (const auto* u = std::get_if<std::uint32_t>(&v)) return std::to_string(*u);
    if (const auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
    if (const auto* x = std::get_if<Vec3>(&v)) return vec({x->x(), x->y(), x->z()});
    if (const auto* q = std::get_if<Quat>(&v)) return vec({q->w(), q->x(), q->y(), q->z()});
    if (const auto* s = std::get_if<std::string>(&v)) return "\"" + *s + "\"";
    return "";
}

template <class Def>
std::string defaultCell(const Field<Def>& f) {
    if (f.required) return "required";
    if (!f.defaultText.empty()) return std::string(f.defaultText);
    if (std::holds_alternative<std::monostate>(f.value)) return "none";
    return "`" + valueText(f.value) + "`";
}

template <class Def>
std::string ruleCell(const Field<Def>& f) {
    const std::string rule = ruleText(f);
    if (f.note.empty()) return rule;
    return rule.empty() ? std::string(f.note) : rule + ": " + std::string(f.note);
}

template <class Def>
std::string row(const Field<Def>& f) {
    return "| `" + std::string(f.key) + "` | " + cell(f.unit) + " | " + cell(defaultCell(f)) + " | " + cell(ruleCell(f)) +
           " |\n";
}

template <class Def, class Keep>
std::string keyTable(const std::vector<Field<Def>>& rows, Keep keep) {
    std::string out = "| key | unit | default | rule |\n|---|---|---|---|\n";
    for (const auto& f : rows)
        if (keep(f)) out += row(f);
    return out;
}

// Shapes: one block of rows per type, the type named on its first row.
inline std::string shapeTypeTable() {
    std::string out = "| type | key | unit | default | rule |\n|---|---|---|---|---|\n";
    for (const auto& [type, name] : EnumNames<ShapeType>::values) {
        bool first = true;
        for (const auto& f : shapeFields()) {
            if (f.types == ~0u || (f.types & bit(type)) == 0) continue;
            // Appended piece by piece: g++ 12 at -O3 reports a false overflow (-Werror) on
            // `"literal" + std::string(...)` here.
            out += "| ";
            if (first) out.append("`").append(name).append("`");
            out += " " + row(f);
            first = false;
        }
    }
    return out;
}

// Joints: a column names the types that use each key.
inline std::string jointTable() {
    std::string out = "| key | unit | default | types | rule |\n|---|---|---|---|---|\n";
    for (const auto& f : jointDefFields()) {
        std::string types;
        bool all = true;
        for (const auto& [type, name] : EnumNames<JointType>::values) {
            if (f.types & bit(type)) types += (types.empty() ? "" : ", ") + std::string(name);
            else all = false;
        }
        const std::string r = row(f);  // "| `key` | unit | default | rule |\n"
        const auto ruleAt = r.rfind(" | ", r.size() - 4);
        out += r.substr(0, ruleAt) + " | " + (all ? std::string("all") : types) + r.substr(ruleAt);
    }
    return out;
}
}  // namespace detail

/// The generated tables by marker name, in the doc's order.
inline std::vector<std::pair<std::string, std::string>> markdownTables() {
    const auto all = [](const auto&) { return true; };
    return {
        {"settings", detail::keyTable(settingsFields(), all)},
        {"material", detail::keyTable(materialFields(), all)},
        {"body", detail::keyTable(bodyFields(), all)},
        {"shape-placement", detail::keyTable(shapeFields(),
                                             [](const auto& f) { return f.types == ~0u && !f.childOnly && !f.ownCode; })},
        {"shape-types", detail::shapeTypeTable()},
        {"shape-child", detail::keyTable(shapeFields(), [](const auto& f) { return f.childOnly; })},
        {"joint", detail::jointTable()},
        {"joint-limits", detail::keyTable(jointLimitsFields(), all)},
        {"joint-motor", detail::keyTable(jointMotorFields(), all)},
        {"joint-spring", detail::keyTable(jointSpringFields(), all)},
    };
}

inline std::string beginMarker(const std::string& name) { return "<!-- schema:" + name + " -->\n"; }
inline std::string endMarker(const std::string& name) { return "<!-- /schema:" + name + " -->\n"; }

/// Tables by marker name. fields/ adds its own (anyphys/fields/schema_markdown.hpp).
using Tables = std::vector<std::pair<std::string, std::string>>;

/// Every table with its markers, as `anyphys schema --markdown` prints them.
inline std::string markdown(const Tables& tables = markdownTables()) {
    std::string out;
    for (const auto& [name, table] : tables) out += beginMarker(name) + table + endMarker(name) + "\n";
    return out;
}

/// `doc` with each marked table replaced by the generated one; `missing` gets the names of
/// tables whose markers the doc lacks.
inline std::string updateMarkdown(std::string doc, std::vector<std::string>& missing,
                                  const Tables& tables = markdownTables()) {
    for (const auto& [name, table] : tables) {
        const std::string begin = beginMarker(name), end = endMarker(name);
        const auto from = doc.find(begin);
        const auto to = from == std::string::npos ? from : doc.find(end, from);
        if (to == std::string::npos) {
            missing.push_back(name);
            continue;
        }
        doc.replace(from + begin.size(), to - from - begin.size(), table);
    }
    return doc;
}

}  // namespace anyphys::schema

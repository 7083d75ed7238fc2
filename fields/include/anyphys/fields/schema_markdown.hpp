#pragma once
// The key tables of docs/scene-format.md for fields, fluids and cloths, beside the api's
// (anyphys/schema/markdown.hpp, which may not know these defs): `anyphys schema` prints and
// updates allMarkdownTables().
#include <string>

#include "anyphys/fields/schema_fields.hpp"
#include "anyphys/schema/markdown.hpp"

namespace anyphys::schema {

namespace detail {
// Fields: one block of rows per type, the type named on its first row; a buoyancy field's
// "surface" keys follow it as surface.normal and surface.offset.
inline std::string fieldTypeTable() {
    std::string out = "| type | key | unit | default | rule |\n|---|---|---|---|---|\n";
    for (const auto& n : kFieldTypeNames) {
        bool first = true;
        const auto add = [&](std::string r) {
            out += "| " + (first ? "`" + std::string(n.name) + "`" : std::string()) + " " + r;
            first = false;
        };
        for (const auto& f : fieldDefFields()) {
            if (f.ownCode || (f.types & bit(n.type)) == 0) {
                if (f.key == "surface" && (f.types & bit(n.type)))
                    for (const auto& s : fieldSurfaceFields()) add(row(s).insert(3, "surface."));
                continue;
            }
            add(row(f));
        }
    }
    return out;
}
}  // namespace detail

/// The api's tables and those of fields, fluids and cloths, in the doc's order.
inline Tables allMarkdownTables() {
    const auto all = [](const auto&) { return true; };
    Tables tables = markdownTables();
    tables.emplace_back("field-types", detail::fieldTypeTable());
    tables.emplace_back("fluid", detail::keyTable(fluidDefFields(), all));
    tables.emplace_back("fluid-box", detail::keyTable(fluidBoxFields(), all));
    tables.emplace_back("cloth", detail::keyTable(clothDefFields(), all));
    return tables;
}

}  // namespace anyphys::schema

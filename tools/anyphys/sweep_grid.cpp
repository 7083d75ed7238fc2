// The numbering of a sweep's configurations, shared by `compare` (which runs them) and `merge`
// (which checks that every one came back).
#include "sweep_grid.hpp"

#include "cli.hpp"

namespace anyphys::cli {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const auto at = text.find(separator, start);
        parts.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
        if (at == std::string::npos) return parts;
        start = at + 1;
    }
}

}  // namespace

std::size_t SweepGrid::size() const {
    std::size_t n = 1;
    for (const Axis& axis : axes) n *= axis.values.size();
    return n;
}

std::vector<std::size_t> SweepGrid::coordinates(std::size_t id) const {
    std::vector<std::size_t> at(axes.size(), 0);
    for (std::size_t i = axes.size(); i-- > 0;) {
        at[i] = id % axes[i].values.size();
        id /= axes[i].values.size();
    }
    return at;
}

std::string SweepGrid::describe(std::size_t id) const {
    const std::vector<std::size_t> at = coordinates(id);
    std::vector<std::string> parts;
    for (std::size_t i = 0; i < axes.size(); ++i) parts.push_back(axes[i].name + "=" + axes[i].values[at[i]]);
    return join(parts, " ");
}

std::string SweepGrid::text() const {
    std::vector<std::string> parts;
    for (const Axis& axis : axes) parts.push_back(axis.name + "=" + join(axis.values, ","));
    return join(parts, " ");
}

SweepGrid SweepGrid::parse(const std::string& text) {
    SweepGrid grid;
    for (const std::string& part : split(text, ' ')) {
        const auto eq = part.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == part.size())
            throw Error("grid \"" + text + "\": \"" + part + "\" is not NAME=V1,V2,...");
        grid.axes.push_back({part.substr(0, eq), split(part.substr(eq + 1), ',')});
    }
    return grid;
}

}  // namespace anyphys::cli

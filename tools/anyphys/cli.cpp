// Helpers shared by the subcommands.
#include "cli.hpp"

#include <charconv>
#include <cstdio>
#include <fstream>

namespace anyphys::cli {

std::string join(const std::vector<std::string>& items, std::string_view separator) {
    std::string out;
    for (const std::string& item : items) {
        if (!out.empty()) out += separator;
        out += item;
    }
    return out;
}

Integrator parseIntegrator(const std::string& option, const std::string& name) {
    if (auto integrator = fromString<Integrator>(name)) return *integrator;
    throw Error::invalid(option, "\"" + name + "\"", "must be one of " + allowedNames<Integrator>());
}

BackendInfo parseBackend(const std::string& option, const std::string& name) {
    try {
        return backendInfo(name);
    } catch (const Error& e) {
        throw e.renamed(option);
    }
}

std::string exactNumber(double value) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
    return std::string(buffer, end);
}

std::string printfNumber(const char* pattern, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, pattern, value);
    return buffer;
}

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(ErrorKind::Io, "", path + ": cannot open for writing");
    out << text;
    out.close();
    if (!out) throw Error(ErrorKind::Io, "", path + ": write failed");
}

}  // namespace anyphys::cli

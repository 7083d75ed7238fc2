#include "results.hpp"

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace anyphys::bench::report {
namespace {

std::vector<std::string> split(const std::string& name) {
    std::vector<std::string> parts;
    std::stringstream in(name);
    for (std::string part; std::getline(in, part, '/');) parts.push_back(part);
    return parts;
}

// Google Benchmark's own fields: everything else numeric is one of our counters.
const std::set<std::string> kOwnFields = {"family_index", "per_family_instance_index", "repetitions",
                                          "repetition_index", "threads", "iterations", "real_time", "cpu_time"};

}  // namespace

void Results::load(const std::string& path) {
    std::ifstream file(path);
    if (!file) throw std::runtime_error("cannot read " + path);
    nlohmann::json json;
    try {
        file >> json;
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(path + ": not Google Benchmark JSON (" + e.what() + ")");
    }
    if (load_.empty() && json.contains("context") && json["context"].contains("load_avg"))
        load_ = json["context"]["load_avg"].get<std::vector<double>>();
    for (const auto& b : json.value("benchmarks", nlohmann::json::array())) {
        const std::vector<std::string> parts = split(b.value("name", ""));
        if (parts.size() < 3) continue;  // not one of the suite's names
        Record r;
        r.kind = parts[0];
        r.scene = parts[1];
        r.engine = parts[2];
        if (r.kind == "workers" && parts.size() > 3) r.workers = std::stoi(parts[3]);
        r.label = b.value("label", "");
        if (b.value("error_occurred", false)) r.error = b.value("error_message", "skipped");
        if (b.value("run_type", "") == "aggregate") r.aggregate = b.value("aggregate_name", "");
        for (const auto& [key, value] : b.items())
            if (value.is_number() && !kOwnFields.contains(key)) r.counters[key] = value.get<double>();
        records_.push_back(std::move(r));
    }
}

const Record* Results::find(const std::string& kind, const std::string& scene, const std::string& engine,
                            int workers) const {
    for (const Record& r : records_)
        if (r.kind == kind && r.scene == scene && r.engine == engine && r.workers == workers && r.aggregate.empty())
            return &r;
    return nullptr;
}

const Record* Results::median(const std::string& kind, const std::string& scene, const std::string& engine) const {
    for (const Record& r : records_)
        if (r.kind == kind && r.scene == scene && r.engine == engine && r.aggregate == "median") return &r;
    return find(kind, scene, engine);
}

}  // namespace anyphys::bench::report

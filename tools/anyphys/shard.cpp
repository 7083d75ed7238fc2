// Cost-balanced, deterministic sharding and the job schedulers' environment variables.
#include "shard.hpp"

#include <algorithm>
#include <cstdlib>
#include <numeric>

#include "anyphys/error.hpp"

namespace anyphys::cli {
namespace {

std::optional<long long> parseWhole(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size()) return std::nullopt;
    return v;
}

/// An environment variable as a whole number; nothing when unset; throws when not a number.
std::optional<long long> envNumber(const char* name) {
    const char* text = std::getenv(name);
    if (!text) return std::nullopt;
    const auto v = parseWhole(text);
    if (!v) throw Error(std::string("environment variable ") + name + "=\"" + text + "\" is not a whole number");
    return v;
}

ShardSpec checked(long long k, long long n, const std::string& from) {
    if (n < 1 || k < 1 || k > n)
        throw Error(from + ": shard " + std::to_string(k) + " of " + std::to_string(n) + " is not allowed: need 1 <= k <= N");
    return {static_cast<int>(k), static_cast<int>(n)};
}

}  // namespace

ShardSpec parseShard(const std::string& option, const std::string& text) {
    const auto slash = text.find('/');
    const auto k = slash == std::string::npos ? std::nullopt : parseWhole(text.substr(0, slash));
    const auto n = slash == std::string::npos ? std::nullopt : parseWhole(text.substr(slash + 1));
    if (!k || !n) throw Error(option + ": \"" + text + "\" is not allowed: expected k/N, e.g. 2/8");
    return checked(*k, *n, option + " " + text);
}

ShardSpec shardFromEnvironment(std::optional<int> shardsFlag) {
    const auto slurmId = envNumber("SLURM_ARRAY_TASK_ID");
    const auto slurmCount = envNumber("SLURM_ARRAY_TASK_COUNT");
    if (slurmId && slurmCount) {
        const long long first = envNumber("SLURM_ARRAY_TASK_MIN").value_or(0);
        return checked(*slurmId - first + 1, *slurmCount, "SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT");
    }
    if (const auto index = envNumber("JOB_COMPLETION_INDEX")) {
        std::optional<long long> count = shardsFlag;
        if (!count) count = envNumber("ANYPHYS_SHARD_COUNT");
        if (!count)
            throw Error("JOB_COMPLETION_INDEX is set but the number of shards is not: give --shards N or set ANYPHYS_SHARD_COUNT");
        return checked(*index + 1, *count, "JOB_COMPLETION_INDEX");
    }
    return {};
}

std::vector<std::size_t> shardMembers(const std::vector<double>& costs, const ShardSpec& shard) {
    std::vector<std::size_t> order(costs.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&costs](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
    std::vector<double> load(static_cast<std::size_t>(shard.count), 0.0);
    std::vector<std::size_t> members;
    for (std::size_t id : order) {
        const auto part = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
        load[part] += costs[id];
        if (static_cast<int>(part) + 1 == shard.index) members.push_back(id);
    }
    std::sort(members.begin(), members.end());
    return members;
}

}  // namespace anyphys::cli

#pragma once
// Splitting a sweep into N disjoint parts of about equal cost, so N processes (a Slurm array, a
// Kubernetes indexed job, GNU parallel) together run every configuration exactly once.
#include <optional>
#include <string>
#include <vector>

namespace anyphys::cli {

struct ShardSpec {
    int index = 1;  ///< k, 1-based
    int count = 1;  ///< N
    std::string label() const { return std::to_string(index) + "/" + std::to_string(count); }
};

/// Parses "k/N" (1 <= k <= N); throws anyphys::Error naming `option` otherwise.
ShardSpec parseShard(const std::string& option, const std::string& text);

/// The shard when --shard is not given: a Slurm array task (SLURM_ARRAY_TASK_ID minus
/// SLURM_ARRAY_TASK_MIN, of SLURM_ARRAY_TASK_COUNT), else a Kubernetes indexed job
/// (JOB_COMPLETION_INDEX, of `shardsFlag` or ANYPHYS_SHARD_COUNT), else the whole list (1/1).
ShardSpec shardFromEnvironment(std::optional<int> shardsFlag);

/// The configurations (indices into `costs`) of one shard, ascending. Greedy longest-first:
/// configurations by descending cost (ties: lower index first) each go to the part with the
/// least cost so far (ties: the lower part), so every process computes the same split.
std::vector<std::size_t> shardMembers(const std::vector<double>& costs, const ShardSpec& shard);

}  // namespace anyphys::cli

#pragma once
// The results table of a sweep: one row per configuration, the contract columns of
// docs/sweeps.md in a fixed order.
#include <vector>

#include "results_csv.hpp"
#include "shard.hpp"
#include "sweep_grid.hpp"
#include "sweep_run.hpp"

namespace anyphys::cli {

/// Columns for these axes: the five solver settings always, then each other swept axis, then
/// cost, accuracy and bookkeeping.
std::vector<std::string> sweepColumns(const std::vector<SweepAxis>& axes);
/// The row of one configuration of `grid`, matching sweepColumns(axes).
std::vector<std::string> sweepRow(const std::vector<SweepAxis>& axes, const SweepConfig& config, const SweepRecord& record,
                                  const SweepGrid& grid, const ShardSpec& shard);

}  // namespace anyphys::cli

#pragma once
// `anyphys compare` in sweep mode (--sweep, --repeat, --out, --shard): a full grid over the
// swept settings for every scene x backend, timed and measured, one results row per
// configuration (docs/sweeps.md).
#include <string>
#include <vector>

#include "anyphys/anyphys.hpp"
#include "anyphys/containers/scene_catalogue.hpp"
#include "shard.hpp"
#include "sweep_axes.hpp"

namespace anyphys::cli {

struct SweepOptions {
    std::vector<const CatalogueScene*> scenes;
    std::vector<BackendInfo> backends;
    std::vector<SweepAxis> axes;
    int repeat = 3;
    std::string out;   ///< results CSV ("" for none; the .jsonl goes beside it)
    ShardSpec shard;
    bool json = false; ///< stdout: JSON instead of a table
};

/// Runs this shard of the grid. Checks that miss are data here, not failures: returns 0.
int runSweep(const SweepOptions& options);

}  // namespace anyphys::cli

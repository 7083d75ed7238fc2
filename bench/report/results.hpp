#pragma once
// The benchmark programs' Google Benchmark JSON output, read back as records named by what was
// measured: kind (scene, workers, scaling, raw, overhead), scene, engine, workers.
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace anyphys::bench::report {

struct Record {
    std::string kind;    ///< the first part of the benchmark name
    std::string scene;
    std::string engine;  ///< the backend, or the engine driven directly for raw / overhead
    int workers = 1;
    std::string label;   ///< the solver configuration that ran
    std::string error;   ///< why it was skipped (Google Benchmark's error message); empty if it ran
    std::string aggregate;  ///< "median", "mean", ... over --benchmark_repetitions; empty for a run
    std::map<std::string, double> counters;

    bool ran() const { return error.empty(); }
    /// A counter, or NaN when absent.
    double operator[](const std::string& name) const {
        const auto it = counters.find(name);
        return it == counters.end() ? std::nan("") : it->second;
    }
};

class Results {
public:
    /// Appends the benchmarks of one JSON file; throws std::runtime_error when unreadable.
    void load(const std::string& path);

    const std::vector<Record>& all() const { return records_; }
    /// The record of that measurement, if it was run or skipped.
    const Record* find(const std::string& kind, const std::string& scene, const std::string& engine,
                       int workers = 1) const;
    /// The median over repetitions when the program ran with --benchmark_repetitions, else the run.
    const Record* median(const std::string& kind, const std::string& scene, const std::string& engine) const;
    /// Load averages (1, 5, 15 min) Google Benchmark saw, from the first file that has them.
    const std::vector<double>& loadAverages() const { return load_; }

private:
    std::vector<Record> records_;
    std::vector<double> load_;
};

}  // namespace anyphys::bench::report

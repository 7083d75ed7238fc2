#pragma once
// A progress bar on stderr for long sweeps: redrawn in place on a terminal, one line per ~10 %
// otherwise (a log file or a batch job's output stays short).
#include <cstddef>
#include <string>

namespace anyphys::cli {

class ProgressBar {
public:
    /// `prefix` starts every line, e.g. "shard 2/4 " ("" for none).
    ProgressBar(std::size_t total, std::string prefix);
    /// `done` of total finished; `what` names the one running next (or just finished).
    void update(std::size_t done, const std::string& what);
    /// Ends the redrawn line on a terminal.
    void finish();

private:
    std::size_t total_;
    std::string prefix_;
    bool terminal_;
    int lastDecile_ = -1;
};

}  // namespace anyphys::cli

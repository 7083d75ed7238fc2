// The sweep progress bar.
#include "progress.hpp"

#include <cstdio>
#include <unistd.h>

namespace anyphys::cli {

ProgressBar::ProgressBar(std::size_t total, std::string prefix)
    : total_(total), prefix_(std::move(prefix)), terminal_(isatty(STDERR_FILENO) != 0) {}

void ProgressBar::update(std::size_t done, const std::string& what) {
    constexpr int kWidth = 20;
    const double fraction = total_ ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
    const int filled = static_cast<int>(fraction * kWidth);
    const std::string bar = std::string(static_cast<std::size_t>(filled), '#') + std::string(static_cast<std::size_t>(kWidth - filled), '.');
    const std::string line = prefix_ + "[" + bar + "] " + std::to_string(done) + "/" + std::to_string(total_) + " " + what;
    if (terminal_) {
        std::fprintf(stderr, "\r\033[K%s", line.c_str());  // clear the rest of the previous, longer line
    } else {
        const int decile = static_cast<int>(fraction * 10);
        if (decile == lastDecile_) return;
        lastDecile_ = decile;
        std::fprintf(stderr, "%s\n", line.c_str());
    }
    std::fflush(stderr);
}

void ProgressBar::finish() {
    if (terminal_) std::fprintf(stderr, "\n");
}

}  // namespace anyphys::cli

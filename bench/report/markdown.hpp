#pragma once
// Markdown output helpers: numbers with a fixed precision ("-" when missing) and tables.
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace anyphys::bench::report {

/// `value` with `digits` decimals; "-" when it is NaN (not measured).
inline std::string num(double value, int digits) {
    if (std::isnan(value)) return "-";
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

/// A count per step (an average over the measured window, maybe negative as a difference):
/// whole above 10, otherwise three significant digits, so that one in 60 steps reads 0.0167, not 0.
inline std::string perStepCount(double value) {
    if (std::isnan(value)) return "-";
    if (value == 0 || std::abs(value) >= 10) return num(value, 0);
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

/// Heap allocations per step, or "n/a" where the build does not count them (a negative mark).
inline std::string allocations(double perStep) { return perStep < 0 ? "n/a" : perStepCount(perStep); }

class Table {
public:
    /// The first `textColumns` columns hold names (left-aligned); the rest figures (right-aligned).
    explicit Table(std::vector<std::string> header, std::size_t textColumns = 2)
        : header_(std::move(header)), textColumns_(textColumns) {}
    void row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }
    bool empty() const { return rows_.empty(); }

    void print(std::ostream& out) const {
        line(out, header_);
        out << '|';
        for (std::size_t i = 0; i < header_.size(); ++i) out << (i < textColumns_ ? "---|" : "---:|");
        out << '\n';
        for (const auto& r : rows_) line(out, r);
    }

private:
    static void line(std::ostream& out, const std::vector<std::string>& cells) {
        out << '|';
        for (const std::string& c : cells) out << ' ' << c << " |";
        out << '\n';
    }

    std::vector<std::string> header_;
    std::size_t textColumns_;
    std::vector<std::vector<std::string>> rows_;
};

}  // namespace anyphys::bench::report

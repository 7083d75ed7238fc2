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

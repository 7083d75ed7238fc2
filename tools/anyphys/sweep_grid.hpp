#pragma once
// The shape of a sweep: scenes x backends x each swept axis, and how a configuration's number
// (`config_id`) maps to one value of each. Its text form is stored in every results row (column
// `grid`), so `anyphys merge` can name a configuration that no part holds.
#include <cstddef>
#include <string>
#include <vector>

namespace anyphys::cli {

struct SweepGrid {
    struct Axis {
        std::string name;                 ///< "scene", "backend", then each --sweep NAME
        std::vector<std::string> values;  ///< as typed
    };
    std::vector<Axis> axes;

    /// The number of configurations: the product of the axes' sizes.
    std::size_t size() const;
    /// Which value of each axis configuration `id` has: the first axis outermost, the last
    /// varying fastest.
    std::vector<std::size_t> coordinates(std::size_t id) const;
    /// Configuration `id` in words, "scene=projectile backend=native timeStep=1/60".
    std::string describe(std::size_t id) const;
    /// "scene=a,b backend=native,ode timeStep=1/30,1/60": what parse reads back.
    std::string text() const;
    /// Reads text(); throws anyphys::Error naming the text when it is not one.
    static SweepGrid parse(const std::string& text);
};

}  // namespace anyphys::cli

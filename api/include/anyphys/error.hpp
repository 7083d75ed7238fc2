#pragma once
// The one exception type of anyphys. A rejected call changes nothing.
#include <sstream>
#include <stdexcept>
#include <string>

namespace anyphys {

/// Thrown for bad input, stale handles and unsupported requests. The message names the field,
/// the offending value and what is allowed, e.g. "BodyDef.shape.radius: must be > 0, got -1".
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}

    /// Builds "<field>: <rule>, got <value>".
    template <class T>
    static Error invalid(const std::string& field, const T& value, const std::string& rule) {
        std::ostringstream os;
        os.precision(17);
        os << field << ": " << rule << ", got " << value;
        return Error(os.str());
    }
};

}  // namespace anyphys

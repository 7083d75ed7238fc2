#pragma once
// The one exception type of anyphys. A rejected call changes nothing (World::step's Diverged is
// the exception: the step has run; see docs/errors.md).
#include <charconv>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace anyphys {

/// The shortest text that reads back as the same double: "0.1", not "0.10000000000000001" (what
/// 17 significant digits print), as the tool writes its CSV.
inline std::string formatNumber(double v) {
    char text[32];
    const std::to_chars_result end = std::to_chars(text, text + sizeof text, v);
    return std::string(text, end.ptr);
}

/// What went wrong, for code that reacts to errors (the message is for people). See docs/errors.md.
enum class ErrorKind {
    InvalidArgument,  ///< a value breaks a documented rule: out of range, non-finite, beyond a ceiling, unknown name
    InvalidState,     ///< the call is not allowed now: while stepping or drawing, or a handle of another world
    StaleHandle,      ///< a null handle, or one whose body, joint or world was destroyed
    Unsupported,      ///< the backend lacks a capability the call or the settings need (strict policy)
    Parse,            ///< a scene file or text that is not the expected JSON: syntax, unknown or duplicate key, missing key
    Diverged,         ///< World::step found non-finite or absurd body states (WorldSettings::divergencePolicy throw)
    Io,               ///< a file could not be read or written
    Internal,         ///< a broken invariant inside anyphys or an engine: a bug to report
};

/// "invalid_argument", "stale_handle", ...: the kind as one word, as the tool prints it.
constexpr std::string_view toString(ErrorKind kind) {
    switch (kind) {
        case ErrorKind::InvalidArgument: return "invalid_argument";
        case ErrorKind::InvalidState: return "invalid_state";
        case ErrorKind::StaleHandle: return "stale_handle";
        case ErrorKind::Unsupported: return "unsupported";
        case ErrorKind::Parse: return "parse";
        case ErrorKind::Diverged: return "diverged";
        case ErrorKind::Io: return "io";
        case ErrorKind::Internal: return "internal";
    }
    return "internal";
}

/// Thrown for bad input, stale handles, unsupported requests, unreadable scene files and diverged
/// steps. The message names the field, the offending value and what is allowed, e.g.
/// "BodyDef.shape.radius: must be > 0, got -1"; kind() says what went wrong and field() the path
/// of the value concerned ("BodyDef.shape.radius", "bodies[3].shape.radius", "settings.timeStep"),
/// empty when no single value is to blame.
class Error : public std::runtime_error {
public:
    /// A message only: kind InvalidArgument, no field (what most older call sites meant).
    explicit Error(const std::string& message) : std::runtime_error(message) {}
    Error(ErrorKind kind, std::string field, const std::string& message)
        : std::runtime_error(message), kind_(kind), field_(std::move(field)) {}

    ErrorKind kind() const noexcept { return kind_; }
    /// The path of the value concerned, in the words of the message; empty when none.
    const std::string& field() const noexcept { return field_; }

    /// Builds "<field>: <rule>, got <value>" of kind InvalidArgument (or `kind`) naming `field`.
    template <class T>
    static Error invalid(const std::string& field, const T& value, const std::string& rule,
                         ErrorKind kind = ErrorKind::InvalidArgument) {
        std::ostringstream os;
        os << field << ": " << rule << ", got ";
        if constexpr (std::is_floating_point_v<T>)
            os << formatNumber(static_cast<double>(value));
        else
            os << value;
        return Error(kind, field, os.str());
    }

    /// The same error with "<prefix>: " in front of the message (a file name, an instance path);
    /// kind and field are kept.
    Error within(const std::string& prefix) const { return Error(kind_, field_, prefix + ": " + what()); }
    /// The same error with the message replaced; kind and field are kept.
    Error reworded(const std::string& message) const { return Error(kind_, field_, message); }
    /// The same error about `field` (a tool's flag, a file's key), where the value came from: the
    /// message's leading "<old field>: " becomes "<field>: "; the kind is kept.
    Error renamed(const std::string& field) const {
        const std::string message = what();
        const std::string lead = field_ + ": ";
        const bool leads = !field_.empty() && message.compare(0, lead.size(), lead) == 0;
        return Error(kind_, field, field + ": " + (leads ? message.substr(lead.size()) : message));
    }

private:
    ErrorKind kind_ = ErrorKind::InvalidArgument;
    std::string field_;
};

}  // namespace anyphys

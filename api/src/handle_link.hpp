#pragma once
// The world behind a Body or Joint handle, or a StaleHandle error naming the handle and why.
#include <memory>
#include <string>

#include "anyphys/body.hpp"
#include "anyphys/error.hpp"

namespace anyphys::detail {

/// `what` is "body" or "joint"; `Id` has index, generation and isNull().
template <class Id>
World& linkedWorld(const std::shared_ptr<WorldLink>& link, Id id, const char* what, const char* operation) {
    if (!link || id.isNull())
        throw Error(ErrorKind::StaleHandle, "", std::string(operation) + ": null " + what + " handle");
    if (!link->world)
        throw Error(ErrorKind::StaleHandle, "",
                    std::string(operation) + ": stale " + what + " handle (index " + std::to_string(id.index) +
                        ", generation " + std::to_string(id.generation) + "): the " + what + "'s world was destroyed");
    return *link->world;
}

}  // namespace anyphys::detail

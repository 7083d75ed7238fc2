#pragma once
// World internals shared by world.cpp and body.cpp.
#include <set>
#include <string>
#include <vector>

#include "anyphys/listeners/contact_tracker.hpp"
#include "anyphys/peers/backend.hpp"
#include "anyphys/world.hpp"

namespace anyphys {

struct World::Slot {
    std::unique_ptr<BodyPeer> peer;  // null while the slot is free
    std::uint32_t generation = 1;    // bumped on destroy, so stale ids never match
    BodyDef def;                     // as created (validated, orientation normalised)
    MassProperties mass;
};

struct World::Impl {
    const Backend* backend = nullptr;
    std::unique_ptr<WorldPeer> peer;  // declared before slots: body peers die first
    std::vector<Slot> slots;
    std::vector<std::uint32_t> freeSlots;
    std::size_t liveBodies = 0;

    // Content counters from which effects are derived without scanning the bodies.
    std::size_t gravityBodies = 0;
    std::size_t dampedBodies = 0;
    std::size_t gyroscopicBodies = 0;
    bool forcesUsed = false;

    ForceCallback forceCallback;
    std::vector<ContactListener*> listeners;
    ContactTracker tracker;
    WarningHandler warningHandler;
    std::set<std::string> warned;
    bool stepping = false;  // inside a step: structural changes are refused
};

}  // namespace anyphys

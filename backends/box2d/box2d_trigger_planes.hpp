#pragma once
// Trigger planes as half-planes. The layer's plane is solid below its surface: on the 3D backends
// a body that sinks through a trigger plane stays inside it, and World::overlap answers so on this
// backend too. Box2D would test a sensor plane's run of edges, a line, and end the overlap once the
// body had passed below it. So the world keeps trigger planes out of Box2D's contacts
// (ContactRules::ShouldCollide) and lists their overlaps itself, from how deep each body reaches.
#include <box2d/box2d.h>

#include <vector>

#include "anyphys/effects.hpp"
#include "anyphys/peers/world_peer.hpp"

namespace anyphys::box2d {

class Box2dBody;

/// Whether the fixture is one of a trigger plane's edges.
bool isTriggerPlane(const b2Fixture& fixture);

class TriggerPlanes {
public:
    /// Keeps `body` if its shape is a trigger plane; true then.
    bool addIfTriggerPlane(Box2dBody& body);
    /// Forgets `body`; true if it was a trigger plane.
    bool remove(Box2dBody& body);

    /// Adds a trigger pair for each awake dynamic body (Box2D's sensors meet no other) with a
    /// fixture that the plane's filter admits reaching less than kPairSkin above the plane: the
    /// skinned shapes then overlap, as Box2D's sensors count it for every other trigger.
    void report(const std::vector<Box2dBody*>& bodies, Effects effects, ContactReport& out) const;

private:
    std::vector<Box2dBody*> planes_;
};

}  // namespace anyphys::box2d

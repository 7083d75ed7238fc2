#pragma once
// The trigger overlaps Box2D does not find as the layer means them; the world lists them itself.
//  - Trigger planes: the layer's plane is solid below its surface. On the 3D backends a body that
//    sinks through a trigger plane stays inside it, and World::overlap answers so on this backend
//    too; Box2D would test a sensor plane's run of edges, a line, and end the overlap once the body
//    had passed below it. So trigger planes make no Box2D contacts (ContactRules::ShouldCollide),
//    and their overlaps come from how deep each body reaches.
//  - Pairs without a dynamic body: Box2D makes contacts only where a body is dynamic, so a
//    kinematic body never met a static or kinematic trigger (nor a kinematic trigger anything but
//    dynamic bodies), where the other backends report those overlaps: a kinematic character
//    walking into a trigger zone got no event.
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

    /// Adds a trigger pair for each awake moving body with a fixture that the plane's filter
    /// admits reaching less than kPairSkin above the plane: the skinned shapes then overlap, as
    /// Box2D's sensors count it for every other trigger.
    void report(const std::vector<Box2dBody*>& bodies, Effects effects, ContactReport& out) const;

private:
    std::vector<Box2dBody*> planes_;
};

/// Adds a trigger pair for each overlap of one of the `kinematic` bodies with a static or
/// kinematic body where either fixture is a sensor (the layer's filter and joints'
/// collideConnected as Box2D applies them; skinned shapes, as Box2D's sensors test them; a plane
/// as its half-plane), unless both sleep. Trigger planes are TriggerPlanes'. `found` is scratch.
void reportKinematicTriggers(const std::vector<Box2dBody*>& kinematic, const b2World& world, Effects effects,
                             ContactReport& out, std::vector<const b2Body*>& found);

}  // namespace anyphys::box2d

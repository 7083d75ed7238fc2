#pragma once
// From a body's ShapeDef to what a backend receives: primitive shapes placed in the peer frame
// (centre of mass, principal axes) and the body's mass properties.
#include <vector>

#include "anyphys/defs.hpp"
#include "anyphys/peers/shape_data.hpp"

namespace anyphys {

struct ResolvedShapes {
    MassProperties mass;            ///< dynamic bodies: from shapes and densities (or the def's mass / inertia)
    Transform peerFrame;            ///< the peer frame in the body frame: (centre of mass, principal axes)
    std::vector<PeerShape> shapes;  ///< primitives, placed in the peer frame
};

/// `densities` holds one density per piece (each compound child, else the one shape), resolved
/// by the caller. Static and kinematic bodies keep their body frame as peer frame and get zero mass.
ResolvedShapes resolveShapes(const BodyDef& def, const std::vector<double>& densities);

/// The pieces a body's shape becomes: a compound's children, else the shape itself.
std::vector<const ShapeDef*> shapePieces(const ShapeDef& shape);

/// Primitives of a shape (compound children, or the shape itself) placed in the shape's
/// parent frame, with hulls built; for queries.
std::vector<PeerShape> flattenShape(const ShapeDef& shape);

}  // namespace anyphys

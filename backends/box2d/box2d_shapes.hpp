#pragma once
// The layer's shapes as Box2D shapes: each PeerShape becomes one or more 2D pieces in the Box2D
// body frame (sphere -> circle, box and convex -> polygon, capsule -> rectangle + two circles,
// plane -> a run of one-sided edges along its line, over polygons that hold what sinks below).
#include <box2d/box2d.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "anyphys/peers/shape_data.hpp"

namespace anyphys::box2d {

/// A plane as a half-plane in the Box2D body frame: points x with normal.dot(x) <= offset are
/// inside.
struct HalfPlane {
    b2Vec2 normal;
    float offset = 0.0f;

    /// The unit normal in the world, for the plane's body at xf.
    b2Vec2 worldNormal(const b2Transform& xf) const { return b2Mul(xf.q, normal); }
    /// A point on the plane in the world (the body frame's nearest to its origin).
    b2Vec2 worldPoint(const b2Transform& xf) const { return xf.p + offset * worldNormal(xf); }
};

/// One Box2D fixture's geometry.
struct Piece {
    /// What collides: the true outline grown by kSkin. Polygons and edges keep Box2D's rounding
    /// radius (b2_polygonRadius, which its time of impact needs) with their core shrunk to match.
    std::unique_ptr<b2Shape> collision;
    /// The true outline, for ray casts and overlap queries (answers about the user's geometry).
    std::unique_ptr<b2Shape> exact;
    std::optional<HalfPlane> plane;  ///< set for planes: overlap tests use the half-plane
    /// A polygon under one of a collision plane's edges, its top on the plane: it holds what sank
    /// below the edge's line (a one-sided edge lets go of a piece whose centre is behind it).
    /// Enabled per contact only then (ContactRules::PreSolve); no part of queries or near pairs.
    bool basement = false;
};

/// Builds the pieces of one shape placed at `pose` in the Box2D body frame. `originInBody` is the
/// world origin in that frame (planes are centred on the point of their line nearest to it).
/// Throws anyphys::Error naming `path` when the shape has no Box2D form (a convex outline of more
/// than b2_maxPolygonVertices vertices, or one too thin to be a polygon).
std::vector<Piece> makePieces(const PeerShape& shape, const Transform& pose, const b2Vec2& originInBody,
                              const std::string& path);

/// The smallest value of normal.dot(x) over an exact piece placed at xf: how deep it reaches
/// below a plane of that normal (a circle or polygon; a polygon's outline is its vertices).
float lowest(const b2Shape& exact, const b2Transform& xf, const b2Vec2& normal);

/// Smallest distance from a piece's centre to its surface, m (how far it may move in a step
/// before a discrete step can miss a hit); infinite for planes.
double innerRadius(const Piece& piece);

}  // namespace anyphys::box2d

#pragma once
// Bullet collision shapes built from the layer's shapes (already flattened into primitives and
// placed in the peer body frame), together with everything they point to: Bullet shapes do not
// own their children or their triangle arrays, so one ShapeSet owns them all and frees them in
// the right order.
#include <memory>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "anyphys/peers/shape_data.hpp"

namespace anyphys::bullet {

class Reaching;

class ShapeSet {
public:
    /// Builds the shapes; several shapes, or one not at the body frame's origin, become a
    /// btCompoundShape.
    explicit ShapeSet(const std::vector<PeerShape>& shapes);
    ~ShapeSet();
    ShapeSet(const ShapeSet&) = delete;
    ShapeSet& operator=(const ShapeSet&) = delete;

    /// The shape to give the collision object.
    btCollisionShape* root() const { return root_; }
    /// m, smallest distance from a shape's centre to its surface: moving less than this per
    /// step cannot tunnel (used for continuous collision).
    double coreExtent() const { return coreExtent_; }
    /// Whether one of the shapes is a triangle mesh.
    bool hasMesh() const { return hasMesh_; }
    /// Lets the convex shapes' bounding boxes reach out by their contact breaking threshold (see
    /// ReachingShape), as the world does while it holds a mesh.
    void setReaching(bool on);
    /// A compound of the children that are not sensors, sharing their shapes, for Bullet's
    /// continuous-collision sweeps (which see one shape per body); nullptr when every child is
    /// solid, every child is a sensor, or the root is not a compound.
    btCompoundShape* solidPart() const { return solidPart_.get(); }

private:
    struct Mesh {
        std::vector<btScalar> vertices;  // x, y, z per vertex
        std::vector<int> indices;        // three per triangle
        std::unique_ptr<btTriangleIndexVertexArray> array;
        // The angle at each triangle's shared edges, for btAdjustInternalEdgeContacts (see
        // correctMeshEdge in bullet_dynamics_world.cpp); the mesh shape points to it, not owning it.
        std::unique_ptr<btTriangleInfoMap> edges;
    };
    btCollisionShape* build(const PeerShape& shape, bool& absorbedPose);

    // Destroyed in reverse: the compound first, then the children, then the meshes' arrays.
    std::vector<std::unique_ptr<Mesh>> meshes_;
    std::vector<std::unique_ptr<btCollisionShape>> children_;
    std::unique_ptr<btCompoundShape> compound_;
    std::unique_ptr<btCompoundShape> solidPart_;  // destroyed before the children it shares
    btCollisionShape* root_ = nullptr;
    std::vector<Reaching*> reaching_;  // the convex children
    double coreExtent_ = 0.0;
    bool hasMesh_ = false;
};

}  // namespace anyphys::bullet

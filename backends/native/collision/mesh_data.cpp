// Static triangle meshes: triangles, unit normals and a tree over the triangles' bounds.
#include "collision/mesh_data.hpp"

#include <stdexcept>

namespace anyphys::native {

std::shared_ptr<const MeshData> MeshData::build(const ShapeDef& def) {
    if (def.type != ShapeType::Mesh || def.indices.size() % 3 != 0)
        throw std::invalid_argument("MeshData::build: expects a validated mesh ShapeDef");
    auto mesh = std::make_shared<MeshData>();
    mesh->vertices = def.vertices;
    const std::size_t triangleCount = def.indices.size() / 3;
    mesh->triangles.reserve(triangleCount);
    mesh->normals.reserve(triangleCount);
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const std::array<std::uint32_t, 3> tri{def.indices[3 * t], def.indices[3 * t + 1], def.indices[3 * t + 2]};
        for (const std::uint32_t i : tri)
            if (i >= mesh->vertices.size()) throw std::invalid_argument("MeshData::build: index out of range");
        mesh->triangles.push_back(tri);
        const Vec3& a = mesh->vertices[tri[0]];
        const Vec3& b = mesh->vertices[tri[1]];
        const Vec3& c = mesh->vertices[tri[2]];
        // Validation rejects zero-area triangles, so the cross product is never zero.
        mesh->normals.push_back((b - a).cross(c - a).normalized());
        const Aabb box{a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
        mesh->tree.createProxy(box, static_cast<std::uint64_t>(t));
    }
    return mesh;
}

void MeshData::queryTriangles(const Aabb& box, FunctionRef<bool(int)> visit) const {
    tree.query(box, [&](int proxy) { return visit(static_cast<int>(tree.userData(proxy))); });
}

std::array<Vec3, 3> MeshData::triangleVertices(int triangle) const {
    const auto& tri = triangles[static_cast<std::size_t>(triangle)];
    return {vertices[tri[0]], vertices[tri[1]], vertices[tri[2]]};
}

void MeshData::rayCastTriangles(const Vec3& origin, const Vec3& dir, double maxDistance,
                                FunctionRef<double(int, double)> visit) const {
    tree.rayCast(origin, dir, maxDistance,
                 [&](int proxy, double maxT) { return visit(static_cast<int>(tree.userData(proxy)), maxT); });
}

}  // namespace anyphys::native

#include "ode_box_plane.hpp"

#include <algorithm>
#include <array>

#include "ode_collider_output.hpp"
#include "ode_math.hpp"

namespace anyphys::ode {

int collideBoxPlane(dGeomID o1, dGeomID o2, int flags, dContactGeom* contact, int skip) {
    const int room = std::min(contactRoom(flags), 4);
    if (room <= 0) return 0;
    dVector3 lengths;
    dGeomBoxGetLengths(o1, lengths);
    dVector4 plane;  // n . p = d on the plane
    dGeomPlaneGetParams(o2, plane);
    const Vec3 normal(plane[0], plane[1], plane[2]);
    const Vec3 centre = toVec3(dGeomGetPosition(o1));
    const Mat3 rotation = toMat3(dGeomGetRotation(o1));
    const Vec3 half = 0.5 * Vec3(lengths[0], lengths[1], lengths[2]);

    struct Corner {
        Vec3 point;
        double depth;
    };
    std::array<Corner, 8> corners;
    int found = 0;
    for (int k = 0; k < 8; ++k) {
        const Vec3 sign((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
        const Vec3 point = centre + rotation * sign.cwiseProduct(half);
        const double depth = plane[3] - normal.dot(point);
        if (depth >= -kBoxPlaneReach) corners[found++] = {point, depth};  // a NaN pose gives none
    }
    // The deepest first; equal depths keep the corner order, so the same pose gives the same contacts.
    // An insertion sort: stable like std::stable_sort, which takes a heap buffer in every collision.
    for (int i = 1; i < found; ++i) {
        const Corner corner = corners[i];
        int j = i;
        for (; j > 0 && corners[j - 1].depth < corner.depth; --j) corners[j] = corners[j - 1];
        corners[j] = corner;
    }
    const int count = std::min(found, room);
    for (int c = 0; c < count; ++c)
        writeContact(contactAt(contact, c, skip), corners[c].point, normal, std::max(corners[c].depth, 0.0), o1, o2);
    return count;
}

}  // namespace anyphys::ode

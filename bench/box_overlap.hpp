#pragma once
// Penetration depth of oriented boxes, measured from body poses alone so every backend is judged
// by the same geometry (not by what its own contact reports say).
#include <algorithm>
#include <cmath>
#include <limits>

#include "anyphys/math.hpp"

namespace anyphys::bench {

struct OrientedBox {
    Vec3 center;
    Mat3 axes;  ///< columns: the box's axes in the world frame
    Vec3 half;  ///< half extents along those axes
};

/// Half the box's extent along unit direction `n`.
inline double projectedRadius(const OrientedBox& b, const Vec3& n) {
    return std::abs(b.axes.col(0).dot(n)) * b.half.x() + std::abs(b.axes.col(1).dot(n)) * b.half.y() +
           std::abs(b.axes.col(2).dot(n)) * b.half.z();
}

/// How deep the box reaches below the plane y = 0 (0 when above it).
inline double groundPenetration(const OrientedBox& b) {
    return std::max(0.0, projectedRadius(b, Vec3::UnitY()) - b.center.y());
}

/// Penetration depth of two boxes: the smallest overlap over the 15 separating-axis candidates
/// (3 + 3 face normals, 9 edge cross products), which for boxes is the minimum translation that
/// separates them. 0 when they are apart.
inline double boxPenetration(const OrientedBox& a, const OrientedBox& b) {
    const Vec3 d = b.center - a.center;
    double smallest = std::numeric_limits<double>::infinity();
    const auto test = [&](Vec3 axis) {
        const double length = axis.norm();
        if (length < 1e-9) return;  // parallel edges: the face axes cover this direction
        axis /= length;
        const double overlap = projectedRadius(a, axis) + projectedRadius(b, axis) - std::abs(d.dot(axis));
        smallest = std::min(smallest, overlap);
    };
    for (int i = 0; i < 3; ++i) {
        test(a.axes.col(i));
        test(b.axes.col(i));
        for (int j = 0; j < 3; ++j) test(a.axes.col(i).cross(b.axes.col(j)));
    }
    return std::max(0.0, smallest);
}

}  // namespace anyphys::bench

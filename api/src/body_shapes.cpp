#include "body_shapes.hpp"

#include <Eigen/Eigenvalues>

#include "anyphys/mass_properties.hpp"
#include "geometry/convex_hull.hpp"

namespace anyphys {
namespace {

Transform placement(const ShapeDef& s) { return {s.position, s.orientation.normalized()}; }

// Mass, centroid (parent frame) and inertia tensor about the centroid (parent frame) of one
// placed primitive of uniform density.
struct PieceMass {
    double mass = 0.0;
    Vec3 centroid = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
};

PieceMass pieceMass(const PeerShape& piece, double density) {
    const Mat3 r = piece.local.orientation.toRotationMatrix();
    PieceMass m;
    if (piece.def.type == ShapeType::Convex) {
        m.mass = density * piece.hull->volume;
        m.centroid = piece.local.position + r * piece.hull->centroid;
        m.inertia = m.mass * r * piece.hull->inertiaPerMass * r.transpose();
    } else {
        m.mass = density * shapeVolume(piece.def);
        m.centroid = piece.local.position;
        m.inertia = m.mass * r * unitInertia(piece.def).asDiagonal() * r.transpose();
    }
    return m;
}

// Inertia of a point mass at offset d about the origin (parallel-axis theorem).
Mat3 parallelAxis(double mass, const Vec3& d) { return mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose()); }

}  // namespace

std::vector<PeerShape> flattenShape(const ShapeDef& shape) {
    std::vector<PeerShape> pieces;
    const auto add = [&](const ShapeDef& s, const Transform& at) {
        PeerShape p{s, at, nullptr};
        p.def.shapes.clear();
        if (s.type == ShapeType::Convex) p.hull = buildConvexHull(s.points);
        pieces.push_back(std::move(p));
    };
    if (shape.type == ShapeType::Compound) {
        const Transform parent = placement(shape);
        for (const ShapeDef& child : shape.shapes) {
            const Transform c = placement(child);
            add(child, {parent.position + parent.orientation * c.position, parent.orientation * c.orientation});
        }
    } else {
        add(shape, placement(shape));
    }
    return pieces;
}

std::vector<const ShapeDef*> shapePieces(const ShapeDef& shape) {
    std::vector<const ShapeDef*> pieces;
    if (shape.type == ShapeType::Compound)
        for (const ShapeDef& child : shape.shapes) pieces.push_back(&child);
    else
        pieces.push_back(&shape);
    return pieces;
}

ResolvedShapes resolveShapes(const BodyDef& def, const std::vector<double>& densities) {
    ResolvedShapes out;
    out.shapes = flattenShape(def.shape);
    if (def.type != BodyType::Dynamic) return out;

    double mass = 0.0;
    Vec3 centre = Vec3::Zero();
    std::vector<PieceMass> pieces;
    for (std::size_t i = 0; i < out.shapes.size(); ++i) {
        pieces.push_back(pieceMass(out.shapes[i], densities[i]));
        mass += pieces.back().mass;
        centre += pieces.back().mass * pieces.back().centroid;
    }
    centre /= mass;
    Mat3 inertia = Mat3::Zero();
    for (const PieceMass& p : pieces) inertia += p.inertia + parallelAxis(p.mass, p.centroid - centre);
    if (def.mass) {  // the given mass, distributed as the shapes are
        inertia *= *def.mass / mass;
        mass = *def.mass;
    }

    Quat axes = Quat::Identity();
    Vec3 moments = inertia.diagonal();
    const double offDiagonal = (inertia - Mat3(inertia.diagonal().asDiagonal())).cwiseAbs().maxCoeff();
    if (def.inertia) {
        moments = *def.inertia;  // principal moments in the body frame, as given
    } else if (offDiagonal > 1e-12 * inertia.trace()) {
        // Not diagonal in the body frame: simulate in the principal frame.
        Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia);
        Mat3 v = eigen.eigenvectors();
        if (v.determinant() < 0) v.col(2) = -v.col(2);
        axes = Quat(v).normalized();
        moments = eigen.eigenvalues();
    }
    out.mass = {mass, moments, centre, axes};
    out.peerFrame = {centre, axes};
    // Shapes move from the body frame into the peer frame.
    const Quat toPeer = axes.conjugate();
    for (PeerShape& s : out.shapes) s.local = {toPeer * (s.local.position - centre), toPeer * s.local.orientation};
    return out;
}

}  // namespace anyphys

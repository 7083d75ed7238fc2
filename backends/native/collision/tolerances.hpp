#pragma once
// Tolerances shared by the polyhedral routines, relative to the size of the shapes so that
// results do not depend on the unit of length.

namespace anyphys::native::tolerance {

/// Separating-axis choice: a face of b, or an edge pair, replaces the best face of a only when
/// its separation is larger by this fraction of the smaller shape's size. Ties then resolve the
/// same way every step (coherent feature ids) and faces, which give whole manifolds, win.
inline constexpr double kAxisBias = 1e-3;

/// Edge pairs whose directions differ by less than this sine give no axis: the face axes
/// already cover parallel edges, and the cross product's direction is noise.
inline constexpr double kParallelEdges = 1e-6;

/// Below this fraction of the size, a distance routine's normal is unreliable and the
/// separating-axis test takes over (the shapes touch or overlap).
inline constexpr double kDistanceSwitch = 1e-6;

}  // namespace anyphys::native::tolerance

#pragma once
// Points on a crack belong to both of its faces. Clouds and quadrature rules give each face
// its own copy of such a point, moved off the crack along the crack's normal by a tiny
// offset (a fraction 1e-7 of the nodal spacing, far below any length the method resolves),
// so that supports that respect the domain (kernels/support_paths.hpp) tell the two
// faces apart. A point at a crack tip stays one point: it belongs to the material around
// the tip. At a mouth that meets the boundary at a slant, a copy that the offset would take
// out of the domain steps along the crack back into it. Boundary points of a crack face are
// moved the same way into the face's side.

#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/domain.hpp"

namespace mfree {

/// Offset of the copies, as a fraction of the nodal spacing h; a point within
/// crack_tolerance * h of a crack lies on it.
inline constexpr double crack_offset = 1e-7;
inline constexpr double crack_tolerance = 1e-9;

/// The points with each one on a crack (not at a tip) replaced by its two copies, the copy
/// on the left of the crack segment (a -> b as given) first. `origin`, when given, gets
/// for every returned point the index of the point it came from.
std::vector<Vec2> split_on_cracks(const Domain& domain, const std::vector<Vec2>& points, double h,
                                  std::vector<Index>* origin = nullptr);

/// Whether a crack that is not an interface crosses the inside of the box (a crack along
/// its edges does not: the box shrunk by 1e-9 of its size).
bool crack_crosses(const Domain& domain, const Box& box);

/// A point of boundary segment `segment` moved into the material beside it when the
/// segment is a crack face (offset crack_offset * h against its outward normal); ring
/// edges' points are returned as they are.
Vec2 inside_face(const BoundarySegment& segment, const Vec2& x, double h);

}  // namespace mfree

#pragma once
// What supports that respect the domain must respect (kernels/support_paths.hpp), made from
// a domain:
//   obstacles  both faces of every crack (one segment each), and the boundary edges that can
//              separate two points of the domain within a support: an edge is one when a
//              boundary vertex within `reach` of it lies strictly on its outer side (the
//              walls of a notch, a slot or a hole; never an edge of a convex outer ring);
//   corners    the reflex vertices of the rings (the domain turns right there), crack tips
//              and the inner vertices of cracks, these on the face where the crack turns
//              away (1e-3 of the shorter segment off the crack along the bisector, so that a
//              path bending there does not pass from one face to the other): where shortest
//              paths bend.
// Vertices where the boundary or a crack runs straight on are dropped first (a straight side
// meshed into many elements is one obstacle). An obstacle's end at a convex vertex or at a crack's mouth is
// moved out by 1e-9 of the segment's length, so no path along the boundary slips past it through the outside.

//
// In a solid the obstacles are the surface triangles that can separate two points of the
// solid within a support (kernels/surface_visibility.hpp): a triangle is one when a vertex of
// the surface within `reach` of it lies strictly on its outer side, beyond 1e-9 of the reach
// (the walls of a slot, a cavity or a hole, the faces of a re-entrant edge; never a face of a
// convex part, nor a facet of a convex curved face).

#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/solid.hpp"
#include "mfree/kernels/support_paths.hpp"
#include "mfree/kernels/surface_visibility.hpp"

namespace mfree {

/// The obstacles and corners of `domain` for supports of radius up to `reach`.
SupportObstacles support_obstacles(const Domain& domain, double reach);

/// The obstacle triangles of `solid`'s surface for supports of radius up to `reach`.
SurfaceObstacles support_obstacles(const Solid& solid, double reach);

}  // namespace mfree

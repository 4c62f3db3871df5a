#pragma once
// Convex polygons in space (pieces of a solid's surface triangles): clipped by axis-aligned
// half-spaces and boxes (Sutherland and Hodgman 1974, one plane at a time; a convex polygon
// stays convex), and split into the part inside a box and convex parts outside it. Vertices
// in order round the polygon; fewer than 3 is empty.

#include <vector>

#include "mfree/geometry/solid.hpp"

namespace mfree {

using ConvexPolygon = std::vector<Point<3>>;

/// The part of p with x[axis] <= value (below) or x[axis] >= value (not below).
ConvexPolygon clip_half_space(const ConvexPolygon& p, int axis, double value, bool below);
/// The part of p inside the closed box.
ConvexPolygon clip_to_box(ConvexPolygon p, const AlignedBox<3>& box);
/// p cut by the six planes of the box: the part inside it first (possibly empty), then the
/// parts outside it, each within or beyond every plane of the box.
std::vector<ConvexPolygon> split_by_box(const ConvexPolygon& p, const AlignedBox<3>& box);
/// The area of p.
double polygon_area(const ConvexPolygon& p);

}  // namespace mfree

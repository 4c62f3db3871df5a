#pragma once
// Quadrature of a cut cell: the part of a background cell inside the domain (or inside one
// region of it), a polygon that Domain::clip returns.
//
// The polygon is cut into convex pieces (Hertel and Mehlhorn's approximate convex partition,
// by CGAL). A piece of a curved boundary has many vertices, nearly in line; its corners are
// kept (Douglas and Peucker: a vertex stays when it lies more than 1/20 of the cell's size
// from the chord of those kept around it), and the convex polygon of the corners is fanned
// into triangles that carry the collapsed (Duffy) product rule of m x m Gauss points, exact
// for polynomials of total degree 2 m - 2: with t_i, w_i on [0, 1], x(u, v) = a + u [(b - a)
// + v (c - b)], weight w_i w_j u_i |det(b - a, c - b)|. The thin caps between the corners'
// chords and the piece's own edges (convex, so outside the corners' polygon and inside the
// piece) carry a point at the centroid of each of their fan triangles, weighted by its area:
// exact for linear functions on a sliver whose width is below 1/20 of the cell. Every point
// lies inside the polygon; every weight is positive.

#include <vector>

#include "mfree/geometry/domain.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

/// Appends the points of the polygon `rings` (counter-clockwise outer rings, clockwise holes,
/// as Domain::clip returns them) with m points per direction per triangle; `size` is the
/// cell's size (the simplification's scale). Convex pieces of each ring take the rule; a
/// region with a hole, or a ring that touches itself (a hole's vertex on the cell's side),
/// takes it on the triangles of the region (triangulate_rings). Returns false, appending
/// nothing, when rounding made edges cross: the caller cuts the cell smaller.
bool add_polygon_rule(const std::vector<Ring>& rings, int m, double size, QuadratureRule<2>& rule);

/// Appends the points of the part of `cell` in the domain (in region `region` when >= 0:
/// Domain::clip), m points per direction per triangle; `clipped`, when given, is that part
/// already clipped. A part with a hole, or not simple, is cut into four first (to depth 8).
void add_cut_cell_rule(const Domain& domain, const Box& cell, int region, int m, QuadratureRule<2>& rule,
                       const std::vector<Ring>* clipped = nullptr, int depth = 0);

}  // namespace mfree

#pragma once
// Gauss–Legendre points on a background grid of square-ish cells, the classic "background
// cell" quadrature of meshfree methods. Cells are fitted to the domain's bounding box
// (nominal side `cell_size`, adjusted per axis to an integer count). A cell the boundary cuts
// is integrated over its part in the domain (Domain::clip) by a polygon rule of degree 2 n
// (polygon_quadrature.hpp), and in a domain of regions each region's part of a cell near an
// interface separately, so that no cell's points straddle a kink of the solution or a jump
// of the law. (Dropping the points outside, the common practice, left the Lamé cylinder's L2
// error non-monotone in h: 2.0e-4 at h = 0.05, 3.0e-4 at 0.025.) A point on a crack becomes
// two, one on each face, with half its weight each (geometry/crack_faces.hpp); a cell that a
// crack crosses is quartered (crack_depth).

#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/solid.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

/// Levels of quartering of a cell that a crack crosses: the functions jump across a crack, and a
/// Gauss rule over the jump is first-order (an inclined crack through the cells left quadratic
/// RK on a perturbed cloud noisy beside it: the reactions of a notched plate off balance by
/// 1.1e-2, 1.3e-5 with the quarters).
inline constexpr int crack_depth = 3;

/// n x n Gauss points per cell (n >= 1).
QuadratureRule<2> gauss_cell_rule(const Domain& domain, double cell_size, int n);
/// n x n x n Gauss points per cell of a solid (a box: every cell whole), cells fitted to its
/// bounding box as above; exact for polynomials of degree 2 n - 1 in each coordinate. A
/// meshed solid: its tetrahedra clipped to the cells, n^3 collapsed Gauss points on each
/// piece (quadrature/tetrahedron_rule.hpp: exact to total degree 2 n - 3 over Omega_h).
QuadratureRule<3> gauss_cell_rule(const Solid& solid, double cell_size, int n);

/// Appends the points of one cell: n x n Gauss points, or a polygon rule of degree 2 n on its
/// part in the domain (each region's part apart, polygon_quadrature.hpp); a cell a crack
/// crosses is quartered first, to depth crack_depth. Points on a crack are not split here.
void add_cell_points(const Domain& domain, const Box& cell, int n, QuadratureRule<2>& rule, int depth = 0);

}  // namespace mfree

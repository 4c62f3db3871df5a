#pragma once
// Gauss–Legendre points on a background grid of square-ish cells, the classic "background
// cell" quadrature of meshfree methods. Cells are fitted to the domain's bounding box
// (nominal side `cell_size`, adjusted per axis to an integer count). A cell the boundary cuts
// is integrated over its part in the domain (Domain::clip) by a polygon rule of degree 2 n
// (polygon_quadrature.hpp), and in a domain of regions each region's part of a cell near an
// interface separately, so that no cell's points straddle a kink of the solution or a jump
// of the law. (Dropping the points outside, the common practice, left the Lamé cylinder's L2
// error non-monotone in h: 2.0e-4 at h = 0.05, 3.0e-4 at 0.025.) A point on a crack becomes
// two, one on each face, with half its weight each (geometry/crack_faces.hpp).

#include "mfree/geometry/domain.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

/// n x n Gauss points per cell (n >= 1).
QuadratureRule gauss_cell_rule(const Domain& domain, double cell_size, int n);

}  // namespace mfree

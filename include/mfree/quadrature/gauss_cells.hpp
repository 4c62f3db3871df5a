#pragma once
// Baseline: Gauss–Legendre points on a background grid of square-ish cells, the classic
// "background cell" quadrature of meshfree methods. Cells are fitted to the domain's
// bounding box (nominal side `cell_size`, adjusted per axis to an integer count);
// points outside the domain are dropped, as that practice does (cut cells are not
// integrated exactly: the reason meshfree quadrature exists). A point on a crack becomes
// two, one on each face, with half its weight each (geometry/crack_faces.hpp).

#include "mfree/geometry/domain.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

/// n x n Gauss points per cell (n >= 1).
QuadratureRule gauss_cell_rule(const Domain& domain, double cell_size, int n);

}  // namespace mfree

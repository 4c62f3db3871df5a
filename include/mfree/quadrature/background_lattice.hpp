#pragma once
// The background lattice: one global lattice over the domain's bounding box whose
// windows are the local virtual background grids of the quadrature points (seed 003;
// SPEC sections 2 and 3).
//
// Integration cells of side order * spacing carry a tensor Newton–Cotes rule:
// order 1 is the trapezoid rule (cell vertices), order 2 Simpson's rule (vertices, edge
// midpoints and centre). Each lattice vertex v gets the weight
//
//     c_v = integral over Omega of N_v,
//
// N_v the tensor Lagrange function of v on the cells around it, so the lattice rule
// sum_v c_v f(x_v) integrates the piecewise (bi)linear / (bi)quadratic interpolant of f
// over Omega. Cells cut by the boundary integrate that interpolant over their inside part
// exactly (the cell clipped by Domain::clip, Green's theorem on the clipped rings):
// no cut-cell approximation beyond the interpolation itself.
//
// Why one lattice: a quadrature point's weight w_K = integral of phi_K is computed as
// sum_v c_v phi_K(x_v), i.e. on the window of this lattice covering supp(phi_K). Because
// every window shares the vertices and the c_v, the partition of unity sum_K phi_K = 1 and
// linear reproduction give sum_K w_K = sum_v c_v = |Omega| and sum_K w_K x_K = integral of x
// to round-off, and each phi_K(x_v) is evaluated once for all K instead of once per window.

#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/domain.hpp"

namespace mfree {

class BackgroundLattice {
 public:
  /// Lattice of vertex spacing `spacing` > 0 and Newton–Cotes order 1 or 2 over the domain.
  BackgroundLattice(const Domain& domain, double spacing, int order);

  [[nodiscard]] double spacing() const { return spacing_; }
  [[nodiscard]] int order() const { return order_; }
  /// Vertices with a non-zero weight (those of cells meeting Omega), in lattice order.
  [[nodiscard]] const std::vector<Vec2>& points() const { return points_; }
  /// c_v for each of points(); may be negative on cut Simpson cells.
  [[nodiscard]] const std::vector<double>& weights() const { return weights_; }
  [[nodiscard]] Index cut_cells() const { return cut_cells_; }
  [[nodiscard]] Index cells() const { return cells_; }

 private:
  double spacing_;
  int order_;
  std::vector<Vec2> points_;
  std::vector<double> weights_;
  Index cut_cells_ = 0;
  Index cells_ = 0;
};

/// Integrals over the region bounded by `rings` (Green's theorem orientation: outer
/// counter-clockwise, holes clockwise) of the (order+1)^2 tensor Lagrange functions of
/// the square cell [lo, lo + side]^2 with equispaced nodes; out[j * (order + 1) + i]
/// belongs to the node (i, j). Exact for polygons.
void lagrange_cell_integrals(const std::vector<Ring>& rings, const Vec2& lo, double side,
                             int order, double* out);

}  // namespace mfree

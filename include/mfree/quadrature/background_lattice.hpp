#pragma once
// The background lattice: one global lattice over the domain's bounding box whose
// windows are the local virtual background grids of the quadrature points (seed 003;
// SPEC sections 2 and 3).
//
// Integration cells of side order * spacing carry a tensor Newton–Cotes rule:
// order 1 is the trapezoid rule (cell vertices), order 2 Simpson's rule (vertices, edge
// midpoints and centre). Each lattice vertex v of the cells wholly inside Omega gets the
// weight c_v = sum over those cells of the integral of its Lagrange function N_v.
// A cell cut by the boundary is clipped to Omega (Domain::clip) and integrated by its own
// points, all in the closed domain (vertices and edge midpoints of the cut part, inside
// Gauss points), with weights fitted to the exact moments of the cut part (Green's theorem):
// exact for polynomials of degree <= order, so the whole rule is too.
//
// Why one lattice: a quadrature point's weight w_K = integral of phi_K is computed as
// sum_v c_v phi_K(x_v), i.e. on the window of this lattice covering supp(phi_K). Because
// every window shares the points and the c_v, the partition of unity sum_K phi_K = 1 and
// linear reproduction give sum_K w_K = sum_v c_v = |Omega| and sum_K w_K x_K = integral of x
// to round-off, and each phi_K(x_v) is evaluated once for all K instead of once per window.
// Every point lies in the closed domain, where the quadrature-cloud functions are defined.
// A cell near an interface, or one a crack crosses, is integrated by the points of
// gauss_cells.hpp's add_cell_points (region by region, quartered along the crack; degree
// 2 order + 1), so that no point's rule straddles a jump of the functions or the law. A point
// on a crack or an interface is two, one on each face with half its weight
// (quadrature/rule_on_cracks.hpp): the functions of either face see their own copy. In a
// solid a cell that touches a tied interface (Solid::interfaces()) is a cut cell, its part in
// each region integrated apart by points inside that region.

#include <type_traits>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/domain_of.hpp"

namespace mfree {

/// The lattice of a plane Domain (above) or of a Solid (dim = 3). A solid's lattice is fitted
/// to its bounding box, the cell sides order * spacing adjusted per axis so that a whole
/// number of cells spans it: every cell of a box solid is whole, and c_v is the tensor
/// product of the composite Newton–Cotes weights along the three axes. (Cut cells against a
/// solid's surfaces come with the solids from gmsh.)
template <int dim>
class BackgroundLattice {
 public:
  using DomainType = DomainOf<dim>;

  /// Lattice of vertex spacing `spacing` > 0 and Newton–Cotes order 1 or 2 over the domain.
  BackgroundLattice(const DomainType& domain, double spacing, int order);

  /// The nominal vertex spacing (a solid's is adjusted per axis, above).
  [[nodiscard]] double spacing() const { return spacing_; }
  [[nodiscard]] int order() const { return order_; }
  /// Lattice vertices with a non-zero weight, in lattice order, then the cut cells' points
  /// (each on a crack as its two face copies).
  [[nodiscard]] const std::vector<Point<dim>>& points() const { return points_; }
  /// The weight of each of points(); cut cells' weights may be negative.
  [[nodiscard]] const std::vector<double>& weights() const { return weights_; }
  [[nodiscard]] Index cut_cells() const { return cut_cells_; }
  [[nodiscard]] Index cells() const { return cells_; }

 private:
  double spacing_;
  int order_;
  std::vector<Point<dim>> points_;
  std::vector<double> weights_;
  Index cut_cells_ = 0;
  Index cells_ = 0;
};

template <>
BackgroundLattice<2>::BackgroundLattice(const Domain& domain, double spacing, int order);
template <>
BackgroundLattice<3>::BackgroundLattice(const Solid& solid, double spacing, int order);

/// Integrals over the region bounded by `rings` (Green's theorem orientation: outer
/// counter-clockwise, holes clockwise) of the (order+1)^2 tensor Lagrange functions of
/// the square cell [lo, lo + side]^2 with equispaced nodes; out[j * (order + 1) + i]
/// belongs to the node (i, j). Exact for polygons.
void lagrange_cell_integrals(const std::vector<Ring>& rings, const Vec2& lo, double side,
                             int order, double* out);

}  // namespace mfree

#pragma once
// Quadrature of the Galerkin weak form: points x_K with weights w_K and, at each point, the
// DOF-node shape functions the weak form needs there, stored row by row (CSR):
//
//   row K: nodes I (sorted), phi_I(x_K), and the gradient used for phi_I at x_K.
//
// Three constructions, all on the same DOF cloud:
//   projected   our scheme (seed 003; SPEC section 3): quadrature cloud x_K, weights
//               w_K = integral of phi_K, projected gradients
//                 gradbar phi_I(x_K) = (1 / w_K) integral of phi_K grad phi_I,
//               both on the background lattice (one evaluation of every function per
//               lattice point). gradbar reproduces gradients exactly: sum_I gradbar phi_I x_I^T = I.
//               For quadratic RK it is the gradient of a quadratic field at the centroid
//               c_K = (1 / w_K) integral of phi_K x (the field's gradient is linear), not at
//               x_K: quadratic consistency conditions are stated at c_K (SPEC section 3).
//   direct      any given rule (Gauss points on background cells, or the nodes themselves
//               with Voronoi weights: direct nodal integration) with the gradients of phi_I.
// A consistency correction (consistency.hpp) may then adjust the gradients.

#include <span>
#include <vector>

#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/quadrature/background_lattice.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

template <int dim>
struct GalerkinQuadrature {
  std::vector<Point<dim>> points;
  std::vector<double> weights;
  std::vector<Point<dim>> centroids;  ///< c_K: where the row's gradients are exact (x_K for direct rules)
  std::vector<Index> offsets;  ///< row K is [offsets[K], offsets[K + 1])
  std::vector<Index> nodes;
  std::vector<double> phi;
  std::vector<Point<dim>> grad;

  [[nodiscard]] Index size() const { return static_cast<Index>(points.size()); }
  [[nodiscard]] Index row_begin(Index k) const { return offsets[k]; }
  [[nodiscard]] Index row_end(Index k) const { return offsets[k + 1]; }
};

/// The projected construction on a quadrature cloud with its RK functions (dim = 2, 3).
template <int dim>
GalerkinQuadrature<dim> projected_quadrature(const RKShapeFunctions<dim>& trial,
                                             const RKShapeFunctions<dim>& quadrature_functions,
                                             const BackgroundLattice<dim>& lattice);

/// The direct construction on a given rule.
template <int dim>
GalerkinQuadrature<dim> direct_quadrature(const RKShapeFunctions<dim>& trial,
                                          const QuadratureRule<dim>& rule);

/// Values and gradients of the trial functions at arbitrary points (boundary points,
/// error points, output points), row by row like a GalerkinQuadrature with unit weights.
template <int dim>
GalerkinQuadrature<dim> sample_shape_functions(const RKShapeFunctions<dim>& trial,
                                               const std::vector<Point<dim>>& points, bool with_gradient);

}  // namespace mfree

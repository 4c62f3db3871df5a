#pragma once
// A quadrature rule: integral of f over Omega ~ sum_k weights[k] f(points[k]).

#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

/// Points and weights in dim dimensions.
template <int dim>
struct QuadratureRule {
  std::vector<Point<dim>> points;
  std::vector<double> weights;
  [[nodiscard]] std::size_t size() const { return points.size(); }
};

/// Gauss–Legendre points and weights on [0, 1] (n >= 1 points, exact to degree 2n - 1),
/// ascending, from the roots of the Legendre polynomial P_n by Newton's method.
struct GaussLegendre1D {
  std::vector<double> points;
  std::vector<double> weights;
};
GaussLegendre1D gauss_legendre(int n);

}  // namespace mfree

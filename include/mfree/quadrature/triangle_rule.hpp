#pragma once
// The collapsed (Duffy) product rule on a flat triangle (a, b, c) in the plane or in space:
// with t_i, w_i the Gauss–Legendre points and weights on [0, 1],
//   x(u, v) = a + u [(b - a) + v (c - b)],   weight w_i w_j u_i |(b - a) x (c - b)|,
// exact for polynomials of total degree 2 m - 2 (m points per direction); every point
// inside, every weight positive. A degenerate triangle adds nothing.

#include <cmath>

#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

/// The area of the parallelogram of edges e and f (twice the triangle's) (|e x f|).
inline double parallelogram_area(const Point<2>& e, const Point<2>& f) {
  return std::abs(e.x() * f.y() - e.y() * f.x());
}
inline double parallelogram_area(const Point<3>& e, const Point<3>& f) { return e.cross(f).norm(); }

template <int dim>
void add_triangle_rule(const Point<dim>& a, const Point<dim>& b, const Point<dim>& c,
                       const GaussLegendre1D& g, QuadratureRule<dim>& rule) {
  const Point<dim> ab = b - a, bc = c - b;
  const double det = parallelogram_area(ab, Point<dim>(c - a));
  if (det == 0.0) return;
  for (std::size_t i = 0; i < g.points.size(); ++i)
    for (std::size_t j = 0; j < g.points.size(); ++j) {
      const double u = g.points[i], v = g.points[j];
      rule.points.push_back(a + u * (ab + v * bc));
      rule.weights.push_back(g.weights[i] * g.weights[j] * u * det);
    }
}

}  // namespace mfree

#pragma once
// The collapsed (Duffy) product rule on a tetrahedron (a, b, c, d): with t_i, w_i the
// Gauss–Legendre points and weights on [0, 1],
//   x(u, v, s) = a + u [(b - a) + v ((c - b) + s (d - c))],
//   weight w_i w_j w_k u_i^2 v_j |det(b - a, c - a, d - a)|
// (the Jacobian of the map is u^2 v det), exact for polynomials of total degree 2 m - 3
// (m points per direction); every point inside, every weight positive. A degenerate
// tetrahedron adds nothing.

#include <cmath>

#include "mfree/geometry/tetrahedron.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

inline void add_tetrahedron_rule(const Tetrahedron& t, const GaussLegendre1D& g, QuadratureRule<3>& rule) {
  const Point<3> e1 = t[1] - t[0], e2 = t[2] - t[1], e3 = t[3] - t[2];
  const double det = std::abs(e1.dot(e2.cross(e3)));
  if (det == 0.0) return;
  for (std::size_t i = 0; i < g.points.size(); ++i)
    for (std::size_t j = 0; j < g.points.size(); ++j)
      for (std::size_t k = 0; k < g.points.size(); ++k) {
        const double u = g.points[i], v = g.points[j], s = g.points[k];
        rule.points.push_back(t[0] + u * (e1 + v * (e2 + s * e3)));
        rule.weights.push_back(g.weights[i] * g.weights[j] * g.weights[k] * u * u * v * det);
      }
}

}  // namespace mfree

#pragma once
// Gauss points on the boundary segments of the domain: each segment is cut into pieces no
// longer than `max_length`, each piece carrying `gauss_points` Gauss–Legendre points.
// Exact for polynomials of degree 2 gauss_points - 1 along straight segments, so sums of
// x n and 1 n over the whole boundary vanish/close to round-off (divergence theorem).

#include <vector>

#include "mfree/geometry/domain.hpp"

namespace mfree {

struct BoundaryQuadrature {
  std::vector<Vec2> points;
  std::vector<Vec2> normals;    ///< outward unit normals
  std::vector<double> weights;  ///< length weights
  std::vector<Index> segment;   ///< index into Domain::boundary()
  [[nodiscard]] Index size() const { return static_cast<Index>(points.size()); }
};

BoundaryQuadrature boundary_quadrature(const Domain& domain, double max_length, int gauss_points);

}  // namespace mfree

#include "mfree/galerkin/boundary_quadrature.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

BoundaryQuadrature boundary_quadrature(const Domain& domain, double max_length, int gauss_points) {
  if (!(max_length > 0.0)) throw InputError(fmt::format("boundary quadrature: piece length must be positive, got {}", max_length));
  const GaussLegendre1D g = gauss_legendre(gauss_points);
  BoundaryQuadrature bq;
  const auto& segments = domain.boundary();
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const BoundarySegment& seg = segments[s];
    const int pieces = std::max(1, static_cast<int>(std::ceil(seg.length / max_length - 1e-9)));
    const double piece = seg.length / pieces;
    for (int p = 0; p < pieces; ++p)
      for (std::size_t k = 0; k < g.points.size(); ++k) {
        const double t = (p + g.points[k]) / pieces;
        bq.points.push_back(seg.a + t * (seg.b - seg.a));
        bq.normals.push_back(seg.normal);
        bq.weights.push_back(g.weights[k] * piece);
        bq.segment.push_back(static_cast<Index>(s));
      }
  }
  return bq;
}

}  // namespace mfree

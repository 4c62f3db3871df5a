#include "mfree/galerkin/boundary_quadrature.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

BoundaryQuadrature boundary_quadrature(const Domain& domain, double max_length, int gauss_points,
                                       const std::vector<BoundarySelection>& parts) {
  if (!(max_length > 0.0)) throw InputError(fmt::format("boundary quadrature: piece length must be positive, got {}", max_length));
  const GaussLegendre1D g = gauss_legendre(gauss_points);
  BoundaryQuadrature bq;
  const auto& segments = domain.boundary();
  // Per segment, the parameters where a part begins or ends.
  std::vector<std::vector<double>> breaks(segments.size(), std::vector<double>{0.0, 1.0});
  for (const BoundarySelection& part : parts)
    for (const BoundaryPiece& p : part) {
      breaks[p.segment].push_back(p.t0);
      breaks[p.segment].push_back(p.t1);
    }
  std::vector<Index> first(segments.size() + 1, 0);  // segment s's points: [first[s], first[s + 1])
  for (std::size_t s = 0; s < segments.size(); ++s) {
    first[s] = bq.size();
    const BoundarySegment& seg = segments[s];
    std::vector<double>& b = breaks[s];
    std::sort(b.begin(), b.end());
    // Breaks closer than round-off of the segment make no interval of their own.
    b.erase(std::unique(b.begin(), b.end(), [](double x, double y) { return y - x < 1e-12; }), b.end());
    b.back() = 1.0;
    const Vec2 tangent = (seg.b - seg.a) / seg.length;
    for (std::size_t i = 0; i + 1 < b.size(); ++i) {
      const double t0 = b[i], span = b[i + 1] - b[i];
      const int pieces = std::max(1, static_cast<int>(std::ceil(span * seg.length / max_length - 1e-9)));
      const double piece = span * seg.length / pieces;
      for (int p = 0; p < pieces; ++p)
        for (std::size_t k = 0; k < g.points.size(); ++k) {
          const double t = t0 + span * ((p + g.points[k]) / pieces);
          bq.points.push_back(seg.a + t * (seg.b - seg.a));
          bq.samples.push_back(inside_face(seg, bq.points.back(), max_length));
          bq.normals.push_back(seg.normal);
          bq.tangents.push_back(tangent);
          bq.weights.push_back(g.weights[k] * piece);
          bq.segment.push_back(static_cast<Index>(s));
        }
    }
  }
  first[segments.size()] = bq.size();
  // An interface segment's faces a -> b and b -> a follow each other (Domain::boundary()),
  // cut alike (no condition selects them) and with Gauss points symmetric about the middle:
  // the faces' points are the same in reverse order.
  bq.twin.assign(bq.points.size(), -1);
  for (std::size_t s = 0; s + 1 < segments.size(); ++s) {
    const BoundarySegment &face = segments[s], &other = segments[s + 1];
    if (face.crack < 0 || !domain.cracks()[face.crack].interface() || other.crack != face.crack ||
        other.a != face.b || other.b != face.a)
      continue;
    const Index n = first[s + 1] - first[s];
    if (first[s + 2] - first[s + 1] != n)
      throw Error(fmt::format("boundary quadrature: the faces of interface segment {} have {} and {} points",
                              s, n, first[s + 2] - first[s + 1]));
    for (Index j = 0; j < n; ++j) {
      const Index p = first[s] + j, q = first[s + 1] + n - 1 - j;
      if ((bq.points[p] - bq.points[q]).norm() > 1e-9 * max_length)
        throw Error(fmt::format("boundary quadrature: interface point {} has no twin on the other face", p));
      bq.twin[p] = q;
      bq.twin[q] = p;
    }
  }
  return bq;
}

GalerkinQuadrature<2> boundary_functions(const RKShapeFunctions<2>& trial, const BoundaryQuadrature& bq) {
  GalerkinQuadrature<2> at = sample_shape_functions(trial, bq.samples, true);
  for (Index p = 0; p < at.size(); ++p) {
    at.points[p] = bq.points[p];
    const Vec2 back = bq.points[p] - bq.samples[p];
    if (back != Vec2::Zero())
      for (Index s = at.row_begin(p); s < at.row_end(p); ++s) at.phi[s] += at.grad[s].dot(back);
  }
  return at;
}

}  // namespace mfree

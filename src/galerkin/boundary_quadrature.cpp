#include "mfree/galerkin/boundary_quadrature.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/geometry/convex_polygon.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"
#include "mfree/quadrature/triangle_rule.hpp"

namespace mfree {

namespace {

void check_piece_length(double max_length) {
  if (!(max_length > 0.0))
    throw InputError(fmt::format("boundary quadrature: piece length must be positive, got {}", max_length));
}

}  // namespace

int boundary_part(const Domain& domain, const std::vector<BoundarySelection<2>>& parts, Index segment,
                  const Vec2& x) {
  const BoundarySegment& seg = domain.boundary()[segment];
  const double t = (x - seg.a).dot(seg.b - seg.a) / (seg.length * seg.length);
  for (std::size_t k = 0; k < parts.size(); ++k)
    for (const BoundaryPiece<2>& piece : parts[k])
      if (piece.segment == segment && t >= piece.t0 && t <= piece.t1) return static_cast<int>(k);
  return -1;
}

int boundary_part(const Solid&, const std::vector<BoundarySelection<3>>& parts, Index triangle,
                  const Point<3>& x) {
  // A selection's pieces are in triangle order: those of this triangle by bisection.
  const auto by_triangle = [](const BoundaryPiece<3>& p, const BoundaryPiece<3>& q) {
    return p.triangle < q.triangle;
  };
  const BoundaryPiece<3> key{triangle, std::nullopt};
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const auto [from, to] = std::equal_range(parts[k].begin(), parts[k].end(), key, by_triangle);
    for (auto piece = from; piece != to; ++piece)
      if (!piece->clip || piece->clip->contains(x)) return static_cast<int>(k);
  }
  return -1;
}

BoundaryQuadrature<2> boundary_quadrature(const Domain& domain, double max_length, int gauss_points,
                                          const std::vector<BoundarySelection<2>>& parts) {
  check_piece_length(max_length);
  const GaussLegendre1D g = gauss_legendre(gauss_points);
  BoundaryQuadrature<2> bq;
  const auto& segments = domain.boundary();
  // Per segment, the parameters where a part begins or ends.
  std::vector<std::vector<double>> breaks(segments.size(), std::vector<double>{0.0, 1.0});
  for (const BoundarySelection<2>& part : parts)
    for (const BoundaryPiece<2>& p : part) {
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

BoundaryQuadrature<3> boundary_quadrature(const Solid& solid, double max_length, int gauss_points,
                                          const std::vector<BoundarySelection<3>>& parts) {
  check_piece_length(max_length);
  const GaussLegendre1D g = gauss_legendre(gauss_points);
  const auto& surface = solid.surface();
  // Per triangle, the boxes that cut it.
  std::vector<std::vector<AlignedBox<3>>> boxes(surface.size());
  for (const BoundarySelection<3>& part : parts)
    for (const BoundaryPiece<3>& p : part)
      if (p.clip) boxes[static_cast<std::size_t>(p.triangle)].push_back(*p.clip);
  BoundaryQuadrature<3> bq;
  QuadratureRule<3> rule;
  // The rule on triangle (a, a + e_full, a + f_full): cut into m x m similar ones, rows i, the
  // upright (a + i e + j f, + e, + f) and, between them, the inverted ones.
  const auto triangle_rule = [&](const Point<3>& a, const Point<3>& e_full, const Point<3>& f_full) {
    const double longest = std::max({e_full.norm(), f_full.norm(), (f_full - e_full).norm()});
    const int m = std::max(1, static_cast<int>(std::ceil(longest / max_length - 1e-9)));
    const Point<3> e = e_full / m, f = f_full / m;
    rule.points.clear();
    rule.weights.clear();
    for (int i = 0; i < m; ++i)
      for (int j = 0; i + j < m; ++j) {
        const Point<3> x = a + i * e + j * f;
        add_triangle_rule<3>(x, Point<3>(x + e), Point<3>(x + f), g, rule);
        if (i + j + 1 < m)
          add_triangle_rule<3>(Point<3>(x + e), Point<3>(x + e + f), Point<3>(x + f), g, rule);
      }
  };
  const auto add_point = [&bq](const Point<3>& x, const Point<3>& sample, const Point<3>& normal,
                               double weight, std::size_t segment) {
    bq.points.push_back(x);
    bq.samples.push_back(sample);
    bq.normals.push_back(normal);
    bq.weights.push_back(weight);
    bq.segment.push_back(static_cast<Index>(segment));
  };
  for (std::size_t t = 0; t < surface.size(); ++t) {
    const SurfaceTriangle& tri = surface[t];
    const Point<3> normal = tri.area_normal().normalized();
    std::vector<ConvexPolygon> polygons{ConvexPolygon(tri.vertices.begin(), tri.vertices.end())};
    for (const AlignedBox<3>& box : boxes[t]) {
      std::vector<ConvexPolygon> cut;
      for (const ConvexPolygon& p : polygons)
        for (ConvexPolygon& piece : split_by_box(p, box))
          if (!piece.empty()) cut.push_back(std::move(piece));
      polygons = std::move(cut);
    }
    for (const ConvexPolygon& p : polygons)
      for (std::size_t k = 1; k + 1 < p.size(); ++k) {
        triangle_rule(p[0], p[k] - p[0], p[k + 1] - p[0]);
        for (std::size_t q = 0; q < rule.size(); ++q)
          add_point(rule.points[q], rule.points[q], normal, rule.weights[q], t);
      }
  }
  // The tied interfaces: each point on both faces, the `from` side's first (outward normal n,
  // sampled crack_offset max_length into its region), then the `to` side's (-n), twins.
  const std::vector<InterfaceTriangle>& interfaces = solid.interfaces();
  bq.twin.assign(bq.points.size(), -1);
  for (std::size_t t = 0; t < interfaces.size(); ++t) {
    const auto& v = interfaces[t].vertices;
    const Point<3> n = interfaces[t].area_normal().normalized();
    const Point<3> offset = crack_offset * max_length * n;
    triangle_rule(v[0], v[1] - v[0], v[2] - v[0]);
    for (std::size_t q = 0; q < rule.size(); ++q) {
      const auto p = static_cast<Index>(bq.points.size());
      add_point(rule.points[q], Point<3>(rule.points[q] - offset), n, rule.weights[q], surface.size() + t);
      add_point(rule.points[q], Point<3>(rule.points[q] + offset), Point<3>(-n), rule.weights[q],
                surface.size() + t);
      bq.twin.push_back(p + 1);
      bq.twin.push_back(p);
    }
  }
  if (interfaces.empty()) bq.twin.clear();
  return bq;
}

template <int dim>
GalerkinQuadrature<dim> boundary_functions(const RKShapeFunctions<dim>& trial,
                                           const BoundaryQuadrature<dim>& bq) {
  GalerkinQuadrature<dim> at = sample_shape_functions(trial, bq.samples, true);
  for (Index p = 0; p < at.size(); ++p) {
    at.points[p] = bq.points[p];
    const Point<dim> back = bq.points[p] - bq.samples[p];
    if (back != Point<dim>::Zero())
      for (Index s = at.row_begin(p); s < at.row_end(p); ++s) at.phi[s] += at.grad[s].dot(back);
  }
  return at;
}

template GalerkinQuadrature<2> boundary_functions(const RKShapeFunctions<2>&, const BoundaryQuadrature<2>&);
template GalerkinQuadrature<3> boundary_functions(const RKShapeFunctions<3>&, const BoundaryQuadrature<3>&);

}  // namespace mfree

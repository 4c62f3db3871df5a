#include "mfree/quadrature/polygon_quadrature.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Partition_traits_2.h>
#include <CGAL/partition_2.h>
#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <list>

#include "mfree/core/error.hpp"
#include "mfree/geometry/domain_triangulation.hpp"
#include "mfree/geometry/polygon_integrals.hpp"
#include "mfree/quadrature/triangle_rule.hpp"

namespace mfree {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Traits = CGAL::Partition_traits_2<Kernel>;
using Piece = Traits::Polygon_2;

double twice_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 ab = b - a, ac = c - a;
  return ab.x() * ac.y() - ab.y() * ac.x();
}

/// Marks in `keep` the vertices of the chain first..last (indices into p, first < last) that
/// lie more than `tolerance` from the chord of the kept ones around them (Douglas–Peucker).
void keep_corners(const std::vector<Vec2>& p, std::size_t first, std::size_t last, double tolerance,
                  std::vector<bool>& keep) {
  if (last <= first + 1) return;
  const Vec2 d = p[last] - p[first];
  const double length = d.norm();
  std::size_t far = first;
  double distance = 0.0;
  for (std::size_t k = first + 1; k < last; ++k) {
    const double e =
        length > 0.0 ? std::abs(twice_area(p[first], p[last], p[k])) / length : (p[k] - p[first]).norm();
    if (e > distance) {
      distance = e;
      far = k;
    }
  }
  if (distance <= tolerance) return;
  keep[far] = true;
  keep_corners(p, first, far, tolerance, keep);
  keep_corners(p, far, last, tolerance, keep);
}

/// The rule on one convex piece (counter-clockwise vertices).
void add_convex_piece(const std::vector<Vec2>& p, const GaussLegendre1D& g, double tolerance,
                      QuadratureRule<2>& rule) {
  const std::size_t n = p.size();
  // Corners: the vertex farthest from vertex 0 and vertex 0 split the ring into two chains.
  std::size_t opposite = 1;
  for (std::size_t k = 2; k < n; ++k)
    if ((p[k] - p[0]).squaredNorm() > (p[opposite] - p[0]).squaredNorm()) opposite = k;
  std::vector<Vec2> closed(p);
  closed.push_back(p[0]);
  std::vector<bool> keep(n + 1, false);
  keep[0] = keep[opposite] = keep[n] = true;
  keep_corners(closed, 0, opposite, tolerance, keep);
  keep_corners(closed, opposite, n, tolerance, keep);
  std::vector<std::size_t> corners;
  for (std::size_t k = 0; k < n; ++k)
    if (keep[k]) corners.push_back(k);
  // The corners' polygon, fanned.
  for (std::size_t k = 1; k + 1 < corners.size(); ++k)
    add_triangle_rule<2>(p[corners[0]], p[corners[k]], p[corners[k + 1]], g, rule);
  // The caps between consecutive corners a, b and the edges from a to b: a centroid per fan
  // triangle (a, k, k + 1).
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const std::size_t a = corners[c], b = c + 1 < corners.size() ? corners[c + 1] : n;
    for (std::size_t k = a + 1; k < b; ++k) {
      const double area = 0.5 * twice_area(closed[a], closed[k], closed[k + 1]);
      if (!(area > 0.0)) continue;
      rule.points.push_back((closed[a] + closed[k] + closed[k + 1]) / 3.0);
      rule.weights.push_back(area);
    }
  }
}

}  // namespace

bool add_polygon_rule(const std::vector<Ring>& rings, int m, double size, QuadratureRule<2>& rule) {
  const GaussLegendre1D g = gauss_legendre(m);
  // Holes, or rings that touch themselves: Gauss rules on the triangles of the region.
  const auto on_triangles = [&] {
    const auto triangles = triangulate_rings(rings);
    if (!triangles) return false;  // rounding made edges cross: the caller cuts the cell smaller
    for (const std::array<Vec2, 3>& t : *triangles) add_triangle_rule<2>(t[0], t[1], t[2], g, rule);
    return true;
  };
  for (const Ring& ring : rings)
    if (ring_area(ring) < -1e-14 * size * size) return on_triangles();
  std::vector<std::list<Piece>> partitions;
  for (const Ring& ring : rings) {
    // A sliver of no area (the exact intersection touching the cell at a point or along an
    // edge, rounded) holds nothing to integrate.
    if (ring.size() < 3 || ring_area(ring) <= 1e-14 * size * size) continue;
    Piece polygon;
    for (std::size_t k = 0; k < ring.size(); ++k)  // vertices that rounding made equal, once
      if (ring[k] != ring[(k + 1) % ring.size()])
        polygon.push_back(Traits::Point_2(ring[k].x(), ring[k].y()));
    if (!polygon.is_simple()) return on_triangles();  // it touches itself
    std::list<Piece>& pieces = partitions.emplace_back();
    if (polygon.is_convex())
      pieces.push_back(polygon);
    else
      CGAL::approx_convex_partition_2(polygon.vertices_begin(), polygon.vertices_end(),
                                      std::back_inserter(pieces));
  }
  for (const std::list<Piece>& pieces : partitions)
    for (const Piece& piece : pieces) {
      std::vector<Vec2> p;
      for (auto v = piece.vertices_begin(); v != piece.vertices_end(); ++v) p.emplace_back(v->x(), v->y());
      if (p.size() >= 3) add_convex_piece(p, g, size / 20.0, rule);
    }
  return true;
}

void add_cut_cell_rule(const Domain& domain, const Box& cell, int region, int m, QuadratureRule<2>& rule,
                       const std::vector<Ring>* clipped, int depth) {
  const std::vector<Ring> rings = clipped ? *clipped : domain.clip(cell, region);
  if (rings.empty() || add_polygon_rule(rings, m, cell.size().maxCoeff(), rule)) return;
  if (depth == 8)
    throw Error(fmt::format("cut cell: the cell [{}, {}] x [{}, {}] cannot be cut into simple pieces",
                            cell.lo.x(), cell.hi.x(), cell.lo.y(), cell.hi.y()));
  const Vec2 mid = 0.5 * (cell.lo + cell.hi);
  for (const Box& quarter : {Box{cell.lo, mid}, Box{Vec2(mid.x(), cell.lo.y()), Vec2(cell.hi.x(), mid.y())},
                             Box{Vec2(cell.lo.x(), mid.y()), Vec2(mid.x(), cell.hi.y())}, Box{mid, cell.hi}})
    add_cut_cell_rule(domain, quarter, region, m, rule, nullptr, depth + 1);
}

}  // namespace mfree

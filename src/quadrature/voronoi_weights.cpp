#include "mfree/quadrature/voronoi_weights.hpp"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/convex_hull_2.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <utility>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/geometry/polygon_integrals.hpp"
#include "mfree/geometry/segment_grid.hpp"

namespace mfree {

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
// Vertices carry the point index (-1 for the bounding dummies), faces the index of their
// circumcentre, computed once so that neighbouring cells share the very same vertices.
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<Index, Epick>;
using FaceBase = CGAL::Triangulation_face_base_with_info_2<std::size_t, Epick>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Epick, Tds>;
using ExactPolygon = CGAL::Polygon_2<Epeck>;
using ExactPolygonWithHoles = CGAL::Polygon_with_holes_2<Epeck>;

ExactPolygon exact_polygon(const Ring& ring) {
  ExactPolygon p;
  for (const Vec2& x : ring) p.push_back(Epeck::Point_2(x.x(), x.y()));
  return p;
}

bool boxes_meet(const Box& a, const Box& b) {
  return a.lo.x() <= b.hi.x() && b.lo.x() <= a.hi.x() && a.lo.y() <= b.hi.y() &&
         b.lo.y() <= a.hi.y();
}

/// |cell ∩ Omega| by an exact Boolean intersection, rounded to double at the end.
double clipped_area(const Ring& cell, const Box& cell_box, const std::vector<Ring>& rings,
                    const std::vector<Box>& ring_boxes) {
  // Holes away from the cell cannot change the intersection; leaving them out shortens the
  // sweep.
  ExactPolygonWithHoles omega(exact_polygon(rings[0]));
  for (std::size_t k = 1; k < rings.size(); ++k) {
    if (boxes_meet(cell_box, ring_boxes[k])) omega.add_hole(exact_polygon(rings[k]));
  }
  std::vector<ExactPolygonWithHoles> pieces;
  CGAL::intersection(omega, exact_polygon(cell), std::back_inserter(pieces));
  // Exact signed areas (outer boundaries CCW, holes CW), one rounding per piece.
  Epeck::FT area = 0;
  for (const ExactPolygonWithHoles& piece : pieces) {
    area += piece.outer_boundary().area();
    for (auto h = piece.holes_begin(); h != piece.holes_end(); ++h) area += h->area();
  }
  return CGAL::to_double(area);
}

}  // namespace

std::vector<double> voronoi_weights(const std::vector<Vec2>& points, const Domain& domain) {
  const std::size_t n = points.size();
  std::vector<double> weights(n, 0.0);
  if (n == 0) return weights;

  Box extent = domain.bounding_box();
  std::vector<std::pair<Epick::Point_2, Index>> sites;
  sites.reserve(n + 4);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& x = points[i];
    if (!x.allFinite()) {
      throw InputError(
          fmt::format("voronoi_weights: point {} has a non-finite coordinate ({}, {})", i, x.x(),
                      x.y()));
    }
    extent.lo = extent.lo.cwiseMin(x);
    extent.hi = extent.hi.cwiseMax(x);
    sites.emplace_back(Epick::Point_2(x.x(), x.y()), static_cast<Index>(i));
  }
  // Four dummy sites on a square of half-side R = 2 d around the centre c of the extent
  // (d its diagonal) bound every real cell. They cannot steal any part of Omega: a point of
  // Omega lies within d/2 of c, hence within d of every real site, but at least
  // R sqrt(2) - d/2 > 2.3 d from every dummy.
  const Vec2 c = 0.5 * (extent.lo + extent.hi);
  const double radius = 2.0 * (extent.hi - extent.lo).norm();
  for (const Vec2& corner : {Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)}) {
    const Vec2 x = c + radius * corner;
    sites.emplace_back(Epick::Point_2(x.x(), x.y()), Index{-1});
  }

  Delaunay dt;
  dt.insert(sites.begin(), sites.end());
  if (dt.number_of_vertices() != sites.size()) {
    // Some point was merged into an equal one; find one that lost its vertex.
    std::vector<char> present(n, 0);
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
      if (v->info() >= 0) present[static_cast<std::size_t>(v->info())] = 1;
    }
    const auto lost = static_cast<std::size_t>(
        std::find(present.begin(), present.end(), 0) - present.begin());
    const auto kept = static_cast<std::size_t>(dt.nearest_vertex(sites[lost].first)->info());
    throw InputError(fmt::format(
        "voronoi_weights: points {} and {} coincide at ({}, {}); points must be distinct",
        std::min(kept, lost), std::max(kept, lost), points[lost].x(), points[lost].y()));
  }

  // Voronoi vertices: the circumcentre of each Delaunay face.
  std::vector<Vec2> centres;
  centres.reserve(static_cast<std::size_t>(dt.number_of_faces()));
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    const Epick::Point_2 q = dt.dual(f);
    f->info() = centres.size();
    centres.emplace_back(q.x(), q.y());
  }

  const std::vector<Ring>& rings = domain.rings();
  std::vector<Box> ring_boxes;
  for (const Ring& r : rings) ring_boxes.push_back(ring_bounding_box(r));
  const SegmentGrid grid(domain.boundary());
  const Box& omega_box = ring_boxes[0];

  // Cells the boundary may cross, clipped afterwards: (point index, cell, cell box).
  struct Pending {
    std::size_t point;
    Ring cell;
    Box box;
  };
  std::vector<Pending> pending;
  std::vector<Epick::Point_2> corners;
  std::vector<Epick::Point_2> hull;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    if (v->info() < 0) continue;
    const auto i = static_cast<std::size_t>(v->info());
    // Every real site lies strictly inside the dummies' square, so all its faces are finite.
    corners.clear();
    auto f = dt.incident_faces(v);
    const auto first = f;
    do {
      const Vec2& q = centres[f->info()];
      corners.emplace_back(q.x(), q.y());
    } while (++f != first);
    // Cocircular sites (a lattice) give repeated circumcentres whose rounding may fold the
    // cell by ~1e-16; the convex hull (exact predicates) restores a simple convex cell and
    // moves its area by round-off only.
    hull.clear();
    CGAL::convex_hull_2(corners.begin(), corners.end(), std::back_inserter(hull));
    Ring cell;
    cell.reserve(hull.size());
    for (const Epick::Point_2& q : hull) cell.emplace_back(q.x(), q.y());
    const Box box = ring_bounding_box(cell);

    if (!boxes_meet(box, omega_box)) continue;
    if (!grid.may_touch(box)) {
      // No boundary point in the cell: it lies wholly inside or outside, like its site.
      if (domain.contains(points[i])) weights[i] = ring_area(cell);
      continue;
    }
    pending.push_back(Pending{i, std::move(cell), box});
  }

  // Each block builds its own exact polygons, so threads share no CGAL object.
  parallel_blocks(static_cast<Index>(pending.size()), 16, [&](Index begin, Index end) {
    for (Index k = begin; k < end; ++k) {
      const Pending& p = pending[static_cast<std::size_t>(k)];
      weights[p.point] = clipped_area(p.cell, p.box, rings, ring_boxes);
    }
  });
  return weights;
}

}  // namespace mfree

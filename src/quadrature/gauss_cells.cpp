#include "mfree/quadrature/gauss_cells.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"
#include "mfree/quadrature/polygon_quadrature.hpp"
#include "mfree/quadrature/rule_on_cracks.hpp"
#include "mfree/quadrature/tetrahedron_rule.hpp"

namespace mfree {

namespace {

/// Whether the rings are the box itself (one ring of its four corners).
bool is_box(const std::vector<Ring>& rings, const Box& box) {
  if (rings.size() != 1 || rings[0].size() != 4) return false;
  return std::all_of(rings[0].begin(), rings[0].end(), [&](const Vec2& x) {
    return (x.x() == box.lo.x() || x.x() == box.hi.x()) && (x.y() == box.lo.y() || x.y() == box.hi.y());
  });
}

}  // namespace

void add_cell_points(const Domain& domain, const Box& cell, int n, QuadratureRule<2>& rule, int depth) {
  if (depth < crack_depth && crack_crosses(domain, cell)) {  // the functions jump across the crack
    const Vec2 mid = 0.5 * (cell.lo + cell.hi);
    for (const Box& quarter : {Box{cell.lo, mid}, Box{Vec2(mid.x(), cell.lo.y()), Vec2(cell.hi.x(), mid.y())},
                               Box{Vec2(cell.lo.x(), mid.y()), Vec2(mid.x(), cell.hi.y())}, Box{mid, cell.hi}})
      add_cell_points(domain, quarter, n, rule, depth + 1);
    return;
  }
  const int regions = static_cast<int>(domain.regions().size());
  if (!domain.boundary_near(cell)) {
    if (!domain.contains(0.5 * (cell.lo + cell.hi))) return;
  } else if (regions > 0) {  // each region's part: the law and the functions jump between them
    for (int r = 0; r < regions; ++r) add_cut_cell_rule(domain, cell, r, n + 1, rule);
    return;
  } else if (const std::vector<Ring> inside = domain.clip(cell); !is_box(inside, cell)) {  // cut by the boundary
    add_cut_cell_rule(domain, cell, -1, n + 1, rule, &inside);
    return;
  }
  const GaussLegendre1D g = gauss_legendre(n);
  const Vec2 size = cell.size();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      rule.points.emplace_back(cell.lo.x() + g.points[i] * size.x(), cell.lo.y() + g.points[j] * size.y());
      rule.weights.push_back(g.weights[i] * g.weights[j] * size.x() * size.y());
    }
}

QuadratureRule<2> gauss_cell_rule(const Domain& domain, double cell_size, int n) {
  if (!(cell_size > 0.0))
    throw InputError(fmt::format("Gauss cells: cell size must be positive, got {}", cell_size));
  const Box box = domain.bounding_box();
  const int nx = std::max(1, static_cast<int>(std::lround(box.size().x() / cell_size)));
  const int ny = std::max(1, static_cast<int>(std::lround(box.size().y() / cell_size)));
  const double hx = box.size().x() / nx, hy = box.size().y() / ny;
  // Rows of cells in parallel, each into a rule of its own, joined in row order.
  std::vector<QuadratureRule<2>> rows(static_cast<std::size_t>(ny));
  parallel_blocks(ny, 1, [&](Index begin, Index end) {
    for (Index cj = begin; cj < end; ++cj) {
      QuadratureRule<2>& row = rows[static_cast<std::size_t>(cj)];
      for (int ci = 0; ci < nx; ++ci) {
        const Vec2 lo(box.lo.x() + ci * hx, box.lo.y() + static_cast<double>(cj) * hy);
        add_cell_points(domain, Box{lo, lo + Vec2(hx, hy)}, n, row);
      }
    }
  });
  QuadratureRule<2> rule;
  for (const QuadratureRule<2>& row : rows) {
    rule.points.insert(rule.points.end(), row.points.begin(), row.points.end());
    rule.weights.insert(rule.weights.end(), row.weights.begin(), row.weights.end());
  }
  // A point on a crack integrates both faces.
  return split_rule_on_cracks(domain, std::move(rule), std::min(hx, hy));
}

QuadratureRule<3> gauss_cell_rule(const Solid& solid, double cell_size, int n) {
  if (!(cell_size > 0.0))
    throw InputError(fmt::format("Gauss cells: cell size must be positive, got {}", cell_size));
  const AlignedBox<3>& box = solid.bounding_box();
  const GaussLegendre1D g = gauss_legendre(n);
  std::array<int, 3> cells;
  Point<3> size;
  for (int a = 0; a < 3; ++a) {
    cells[a] = std::max(1, static_cast<int>(std::lround(box.sizes()[a] / cell_size)));
    size[a] = box.sizes()[a] / cells[a];
  }
  QuadratureRule<3> rule;
  if (const TetrahedralMesh* mesh = solid.mesh()) {
    // The tetrahedra clipped to the cells, each piece with the collapsed rule.
    std::vector<Tetrahedron> pieces;
    for (Index t = 0; t < mesh->size(); ++t) {
      const Tetrahedron tet = mesh->tetrahedron(t);
      AlignedBox<3> bounds(tet[0]);
      for (const Point<3>& v : tet) bounds.extend(v);
      std::array<int, 3> from, to;
      for (int a = 0; a < 3; ++a) {
        const auto cell = [&](double x) {
          return std::clamp(static_cast<int>(std::floor((x - box.min()[a]) / size[a])), 0, cells[a] - 1);
        };
        from[a] = cell(bounds.min()[a]);
        to[a] = cell(bounds.max()[a]);
      }
      for (int k = from[2]; k <= to[2]; ++k)
        for (int j = from[1]; j <= to[1]; ++j)
          for (int i = from[0]; i <= to[0]; ++i) {
            const Point<3> lo = box.min() + size.cwiseProduct(Point<3>(i, j, k));
            pieces.clear();
            clip_to_box(tet, AlignedBox<3>(lo, Point<3>(lo + size)), pieces);
            for (const Tetrahedron& piece : pieces) add_tetrahedron_rule(piece, g, rule);
          }
    }
    return rule;
  }
  const double weight = size.prod();
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) {
        const Point<3> lo = box.min() + size.cwiseProduct(Point<3>(i, j, k));
        for (std::size_t c = 0; c < g.points.size(); ++c)
          for (std::size_t b = 0; b < g.points.size(); ++b)
            for (std::size_t a = 0; a < g.points.size(); ++a) {
              rule.points.push_back(lo + size.cwiseProduct(Point<3>(g.points[a], g.points[b], g.points[c])));
              rule.weights.push_back(weight * g.weights[a] * g.weights[b] * g.weights[c]);
            }
      }
  return rule;
}

}  // namespace mfree

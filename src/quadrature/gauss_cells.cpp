#include "mfree/quadrature/gauss_cells.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/quadrature/polygon_quadrature.hpp"

namespace mfree {

namespace {

/// Points on the part of `cell` in the domain (in `region` when >= 0): a polygon rule of
/// degree 2 n on the clipped cell; a clipped piece with a hole is cut into four first.
void add_cut_cell(const Domain& domain, const Box& cell, int region, int n, int depth, QuadratureRule& rule,
                  const std::vector<Ring>* clipped = nullptr) {
  const std::vector<Ring> rings = clipped ? *clipped : domain.clip(cell, region);
  if (rings.empty() || add_polygon_rule(rings, n + 1, cell.size().maxCoeff(), rule)) return;
  if (depth == 8)
    throw Error(fmt::format("Gauss cells: the cell [{}, {}] x [{}, {}] cannot be cut into simple pieces",
                            cell.lo.x(), cell.hi.x(), cell.lo.y(), cell.hi.y()));
  const Vec2 mid = 0.5 * (cell.lo + cell.hi);
  for (const Box& quarter : {Box{cell.lo, mid}, Box{Vec2(mid.x(), cell.lo.y()), Vec2(cell.hi.x(), mid.y())},
                             Box{Vec2(cell.lo.x(), mid.y()), Vec2(mid.x(), cell.hi.y())}, Box{mid, cell.hi}})
    add_cut_cell(domain, quarter, region, n, depth + 1, rule);
}

/// Whether the rings are the box itself (one ring of its four corners).
bool is_box(const std::vector<Ring>& rings, const Box& box) {
  if (rings.size() != 1 || rings[0].size() != 4) return false;
  return std::all_of(rings[0].begin(), rings[0].end(), [&](const Vec2& x) {
    return (x.x() == box.lo.x() || x.x() == box.hi.x()) && (x.y() == box.lo.y() || x.y() == box.hi.y());
  });
}

}  // namespace

QuadratureRule gauss_cell_rule(const Domain& domain, double cell_size, int n) {
  if (!(cell_size > 0.0))
    throw InputError(fmt::format("Gauss cells: cell size must be positive, got {}", cell_size));
  const GaussLegendre1D g = gauss_legendre(n);
  const Box box = domain.bounding_box();
  const int nx = std::max(1, static_cast<int>(std::lround(box.size().x() / cell_size)));
  const int ny = std::max(1, static_cast<int>(std::lround(box.size().y() / cell_size)));
  const double hx = box.size().x() / nx, hy = box.size().y() / ny;
  const int regions = static_cast<int>(domain.regions().size());
  // Rows of cells in parallel, each into a rule of its own, joined in row order.
  std::vector<QuadratureRule> rows(static_cast<std::size_t>(ny));
  parallel_blocks(ny, 1, [&](Index begin, Index end) {
    for (Index cj = begin; cj < end; ++cj) {
      QuadratureRule& row = rows[static_cast<std::size_t>(cj)];
      for (int ci = 0; ci < nx; ++ci) {
        const Vec2 lo(box.lo.x() + ci * hx, box.lo.y() + static_cast<double>(cj) * hy);
        const Box cell{lo, lo + Vec2(hx, hy)};
        if (!domain.boundary_near(cell)) {
          if (!domain.contains(0.5 * (cell.lo + cell.hi))) continue;
        } else if (regions > 0) {  // each region's part: the law and the functions jump between them
          for (int r = 0; r < regions; ++r) add_cut_cell(domain, cell, r, n, 0, row);
          continue;
        } else if (const std::vector<Ring> inside = domain.clip(cell); !is_box(inside, cell)) {  // cut by the boundary
          add_cut_cell(domain, cell, -1, n, 0, row, &inside);
          continue;
        }
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            row.points.emplace_back(lo.x() + g.points[i] * hx, lo.y() + g.points[j] * hy);
            row.weights.push_back(g.weights[i] * g.weights[j] * hx * hy);
          }
      }
    }
  });
  QuadratureRule rule;
  for (const QuadratureRule& row : rows) {
    rule.points.insert(rule.points.end(), row.points.begin(), row.points.end());
    rule.weights.insert(rule.weights.end(), row.weights.begin(), row.weights.end());
  }
  if (domain.cracks().empty()) return rule;
  // A point on a crack integrates both faces: two copies with half its weight each.
  std::vector<Index> origin;
  std::vector<Vec2> points = split_on_cracks(domain, rule.points, std::min(hx, hy), &origin);
  std::vector<double> weights(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const bool split =
        (p > 0 && origin[p - 1] == origin[p]) || (p + 1 < points.size() && origin[p + 1] == origin[p]);
    weights[p] = rule.weights[origin[p]] * (split ? 0.5 : 1.0);
  }
  return QuadratureRule{std::move(points), std::move(weights)};
}

}  // namespace mfree

#include "mfree/quadrature/gauss_cells.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/geometry/crack_faces.hpp"

namespace mfree {

QuadratureRule gauss_cell_rule(const Domain& domain, double cell_size, int n) {
  if (!(cell_size > 0.0))
    throw InputError(fmt::format("Gauss cells: cell size must be positive, got {}", cell_size));
  const GaussLegendre1D g = gauss_legendre(n);
  const Box box = domain.bounding_box();
  const int nx = std::max(1, static_cast<int>(std::lround(box.size().x() / cell_size)));
  const int ny = std::max(1, static_cast<int>(std::lround(box.size().y() / cell_size)));
  const double hx = box.size().x() / nx, hy = box.size().y() / ny;
  QuadratureRule rule;
  for (int cj = 0; cj < ny; ++cj)
    for (int ci = 0; ci < nx; ++ci)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Vec2 x(box.lo.x() + (ci + g.points[i]) * hx, box.lo.y() + (cj + g.points[j]) * hy);
          if (!domain.contains(x)) continue;
          rule.points.push_back(x);
          rule.weights.push_back(g.weights[i] * g.weights[j] * hx * hy);
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

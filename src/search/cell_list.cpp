#include "mfree/search/cell_list.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

template <int dim>
CellList<dim>::CellList(std::span<const Point> points, double cell_size) : cell_size_(cell_size) {
  if (!(cell_size > 0.0) || !std::isfinite(cell_size))
    throw Error(fmt::format("cell list: cell size must be positive and finite, got {}", cell_size));
  if (points.empty()) return;
  Point lo = points[0], hi = points[0];
  for (const Point& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  origin_ = lo;
  // Cap the grid at ~4 cells per point so that a tiny cell size cannot exhaust memory.
  const double cap = 4.0 * static_cast<double>(points.size()) + 16.0;
  const auto cells_at = [&](double size) {
    double cells = 1.0;
    for (int c = 0; c < dim; ++c) cells *= std::floor((hi[c] - lo[c]) / size) + 1.0;
    return cells;
  };
  if (cells_at(cell_size) > cap) {
    // The side that leaves cap / 4 cells over the box's (non-degenerate) extent.
    double extent = 1.0;
    int spanned = 0;
    for (int c = 0; c < dim; ++c)
      if (hi[c] > lo[c]) {
        extent *= hi[c] - lo[c];
        ++spanned;
      }
    const double per_cell = extent / (cap / 4.0);
    const double side = spanned == 3 ? std::cbrt(per_cell) : (spanned == 2 ? std::sqrt(per_cell) : per_cell);
    cell_size_ = std::max(side + 1e-300, cell_size);
  }
  std::size_t cells = 1;
  for (int c = 0; c < dim; ++c) {
    n_[c] = static_cast<int>(std::floor((hi[c] - lo[c]) / cell_size_)) + 1;
    cells *= static_cast<std::size_t>(n_[c]);
  }

  const Index n = static_cast<Index>(points.size());
  std::vector<Index> cell_of(n);
  start_.assign(cells + 1, 0);
  for (Index i = 0; i < n; ++i) {
    Index cell = 0;
    for (int c = dim - 1; c >= 0; --c) cell = cell * n_[c] + clamp_cell(points[i][c], c);
    cell_of[i] = cell;
    ++start_[cell + 1];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  order_.resize(n);
  sorted_.resize(n);
  std::vector<Index> fill(start_.begin(), start_.end() - 1);
  for (Index i = 0; i < n; ++i) {  // stable: indices stay increasing within a cell
    const Index slot = fill[cell_of[i]]++;
    order_[slot] = i;
    sorted_[slot] = points[i];
  }
}

template <int dim>
void CellList<dim>::within(const Point& x, double r, std::vector<Index>& out) const {
  out.clear();
  const double r2 = r * r;
  for_each_in_box(x, r, [&](Index i, const Point& p) {
    if ((p - x).squaredNorm() < r2) out.push_back(i);
  });
}

template class CellList<2>;
template class CellList<3>;

}  // namespace mfree

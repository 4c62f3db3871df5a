#include "mfree/search/cell_list.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

CellList::CellList(std::span<const Vec2> points, double cell_size) : cell_size_(cell_size) {
  if (!(cell_size > 0.0) || !std::isfinite(cell_size))
    throw Error(fmt::format("cell list: cell size must be positive and finite, got {}", cell_size));
  if (points.empty()) return;
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  origin_ = lo;
  // Cap the grid at ~4 cells per point so that a tiny cell size cannot exhaust memory.
  const double cap = 4.0 * static_cast<double>(points.size()) + 16.0;
  const double cells = std::floor((hi.x() - lo.x()) / cell_size) + 1.0;
  const double rows = std::floor((hi.y() - lo.y()) / cell_size) + 1.0;
  if (cells * rows > cap) {
    cell_size_ = std::sqrt((hi - lo).prod() / (cap / 4.0)) + 1e-300;
    cell_size_ = std::max(cell_size_, cell_size);
  }
  nx_ = static_cast<int>(std::floor((hi.x() - lo.x()) / cell_size_)) + 1;
  ny_ = static_cast<int>(std::floor((hi.y() - lo.y()) / cell_size_)) + 1;

  const Index n = static_cast<Index>(points.size());
  std::vector<Index> cell_of(n);
  start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (Index i = 0; i < n; ++i) {
    const Vec2& p = points[i];
    cell_of[i] = static_cast<Index>(clamp_y(p.y())) * nx_ + clamp_x(p.x());
    ++start_[cell_of[i] + 1];
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

void CellList::within(const Vec2& x, double r, std::vector<Index>& out) const {
  out.clear();
  const double r2 = r * r;
  for_each_in_box(x, r, [&](Index i, const Vec2& p) {
    if ((p - x).squaredNorm() < r2) out.push_back(i);
  });
}

}  // namespace mfree

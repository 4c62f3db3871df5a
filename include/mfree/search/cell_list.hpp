#pragma once
// Neighbour search by a uniform cell list (bucket grid).
//
// Points are sorted into square cells of a given size (usually the largest search
// radius), stored cell by cell (CSR) with a copy of their coordinates in that order,
// so a query touches a few contiguous runs of memory. Building is O(n); a query
// within radius r <= cell size visits the 3 x 3 cells around the query point.
// Measured against CGAL's kd-tree in verification/benchmarks (bench_search.cpp).

#include <span>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

class CellList {
 public:
  CellList() = default;
  /// Sorts `points` into cells of side `cell_size` > 0 covering their bounding box.
  CellList(std::span<const Vec2> points, double cell_size);

  [[nodiscard]] Index size() const { return static_cast<Index>(order_.size()); }
  [[nodiscard]] double cell_size() const { return cell_size_; }

  /// Calls f(index, position) for every point with |x_I - x|_inf <= r (a square window),
  /// in a fixed order (cell by cell). Callers filter further for circular supports.
  template <class F>
  void for_each_in_box(const Vec2& x, double r, F&& f) const {
    if (order_.empty()) return;
    const int i0 = clamp_x(x.x() - r), i1 = clamp_x(x.x() + r);
    const int j0 = clamp_y(x.y() - r), j1 = clamp_y(x.y() + r);
    for (int j = j0; j <= j1; ++j) {
      const Index row = static_cast<Index>(j) * nx_;
      for (Index c = start_[row + i0]; c < start_[row + i1 + 1]; ++c) {
        const Vec2& p = sorted_[c];
        if (std::abs(p.x() - x.x()) <= r && std::abs(p.y() - x.y()) <= r) f(order_[c], p);
      }
    }
  }

  /// Indices of the points with |x_I - x| < r, appended to `out` (cleared first).
  void within(const Vec2& x, double r, std::vector<Index>& out) const;

 private:
  int clamp_x(double x) const { return clamp_cell((x - origin_.x()) / cell_size_, nx_); }
  int clamp_y(double y) const { return clamp_cell((y - origin_.y()) / cell_size_, ny_); }
  static int clamp_cell(double t, int n) {
    if (!(t >= 0.0)) return 0;
    return t >= n - 1 ? n - 1 : static_cast<int>(t);
  }

  double cell_size_ = 1.0;
  Vec2 origin_ = Vec2::Zero();
  int nx_ = 0, ny_ = 0;
  std::vector<Index> start_;  ///< (nx * ny + 1) offsets into order_ / sorted_
  std::vector<Index> order_;  ///< point indices, cell by cell
  std::vector<Vec2> sorted_;  ///< point coordinates in that order
};

}  // namespace mfree

#pragma once
// Neighbour search by a uniform cell list (bucket grid), in dim = 2 or 3 dimensions.
//
// Points are sorted into square (cubic) cells of a given size (usually the largest search
// radius), stored cell by cell (CSR, x fastest) with a copy of their coordinates in that
// order, so a query touches a few contiguous runs of memory. Building is O(n); a query
// within radius r <= cell size visits the 3^dim cells around the query point.
// Measured against CGAL's kd-tree in verification/benchmarks (bench_search.cpp).

#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

template <int dim>
class CellList {
 public:
  using Point = mfree::Point<dim>;

  CellList() = default;
  /// Sorts `points` into cells of side `cell_size` > 0 covering their bounding box.
  CellList(std::span<const Point> points, double cell_size);

  [[nodiscard]] Index size() const { return static_cast<Index>(order_.size()); }
  [[nodiscard]] double cell_size() const { return cell_size_; }

  /// Calls f(index, position) for every point with |x_I - x|_inf <= r (a square or cubic
  /// window), in a fixed order (cell by cell). Callers filter further for round supports.
  template <class F>
  void for_each_in_box(const Point& x, double r, F&& f) const {
    if (order_.empty()) return;
    std::array<int, dim> lo, hi;
    for (int c = 0; c < dim; ++c) {
      lo[c] = clamp_cell(x[c] - r, c);
      hi[c] = clamp_cell(x[c] + r, c);
    }
    // The runs of cells along x, one per (y, z) cell of the window.
    const int layers = dim == 3 ? hi[dim - 1] - lo[dim - 1] + 1 : 1;
    for (int l = 0; l < layers; ++l)
      for (int j = lo[1]; j <= hi[1]; ++j) {
        const Index row = (dim == 3 ? static_cast<Index>(lo[dim - 1] + l) * n_[1] : Index{0}) * n_[0] +
                          static_cast<Index>(j) * n_[0];
        for (Index s = start_[row + lo[0]]; s < start_[row + hi[0] + 1]; ++s) {
          const Point& p = sorted_[s];
          if (((p - x).cwiseAbs().array() <= r).all()) f(order_[s], p);
        }
      }
  }

  /// Indices of the points with |x_I - x| < r, appended to `out` (cleared first).
  void within(const Point& x, double r, std::vector<Index>& out) const;

 private:
  [[nodiscard]] int clamp_cell(double coordinate, int axis) const {
    const double t = (coordinate - origin_[axis]) / cell_size_;
    if (!(t >= 0.0)) return 0;
    return t >= n_[axis] - 1 ? n_[axis] - 1 : static_cast<int>(t);
  }

  double cell_size_ = 1.0;
  Point origin_ = Point::Zero();
  std::array<int, dim> n_{};  ///< cells per axis
  std::vector<Index> start_;  ///< (cells + 1) offsets into order_ / sorted_
  std::vector<Index> order_;  ///< point indices, cell by cell
  std::vector<Point> sorted_;  ///< point coordinates in that order
};

extern template class CellList<2>;
extern template class CellList<3>;

}  // namespace mfree

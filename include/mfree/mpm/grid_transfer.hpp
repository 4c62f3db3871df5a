#pragma once
// Transfers between points (particles, or the Gauss points of the MLS reconstruction) and
// grid nodes through a table of weights: for point q, stride entries (node, S, G).
//
// The table holds them in one of two layouts, both read through for_each(q, f), which calls
// f(node, S, G) for every entry of point q:
//
//   tensor (axis = n > 0): the point's functions are the n x n products N_{fx+a}(x) N_{fy+b}(y)
//     of two axes (hats, the GIMPs' averaged hats, B-splines). The slot holds node (fx, fy) and
//     each axis' n values and n derivatives; reading forms S = N_a N_b and
//     G = (N'_a N_b, N_a N'_b) (seed 000 eqs. 4-5), the entries bit for bit, from 4n numbers
//     instead of 3n^2. Every transfer of a step streams the table, so its size is their cost.
//   explicit (axis = 0): stride entries (node, S, G) (the CPDIs, whose element nodes share
//     grid nodes).
//
// Tensor entries come in the order b (y) outer, a (x) inner.
//
// scatter() sums point contributions into grid nodes: each thread adds its contiguous range
// of points into a grid of its own, and the thread grids are summed in thread order, so the
// result is race-free and, for a fixed thread count, reproducible bit for bit. The thread
// grids live in a ScatterBuffers the caller keeps, so a run allocates them once. Gathers need
// no such care (each point reads the grid).

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include "mfree/core/parallel.hpp"
#include "mfree/core/types.hpp"

namespace mfree {

/// An explicit slot to write: stride consecutive entries.
struct WeightSlot {
  Index* node;
  double* S;
  Vec2* G;
};

struct WeightTable {
  int stride = 0;  ///< entries per point (axis^2 in the tensor layout)
  int axis = 0;    ///< tensor layout: functions per axis; 0: explicit entries
  Index nx = 0;    ///< tensor layout: grid nodes per row (node (i, j) = i + nx j)
  std::vector<Index> node;    ///< explicit: per entry; tensor: node (fx, fy) per point
  std::vector<double> S;      ///< explicit: per entry
  std::vector<Vec2> G;        ///< explicit: per entry
  std::vector<double> axes;   ///< tensor: per point N_x, N'_x, N_y, N'_y (axis numbers each)

  [[nodiscard]] Index points() const {
    if (axis > 0) return static_cast<Index>(node.size());
    return stride == 0 ? 0 : static_cast<Index>(node.size() / stride);
  }
  void resize(Index points, int new_stride, int new_axis, Index new_nx) {
    stride = new_stride;
    axis = new_axis;
    nx = new_nx;
    const auto n = static_cast<std::size_t>(points);
    if (axis > 0) {
      node.resize(n);
      axes.resize(n * 4 * axis);
    } else {
      node.resize(n * stride);
      S.resize(n * stride);
      G.resize(n * stride);
    }
  }
  /// Explicit layout: point q's entries.
  WeightSlot slot(Index q) {
    const std::size_t o = static_cast<std::size_t>(q) * stride;
    return {node.data() + o, S.data() + o, G.data() + o};
  }
  /// Tensor layout with n == axis: point q's node (fx, fy) and its axes, each with
  /// value[k] = N_{f+k} and derivative[k] = N'_{f+k}, k < n (a constant, so that the copies
  /// are moves, not calls).
  template <int n, class Axis>
  void set_tensor(Index q, Index first, const Axis& x, const Axis& y) {
    node[q] = first;
    double* a = axes.data() + static_cast<std::size_t>(q) * 4 * n;
    std::copy_n(x.value.begin(), n, a);
    std::copy_n(x.derivative.begin(), n, a + n);
    std::copy_n(y.value.begin(), n, a + 2 * n);
    std::copy_n(y.derivative.begin(), n, a + 3 * n);
  }

  /// f(node, S, G) for every entry of point q.
  template <class F>
  void for_each(Index q, F&& f) const {
    switch (axis) {
      case 0: {
        // Pointers and count in locals: Eigen's vector stores (in f) may alias anything, so
        // whatever is read through the table's members would be loaded again after each.
        const std::size_t o = static_cast<std::size_t>(q) * stride;
        const Index* n = node.data() + o;
        const double* s = S.data() + o;
        const Vec2* g = G.data() + o;
        const int m = stride;
        for (int k = 0; k < m; ++k) f(n[k], s[k], g[k]);
        return;
      }
      case 2: return for_each_tensor<2>(q, f);
      case 3: return for_each_tensor<3>(q, f);
      case 4:
        return for_each_tensor<4>(q, f);
      default:
        return for_each_tensor<5>(q, f);
    }
  }

 private:
  template <int n, class F>
  void for_each_tensor(Index q, F& f) const {
    // Copied into locals first, as in for_each().
    const double* a = axes.data() + static_cast<std::size_t>(q) * 4 * n;
    std::array<double, n> vx, dx, vy, dy;
    std::copy_n(a, n, vx.begin());
    std::copy_n(a + n, n, dx.begin());
    std::copy_n(a + 2 * n, n, vy.begin());
    std::copy_n(a + 3 * n, n, dy.begin());
    const Index first = node[q], row = nx;
    for (int b = 0; b < n; ++b)
      for (int k = 0; k < n; ++k) f(first + k + row * b, vx[k] * vy[b], Vec2(dx[k] * vy[b], vx[k] * dy[b]));
  }
};

template <class T>
T zero_of() {
  if constexpr (std::is_arithmetic_v<T>) return T(0);
  else return T::Zero();
}

/// The per-thread grids of scatter(), kept between calls.
template <class T>
using ScatterBuffers = std::vector<std::vector<T>>;

/// grid[i] = sum over points q and their entries k with node(q, k) = i of c_q(S, G), where
/// c_q = point(q) is asked for once per point (the place for work per point, done by the
/// thread that scatters it) and T is any Eigen fixed-size vector (or double).
template <class T, class Point>
void scatter(const WeightTable& w, Index grid_size, std::vector<T>& grid, ScatterBuffers<T>& partial, Point&& point) {
  partial.resize(static_cast<std::size_t>(thread_count()));
  parallel_ranges(w.points(), [&](int t, Index begin, Index end) {
    partial[t].assign(static_cast<std::size_t>(grid_size), zero_of<T>());
    T* g = partial[t].data();
    for (Index q = begin; q < end; ++q) {
      const auto contribution = point(q);
      w.for_each(q, [&](Index i, double S, const Vec2& G) { g[i] += contribution(S, G); });
    }
  });
  grid.resize(static_cast<std::size_t>(grid_size));
  parallel_ranges(grid_size, [&](int, Index begin, Index end) {
    for (Index i = begin; i < end; ++i) {
      T sum = zero_of<T>();
      for (const std::vector<T>& g : partial) sum += g[i];
      grid[i] = sum;
    }
  });
}

}  // namespace mfree

#pragma once
// Transfers between points (particles, or the Gauss points of the MLS reconstruction) and
// grid nodes through a table of weights: for point q, stride() entries (node, S, G).
//
// scatter() sums point contributions into grid nodes: each thread adds its contiguous range
// of points into a grid of its own, and the thread grids are summed in thread order, so the
// result is race-free and, for a fixed thread count, reproducible bit for bit. Gathers need
// no such care (each point reads the grid).

#include <type_traits>
#include <vector>

#include "mfree/core/parallel.hpp"
#include "mfree/core/types.hpp"
#include "mfree/mpm/particle_basis.hpp"

namespace mfree {

struct WeightTable {
  int stride = 0;
  std::vector<Index> node;
  std::vector<double> S;
  std::vector<Vec2> G;

  [[nodiscard]] Index points() const { return stride == 0 ? 0 : static_cast<Index>(S.size() / stride); }
  void resize(Index points, int new_stride) {
    stride = new_stride;
    const std::size_t n = static_cast<std::size_t>(points) * stride;
    node.resize(n);
    S.resize(n);
    G.resize(n);
  }
  WeightSlot slot(Index q) {
    const std::size_t o = static_cast<std::size_t>(q) * stride;
    return {node.data() + o, S.data() + o, G.data() + o};
  }
};

template <class T>
T zero_of() {
  if constexpr (std::is_arithmetic_v<T>) return T(0);
  else return T::Zero();
}

/// grid[i] = sum over points q and their entries k with node(q, k) = i of
/// contribution(q, k, S, G), T any Eigen fixed-size vector (or double).
template <class T, class Contribution>
void scatter(const WeightTable& w, Index grid_size, std::vector<T>& grid, Contribution&& contribution) {
  const int threads = thread_count();
  std::vector<std::vector<T>> partial(static_cast<std::size_t>(threads));
  parallel_ranges(w.points(), [&](int t, Index begin, Index end) {
    std::vector<T>& g = partial[t];
    g.assign(static_cast<std::size_t>(grid_size), zero_of<T>());
    for (Index q = begin; q < end; ++q) {
      const std::size_t o = static_cast<std::size_t>(q) * w.stride;
      for (int k = 0; k < w.stride; ++k) g[w.node[o + k]] += contribution(q, w.S[o + k], w.G[o + k]);
    }
  });
  grid.resize(static_cast<std::size_t>(grid_size));
  parallel_blocks(grid_size, 4096, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) {
      T sum = zero_of<T>();
      for (int t = 0; t < threads; ++t)
        if (!partial[t].empty()) sum += partial[t][i];
      grid[i] = sum;
    }
  });
}

}  // namespace mfree

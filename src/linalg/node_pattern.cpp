#include "mfree/linalg/node_pattern.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <limits>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"

namespace mfree {

RowIncidence::RowIncidence(std::span<const Index> offsets, std::span<const Index> nodes, Index node_count)
    : offsets_(offsets), nodes_(nodes), node_offsets_(node_count + 1, 0) {
  if (offsets.empty() || offsets.back() != static_cast<Index>(nodes.size()))
    throw Error(fmt::format("row offsets end at {}, the rows hold {} nodes", offsets.empty() ? -1 : offsets.back(),
                            nodes.size()));
  // Counting sort of the slots by node: rows come out increasing for every node.
  for (Index i : nodes) {
    if (i < 0 || i >= node_count) throw Error(fmt::format("row node {} outside [0, {})", i, node_count));
    ++node_offsets_[i + 1];
  }
  for (Index i = 0; i < node_count; ++i) node_offsets_[i + 1] += node_offsets_[i];
  row_of_.resize(nodes.size());
  slot_of_.resize(nodes.size());
  std::vector<Index> next(node_offsets_.begin(), node_offsets_.end() - 1);
  for (Index k = 0; k < rows(); ++k)
    for (Index s = offsets[k]; s < offsets[k + 1]; ++s) {
      const Index at = next[nodes[s]]++;
      row_of_[at] = k;
      slot_of_[at] = s;
    }
}

std::int64_t NodePattern::position(Index i, Index j) const {
  const std::span<const Index> p = neighbours(j);
  return std::lower_bound(p.begin(), p.end(), i) - p.begin();
}

NodePattern node_pattern(std::span<const RowIncidence* const> sets) {
  NodePattern pattern;
  if (sets.empty()) throw Error("node pattern: no row sets");
  const Index n = sets.front()->node_count();
  for (const RowIncidence* set : sets)
    if (set->node_count() != n) throw Error("node pattern: row sets on different node counts");

  // Each thread takes a contiguous range of nodes and lists their neighbours in its own
  // arrays; marker[I] = J flags I as already listed for node J. The ranges are then
  // concatenated in order.
  struct Part {
    std::vector<std::int64_t> sizes;
    std::vector<Index> nodes;
  };
  std::vector<Part> parts(thread_count());
  std::vector<Index> first(thread_count(), n);
  parallel_ranges(n, [&](int t, Index begin, Index end) {
    Part& part = parts[t];
    first[t] = begin;
    std::vector<Index> marker(n, -1);
    for (Index j = begin; j < end; ++j) {
      const std::size_t start = part.nodes.size();
      for (const RowIncidence* set : sets)
        for (Index k : set->rows_of(j))
          for (Index i : set->row(k))
            if (marker[i] != j) {
              marker[i] = j;
              part.nodes.push_back(i);
            }
      std::sort(part.nodes.begin() + static_cast<std::ptrdiff_t>(start), part.nodes.end());
      part.sizes.push_back(static_cast<std::int64_t>(part.nodes.size() - start));
    }
  });
  pattern.offsets.assign(n + 1, 0);
  std::size_t total = 0;
  for (std::size_t t = 0; t < parts.size(); ++t) {
    for (std::size_t a = 0; a < parts[t].sizes.size(); ++a) {
      const Index j = first[t] + static_cast<Index>(a);
      pattern.offsets[j + 1] = pattern.offsets[j] + parts[t].sizes[a];
    }
    total += parts[t].nodes.size();
  }
  pattern.nodes.resize(total);
  parallel_ranges(n, [&](int t, Index, Index) {
    if (!parts[t].sizes.empty())
      std::copy(parts[t].nodes.begin(), parts[t].nodes.end(), pattern.nodes.begin() + pattern.offsets[first[t]]);
  });
  return pattern;
}

SparseMatrix block_matrix(const NodePattern& pattern, int b) {
  const Index n = pattern.size();
  const std::int64_t nnz = std::int64_t{b} * b * static_cast<std::int64_t>(pattern.nodes.size());
  if (nnz > std::numeric_limits<int>::max() || std::int64_t{b} * n > std::numeric_limits<int>::max())
    throw Error(fmt::format("block matrix of {} x {} unknowns with {} entries: over the 2^31 - 1 of Eigen's indices",
                            std::int64_t{b} * n, std::int64_t{b} * n, nnz));
  SparseMatrix m(b * n, b * n);
  m.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = m.outerIndexPtr();
  int* inner = m.innerIndexPtr();
  double* values = m.valuePtr();
  outer[b * n] = static_cast<int>(nnz);
  parallel_blocks(n, 4096, [&](Index begin, Index end) {
    for (Index j = begin; j < end; ++j) {
      const std::span<const Index> p = pattern.neighbours(j);
      const std::int64_t size = static_cast<std::int64_t>(p.size());
      for (int c = 0; c < b; ++c) {
        const std::int64_t start = b * b * pattern.offsets[j] + c * b * size;
        outer[b * j + c] = static_cast<int>(start);
        for (std::int64_t a = 0; a < size; ++a)
          for (int r = 0; r < b; ++r) {
            inner[start + b * a + r] = b * p[a] + r;
            values[start + b * a + r] = 0.0;
          }
      }
    }
  });
  return m;
}

}  // namespace mfree

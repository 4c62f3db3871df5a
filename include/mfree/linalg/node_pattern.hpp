#pragma once
// Sparsity of the matrices of node-based Galerkin methods, built once from the quadrature.
//
// A quadrature point couples every pair of nodes of its row (the nodes whose functions are
// nonzero there, GalerkinQuadrature<2>): block (I, J) of a matrix is nonzero only if some row
// holds both I and J. So
//
//   RowIncidence  rows of node indices (CSR, nodes sorted within a row) and their transpose:
//                 for every node, the rows holding it and where it sits in each;
//   NodePattern   the node-to-node graph of one or more row sets: for every node J the
//                 sorted union of the rows holding J;
//   block_matrix  a matrix with b unknowns per node (unknown b I + r) laid out on that
//                 pattern in Eigen's compressed column storage, values zero, so assembly
//                 adds into it in place: no triplets, no sparse products, no temporaries.
//
// Column b J + c of the block matrix holds rows b I + r for I in J's pattern, in order:
// entry (b I + r, b J + c) is value b^2 start(J) + c b |P_J| + b p + r of the value array,
// p the position of I in P_J (block_slot()).

#include <cstdint>
#include <span>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/linalg/linear_solver.hpp"

namespace mfree {

class RowIncidence {
 public:
  /// Row k is nodes[offsets[k]], ..., nodes[offsets[k + 1] - 1], node indices in
  /// [0, node_count). The arrays are viewed, not copied: they must outlive this object.
  RowIncidence(std::span<const Index> offsets, std::span<const Index> nodes, Index node_count);

  [[nodiscard]] Index rows() const { return static_cast<Index>(offsets_.size()) - 1; }
  [[nodiscard]] Index node_count() const { return static_cast<Index>(node_offsets_.size()) - 1; }
  [[nodiscard]] std::span<const Index> row(Index k) const {
    return nodes_.subspan(offsets_[k], offsets_[k + 1] - offsets_[k]);
  }
  /// The rows holding node i, increasing.
  [[nodiscard]] std::span<const Index> rows_of(Index i) const {
    return {row_of_.data() + node_offsets_[i], static_cast<std::size_t>(node_offsets_[i + 1] - node_offsets_[i])};
  }
  /// Where node i sits in each of rows_of(i): indices into the nodes array.
  [[nodiscard]] std::span<const Index> slots_of(Index i) const {
    return {slot_of_.data() + node_offsets_[i], static_cast<std::size_t>(node_offsets_[i + 1] - node_offsets_[i])};
  }

 private:
  std::span<const Index> offsets_;
  std::span<const Index> nodes_;
  std::vector<Index> node_offsets_;
  std::vector<Index> row_of_;
  std::vector<Index> slot_of_;
};

struct NodePattern {
  std::vector<std::int64_t> offsets;  ///< P_J is nodes[offsets[J]], ..., nodes[offsets[J + 1] - 1]
  std::vector<Index> nodes;           ///< sorted within each P_J; J itself included

  [[nodiscard]] Index size() const { return static_cast<Index>(offsets.size()) - 1; }
  [[nodiscard]] std::span<const Index> neighbours(Index j) const {
    return {nodes.data() + offsets[j], static_cast<std::size_t>(offsets[j + 1] - offsets[j])};
  }
  /// Position p of node i in P_J, P_J[p] = i (bisection); i must be in P_J.
  [[nodiscard]] std::int64_t position(Index i, Index j) const;
};

/// The node-to-node graph of the union of the row sets (all on the same nodes): I and J are
/// coupled if a row of any set holds both.
NodePattern node_pattern(std::span<const RowIncidence* const> sets);

/// The (b N) x (b N) matrix with b x b blocks on the pattern, values zero, compressed.
/// Throws Error when its entries overflow Eigen's 32-bit indices.
SparseMatrix block_matrix(const NodePattern& pattern, int b);

/// Index into the value array of block_matrix(pattern, b) of entry (b I + r, b J + c).
[[nodiscard]] inline std::int64_t block_slot(const NodePattern& pattern, int b, Index i, Index j, int r, int c) {
  const std::int64_t start = pattern.offsets[j], size = pattern.offsets[j + 1] - start;
  return b * b * start + c * b * size + b * pattern.position(i, j) + r;
}

}  // namespace mfree

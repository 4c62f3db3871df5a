#pragma once
// Sparse direct solvers: CHOLMOD (supernodal Cholesky, for symmetric positive definite
// systems) and UMFPACK (LU, for non-symmetric ones), through Eigen's SuiteSparse modules.
//
// analyze() does the symbolic work (fill-reducing ordering, elimination tree) for a
// sparsity pattern; factorize() the numeric work and may be called again and again for
// matrices of that same pattern (Newton iterations, load and time steps) without
// repeating the analysis. SuiteSparse headers stay in sparse_solver.cpp.

#include <Eigen/SparseCore>
#include <memory>
#include <string_view>

#include "mfree/core/name_table.hpp"

namespace mfree {

using SparseMatrix = Eigen::SparseMatrix<double>;  ///< compressed columns, int indices

enum class SolverKind {
  cholmod,  ///< symmetric positive definite (only the lower triangle is read)
  umfpack,  ///< general square
};

/// cholmod, umfpack: the names scenes use.
const NameTable<SolverKind>& solver_kind_names();
std::string_view to_string(SolverKind kind);

class SparseSolver {
 public:
  explicit SparseSolver(SolverKind kind);
  SparseSolver(SparseSolver&&) noexcept;
  SparseSolver& operator=(SparseSolver&&) noexcept;
  ~SparseSolver();

  [[nodiscard]] SolverKind kind() const { return kind_; }
  [[nodiscard]] bool analyzed() const;
  [[nodiscard]] bool factorized() const;
  /// Symbolic analysis of a's pattern (a compressed square matrix). UMFPACK also reads the
  /// values to choose its strategy (a zero diagonal makes it pick the unsymmetric one, with
  /// orderings several times costlier here): analyse a matrix holding real values.
  void analyze(const SparseMatrix& a);
  /// Numeric factorisation; analyze() first. Throws NumericalError when the matrix is not
  /// positive definite (CHOLMOD) or is singular (UMFPACK).
  void factorize(const SparseMatrix& a);
  /// x with a x = b for the last factorised matrix.
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  struct Impl;
  SolverKind kind_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mfree

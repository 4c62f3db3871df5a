#pragma once
// Sparse direct solvers: CHOLMOD (supernodal Cholesky, for symmetric positive definite
// systems) and UMFPACK (LU, for non-symmetric ones), through Eigen's SuiteSparse modules.
//
// analyze() does the symbolic work (fill-reducing ordering, elimination tree) for a
// sparsity pattern; factorize() the numeric work and may be called again and again for
// matrices of that same pattern (Newton iterations, load and time steps) without
// repeating the analysis. SuiteSparse headers stay in sparse_solver.cpp.

#include <memory>

#include "mfree/linalg/linear_solver.hpp"

namespace mfree {

class SparseSolver final : public LinearSolver {
 public:
  /// kind: cholmod or umfpack.
  explicit SparseSolver(SolverKind kind);
  ~SparseSolver() override;

  [[nodiscard]] SolverKind kind() const override { return kind_; }
  [[nodiscard]] std::string description() const override;
  /// CHOLMOD reads only the lower triangle. UMFPACK also reads the values to choose its
  /// strategy (a zero diagonal makes it pick the unsymmetric one, with orderings several
  /// times costlier here): analyse a matrix holding real values.
  void analyze(const SparseMatrix& a) override;
  void factorize(const SparseMatrix& a) override;
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& b) override;

 private:
  struct Impl;
  SolverKind kind_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mfree

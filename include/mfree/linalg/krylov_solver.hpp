#pragma once
// Preconditioned Krylov solvers on PETSc (linear_solver.hpp says which and when).
//
// The matrix is copied once per analyze() into a PETSc AIJ matrix of block size
// system.block_size (row-compressed: rows of a non-symmetric matrix are gathered from
// Eigen's columns through a permutation built then), and factorize() refreshes its values in
// place and rebuilds the preconditioner. GAMG gets the near-null space of the system: the
// rigid-body modes of the nodes (2 unknowns per node) or {1, x, y} (one). PETSc (and MPI,
// as a single process) is started on first use and finalised at exit; its headers stay in
// krylov_solver.cpp. PETSC_OPTIONS in the environment reaches the solvers (-ksp_monitor,
// -ksp_view, ...), after the settings of the scene.
//
// On a distributed run the same objects would hold a block of rows per process: nodes
// partitioned (ParMETIS on the node pattern), each process owning the rows of its nodes and
// assembling from its quadrature rows, with MatSetValues adding entries owned elsewhere;
// see include/mfree/linalg/README.md.

#include <memory>

#include "mfree/linalg/linear_solver.hpp"

namespace mfree {

class KrylovSolver final : public LinearSolver {
 public:
  /// kind: cg or gmres. `system.nodes` must outlive the solver.
  KrylovSolver(SolverKind kind, const SolverSettings& settings, const SystemDescription& system);
  ~KrylovSolver() override;

  [[nodiscard]] SolverKind kind() const override { return kind_; }
  [[nodiscard]] std::string description() const override;
  void analyze(const SparseMatrix& a) override;
  void factorize(const SparseMatrix& a) override;
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& b) override;

 private:
  struct Impl;
  SolverKind kind_;
  SolverSettings settings_;
  SystemDescription system_;
  Preconditioner preconditioner_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mfree

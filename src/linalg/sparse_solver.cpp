#include "mfree/linalg/sparse_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

const NameTable<SolverKind>& solver_kind_names() {
  static const NameTable<SolverKind> table{{"cholmod", SolverKind::cholmod}, {"umfpack", SolverKind::umfpack}};
  return table;
}

std::string_view to_string(SolverKind kind) { return solver_kind_names().name(kind); }

struct SparseSolver::Impl {
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> cholmod;
  Eigen::UmfPackLU<SparseMatrix> umfpack;
  bool analyzed = false, factorized = false;
  Eigen::Index size = 0;
};

SparseSolver::SparseSolver(SolverKind kind) : kind_(kind), impl_(std::make_unique<Impl>()) {
  // Failures reach the user as NumericalError with advice; CHOLMOD's own stderr lines
  // would only repeat them.
  impl_->cholmod.cholmod().print = 0;
  // No iterative refinement in UMFPACK's solves: it triples their cost, and the callers
  // that solve many times (Newton, Newmark) correct the solution by their own iterations.
  impl_->umfpack.umfpackControl()(UMFPACK_IRSTEP) = 0;
}
SparseSolver::SparseSolver(SparseSolver&&) noexcept = default;
SparseSolver& SparseSolver::operator=(SparseSolver&&) noexcept = default;
SparseSolver::~SparseSolver() = default;

bool SparseSolver::analyzed() const { return impl_->analyzed; }
bool SparseSolver::factorized() const { return impl_->factorized; }

void SparseSolver::analyze(const SparseMatrix& a) {
  if (a.rows() != a.cols())
    throw Error(fmt::format("sparse solver: matrix is {} x {}, not square", a.rows(), a.cols()));
  if (kind_ == SolverKind::cholmod) impl_->cholmod.analyzePattern(a);
  else impl_->umfpack.analyzePattern(a);
  impl_->analyzed = true;
  impl_->factorized = false;
  impl_->size = a.rows();
}

void SparseSolver::factorize(const SparseMatrix& a) {
  if (!impl_->analyzed || a.rows() != impl_->size)
    throw Error("sparse solver: factorize() needs analyze() of a matrix of the same pattern first");
  Eigen::ComputationInfo info;
  if (kind_ == SolverKind::cholmod) {
    impl_->cholmod.factorize(a);
    info = impl_->cholmod.info();
  } else {
    impl_->umfpack.factorize(a);
    info = impl_->umfpack.info();
  }
  if (info != Eigen::Success)
    throw NumericalError(fmt::format(
        "sparse solver ({}): the {} x {} matrix could not be factorised: {}", to_string(kind_),
        a.rows(), a.cols(),
        kind_ == SolverKind::cholmod
            ? "it is not positive definite (missing boundary conditions, a Nitsche penalty "
              "too small, or too few quadrature points)"
            : "it is singular (missing boundary conditions or too few quadrature points)"));
  impl_->factorized = true;
}

Eigen::VectorXd SparseSolver::solve(const Eigen::VectorXd& b) const {
  if (!impl_->factorized) throw Error("sparse solver: solve() before factorize()");
  Eigen::VectorXd x = kind_ == SolverKind::cholmod ? Eigen::VectorXd(impl_->cholmod.solve(b))
                                                   : Eigen::VectorXd(impl_->umfpack.solve(b));
  if (!x.allFinite()) throw NumericalError("sparse solver: the solution is not finite");
  return x;
}

}  // namespace mfree

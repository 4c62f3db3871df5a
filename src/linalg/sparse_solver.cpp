#include "mfree/linalg/sparse_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <fmt/format.h>
#include <stdexcept>

#include "mfree/core/error.hpp"

namespace mfree {

struct SparseSolver::Impl {
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> cholmod;
  Eigen::UmfPackLU<SparseMatrix> umfpack;
  Eigen::Index size = 0;
};

SparseSolver::SparseSolver(SolverKind kind) : kind_(kind), impl_(std::make_unique<Impl>()) {
  if (!is_direct(kind)) throw std::logic_error("SparseSolver: not a direct method");
  // Failures reach the user as NumericalError with advice; CHOLMOD's own stderr lines
  // would only repeat them.
  impl_->cholmod.cholmod().print = 0;
  // No iterative refinement in UMFPACK's solves: it triples their cost, and the callers
  // that solve many times (Newton, Newmark) correct the solution by their own iterations.
  impl_->umfpack.umfpackControl()(UMFPACK_IRSTEP) = 0;
}
SparseSolver::~SparseSolver() = default;

std::string SparseSolver::description() const { return std::string(to_string(kind_)); }

void SparseSolver::analyze(const SparseMatrix& a) {
  if (a.rows() != a.cols())
    throw Error(fmt::format("sparse solver: matrix is {} x {}, not square", a.rows(), a.cols()));
  if (kind_ == SolverKind::cholmod) impl_->cholmod.analyzePattern(a);
  else impl_->umfpack.analyzePattern(a);
  analyzed_ = true;
  factorized_ = false;
  impl_->size = a.rows();
}

void SparseSolver::factorize(const SparseMatrix& a) {
  if (!analyzed_ || a.rows() != impl_->size)
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
  factorized_ = true;
}

Eigen::VectorXd SparseSolver::solve(const Eigen::VectorXd& b) {
  if (!factorized_) throw Error("sparse solver: solve() before factorize()");
  Eigen::VectorXd x = kind_ == SolverKind::cholmod ? Eigen::VectorXd(impl_->cholmod.solve(b))
                                                   : Eigen::VectorXd(impl_->umfpack.solve(b));
  if (!x.allFinite()) throw NumericalError("sparse solver: the solution is not finite");
  ++statistics_.solves;
  return x;
}

}  // namespace mfree

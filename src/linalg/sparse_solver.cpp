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
  const auto failed = [&](std::string_view why) {
    return NumericalError(fmt::format("sparse solver ({}): the {} x {} matrix could not be factorised: {}",
                                      to_string(kind_), a.rows(), a.cols(), why));
  };
  if (kind_ == SolverKind::cholmod) {
    impl_->cholmod.factorize(a);
    if (impl_->cholmod.info() != Eigen::Success)
      throw failed("it is not positive definite (missing boundary conditions, a Nitsche penalty too small, or too "
                   "few quadrature points)");
  } else {
    impl_->umfpack.factorize(a);
    // Eigen counts UMFPACK's warnings as failures; those of the determinant's estimate
    // (it over- or underflows from about 10^5 unknowns of a stiffness in SI units) are not.
    switch (const int code = impl_->umfpack.umfpackFactorizeReturncode()) {
      case UMFPACK_OK:
      case UMFPACK_WARNING_determinant_underflow:
      case UMFPACK_WARNING_determinant_overflow:
        break;
      case UMFPACK_WARNING_singular_matrix:
        throw failed("it is singular (missing boundary conditions or too few quadrature points)");
      case UMFPACK_ERROR_out_of_memory:
        throw failed("UMFPACK ran out of memory (its LU factors outgrow memory or its 32-bit indices; use a "
                     "Krylov solver: [solver] kind = \"gmres\" or \"auto\")");
      default:
        throw failed(fmt::format("UMFPACK status {}", code));
    }
  }
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

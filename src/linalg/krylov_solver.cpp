#include "mfree/linalg/krylov_solver.hpp"

#include <fmt/format.h>
#include <petscksp.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "mfree/core/error.hpp"
#include "mfree/linalg/rigid_body_modes.hpp"

namespace mfree {

namespace {

/// Throws NumericalError with PETSc's own message when a PETSc call failed; InputError when
/// it failed on a name no PETSc type has, which only PETSC_OPTIONS can give (a numerical
/// error would make Newton cut its load step back, in vain).
void check(PetscErrorCode code, const char* call) {
  if (!code) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  if (code == PETSC_ERR_ARG_UNKNOWN_TYPE)
    throw InputError(fmt::format("PETSc: {} failed: {} (a type named in PETSC_OPTIONS?)", call,
                                 text ? text : "unknown type"));
  throw NumericalError(fmt::format("PETSc: {} failed: {}", call, text ? text : "unknown error"));
}

/// PETSc (and MPI, as one process) from the first Krylov solver to the program's exit.
/// PETSc's signal handler stays off, so that crashes reach mfree's and the sanitizers' own
/// reports; its errors are returned, not printed, and become exceptions (check()).
void start_petsc() {
  static const bool started = [] {
    PetscBool initialised = PETSC_FALSE;
    check(PetscInitialized(&initialised), "PetscInitialized");
    if (!initialised) {
      check(PetscOptionsSetValue(nullptr, "-no_signal_handler", "true"), "PetscOptionsSetValue");
      check(PetscInitializeNoArguments(), "PetscInitialize");
      std::atexit([] { PetscFinalize(); });
    }
    check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
    return true;
  }();
  (void)started;
}

/// Orthonormalises the columns of v (modified Gram-Schmidt).
void orthonormalise(std::vector<Eigen::VectorXd>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) v[i] -= v[j].dot(v[i]) * v[j];
    v[i].normalize();
  }
}

/// Entries of PETSc's options database for the span of one object: each (key, value) that
/// PETSC_OPTIONS does not give is entered, and taken out again at the end, so that no other
/// solver reads it and the user's own options always win.
class ScopedOptionDefaults {
 public:
  ScopedOptionDefaults(const std::string& prefix,
                       const std::vector<std::pair<std::string, std::string>>& entries) {
    for (const auto& [key, value] : entries) {
      const std::string name = "-" + prefix + key;
      PetscBool given = PETSC_FALSE;
      check(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &given), "PetscOptionsHasName");
      if (given) continue;
      check(PetscOptionsSetValue(nullptr, name.c_str(), value.c_str()), "PetscOptionsSetValue");
      entered_.push_back(name);
    }
  }
  ~ScopedOptionDefaults() {
    for (const std::string& name : entered_) PetscOptionsClearValue(nullptr, name.c_str());
  }
  ScopedOptionDefaults(const ScopedOptionDefaults&) = delete;
  ScopedOptionDefaults& operator=(const ScopedOptionDefaults&) = delete;

 private:
  std::vector<std::string> entered_;
};

}  // namespace

struct KrylovSolver::Impl {
  Mat a = nullptr;
  KSP ksp = nullptr;
  PetscInt size = 0;
  std::size_t nonzeros = 0;
  /// Non-symmetric matrices: value k of the row-compressed PETSc matrix is value gather[k] of
  /// Eigen's column-compressed one. Empty for symmetric ones (the two layouts coincide).
  /// The values go straight into PETSc's array: no copy of the matrix is kept here.
  std::vector<PetscInt> gather;
  std::string overridden;  ///< "KSP + PC" when PETSC_OPTIONS changed the scene's method
  std::string prefix;      ///< of the KSP's options: the system's name, "tangent_stiffness_"
  /// Options PCGAMG reads when it makes its levels' smoothers (factorize()), unless given.
  std::vector<std::pair<std::string, std::string>> smoother_defaults;

  ~Impl() {
    KSPDestroy(&ksp);
    MatDestroy(&a);
  }

  /// The values of `m` into the PETSc matrix, in its row-compressed order.
  void set_values(const SparseMatrix& m) {
    PetscScalar* a_values = nullptr;
    check(MatSeqAIJGetArray(a, &a_values), "MatSeqAIJGetArray");
    const double* v = m.valuePtr();
    if (gather.empty()) std::copy(v, v + m.nonZeros(), a_values);
    else
      for (std::size_t k = 0; k < gather.size(); ++k) a_values[k] = v[gather[k]];
    check(MatSeqAIJRestoreArray(a, &a_values), "MatSeqAIJRestoreArray");
  }
};

KrylovSolver::KrylovSolver(SolverKind kind, const SolverSettings& settings, const SystemDescription& system)
    : kind_(kind),
      settings_(settings),
      system_(system),
      preconditioner_(settings.preconditioner.value_or(system.symmetric || system.nearly_symmetric ? Preconditioner::gamg
                                                                                                 : Preconditioner::boomeramg)),
      impl_(std::make_unique<Impl>()) {
  if (is_direct(kind)) throw std::logic_error("KrylovSolver: not a Krylov method");
  start_petsc();
}

KrylovSolver::~KrylovSolver() = default;

std::string KrylovSolver::description() const {
  const std::string method = impl_->overridden.empty()
                                 ? fmt::format("{} + {}", to_string(kind_), to_string(preconditioner_))
                                 : impl_->overridden + " (PETSC_OPTIONS)";
  return fmt::format("{} (tolerance {:.0e})", method, settings_.tolerance);
}

void KrylovSolver::analyze(const SparseMatrix& m) {
  if (m.rows() != m.cols())
    throw Error(fmt::format("{}: the {} matrix is {} x {}, not square", description(), system_.name, m.rows(), m.cols()));
  if (!m.isCompressed()) throw std::logic_error("KrylovSolver: the matrix is not compressed");
  const int bs = system_.block_size;
  if (bs < 1 || m.rows() % bs)
    throw std::logic_error(fmt::format("KrylovSolver: {} rows are not blocks of {}", m.rows(), bs));
  Impl& p = *impl_;
  KSPDestroy(&p.ksp);
  MatDestroy(&p.a);
  p.size = static_cast<PetscInt>(m.rows());
  const PetscInt n = p.size;

  if (m.nonZeros() >= std::numeric_limits<PetscInt>::max())
    throw Error(fmt::format("{}: the {} matrix has {} nonzeros, more than PETSc's {}-bit indices hold", description(),
                            system_.name, m.nonZeros(), 8 * sizeof(PetscInt)));
  p.nonzeros = static_cast<std::size_t>(m.nonZeros());

  // Row-compressed structure (PETSc copies it): a symmetric matrix's columns are its rows.
  std::vector<PetscInt> row_start(n + 1, 0), columns(p.nonzeros, 0);
  p.gather.clear();
  if (system_.symmetric) {
    std::copy(m.outerIndexPtr(), m.outerIndexPtr() + n + 1, row_start.begin());
    std::copy(m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros(), columns.begin());
  } else {
    p.gather.assign(p.nonzeros, 0);
    for (std::int64_t k = 0; k < m.nonZeros(); ++k) ++row_start[m.innerIndexPtr()[k] + 1];
    for (PetscInt i = 0; i < n; ++i) row_start[i + 1] += row_start[i];
    std::vector<PetscInt> next(row_start.begin(), row_start.end() - 1);
    for (PetscInt j = 0; j < n; ++j)
      for (std::int64_t k = m.outerIndexPtr()[j]; k < m.outerIndexPtr()[j + 1]; ++k) {
        const PetscInt slot = next[m.innerIndexPtr()[k]]++;
        columns[slot] = j;
        p.gather[slot] = static_cast<PetscInt>(k);
      }
  }

  check(MatCreate(PETSC_COMM_SELF, &p.a), "MatCreate");
  check(MatSetSizes(p.a, n, n, n, n), "MatSetSizes");
  check(MatSetType(p.a, MATSEQAIJ), "MatSetType");
  check(MatSetBlockSize(p.a, bs), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocationCSR(p.a, row_start.data(), columns.data(), nullptr),
        "MatSeqAIJSetPreallocationCSR");
  p.set_values(m);
  if (system_.symmetric) {
    check(MatSetOption(p.a, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
    check(MatSetOption(p.a, MAT_SPD, PETSC_TRUE), "MatSetOption");
  }

  // The near-null space of AMG: the rigid-body modes of the nodes.
  const Eigen::MatrixXd r = std::visit(
      [&](auto nodes) -> Eigen::MatrixXd {
        constexpr int dim = decltype(nodes)::value_type::RowsAtCompileTime;
        if (nodes.empty() || (bs != 1 && bs != dim)) return {};
        if (static_cast<Index>(nodes.size()) * bs != n)
          throw std::logic_error(
              fmt::format("KrylovSolver: {} nodes for {} unknowns of block size {}", nodes.size(), n, bs));
        return rigid_body_modes<dim>(nodes, bs, Point<dim>::Zero());
      },
      system_.nodes);
  if (r.cols() > 0) {
    std::vector<Eigen::VectorXd> modes;
    for (Eigen::Index j = 0; j < r.cols(); ++j) modes.emplace_back(r.col(j));
    orthonormalise(modes);
    std::vector<Vec> vecs(modes.size());
    for (std::size_t k = 0; k < modes.size(); ++k) {
      check(VecCreateSeq(PETSC_COMM_SELF, n, &vecs[k]), "VecCreateSeq");
      PetscScalar* v = nullptr;
      check(VecGetArray(vecs[k], &v), "VecGetArray");
      std::memcpy(v, modes[k].data(), sizeof(double) * n);
      check(VecRestoreArray(vecs[k], &v), "VecRestoreArray");
    }
    MatNullSpace space = nullptr;
    check(MatNullSpaceCreate(PETSC_COMM_SELF, PETSC_FALSE, static_cast<PetscInt>(vecs.size()), vecs.data(),
                             &space),
          "MatNullSpaceCreate");
    check(MatSetNearNullSpace(p.a, space), "MatSetNearNullSpace");
    MatNullSpaceDestroy(&space);
    for (Vec& v : vecs) VecDestroy(&v);
  }

  check(KSPCreate(PETSC_COMM_SELF, &p.ksp), "KSPCreate");
  // PETSC_OPTIONS reach one kind of system by its name: -stiffness_ksp_monitor,
  // -consistency_node_pc_gamg_threshold 0.05, ...
  p.prefix.clear();
  for (char c : system_.name) p.prefix += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  p.prefix += '_';
  check(KSPSetOptionsPrefix(p.ksp, p.prefix.c_str()), "KSPSetOptionsPrefix");
  check(KSPSetOperators(p.ksp, p.a, p.a), "KSPSetOperators");
  if (kind_ == SolverKind::cg) {
    check(KSPSetType(p.ksp, KSPCG), "KSPSetType");
    check(KSPSetNormType(p.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  } else {
    check(KSPSetType(p.ksp, KSPGMRES), "KSPSetType");
    check(KSPSetPCSide(p.ksp, PC_RIGHT), "KSPSetPCSide");
    check(KSPGMRESSetRestart(p.ksp, 60), "KSPGMRESSetRestart");
    // Classical Gram-Schmidt, refined where it loses orthogonality: without the refinement
    // the true residual of a small VCI stiffness (96 unknowns, BoomerAMG) stalled at 5e-10
    // and GMRES broke down short of a 1e-13 tolerance; with it, it gets there.
    check(KSPGMRESSetCGSRefinementType(p.ksp, KSP_GMRES_CGS_REFINE_IFNEEDED), "KSPGMRESSetCGSRefinementType");
  }
  check(KSPSetTolerances(p.ksp, settings_.tolerance, 0.0, PETSC_DEFAULT, settings_.max_iterations), "KSPSetTolerances");
  PC pc = nullptr;
  check(KSPGetPC(p.ksp, &pc), "KSPGetPC");
  switch (preconditioner_) {
    case Preconditioner::gamg:
      check(PCSetType(pc, PCGAMG), "PCSetType");
      // Newton and time steps change the values, not the graph: the aggregates and
      // prolongators of the first setup serve them all (the Galerkin coarse operators are
      // recomputed).
      check(PCGAMGSetReuseInterpolation(pc, PETSC_TRUE), "PCGAMGSetReuseInterpolation");
      // The smoothers estimate their own eigenvalue bounds at every setup: the estimate of the
      // prolongator's smoothing (the default) belongs to the first matrix only, and with
      // reused interpolation would make a later, stiffer matrix's Chebyshev smoother diverge
      // (a test shifts the diagonal by 0.5/4 to catch it).
      check(PCGAMGSetUseSAEstEig(pc, PETSC_FALSE), "PCGAMGSetUseSAEstEig");
      {
        // Connections weaker than 3 % of the diagonal do not bind nodes into one aggregate.
        // The wide RK stencils (a node couples with about 110 others) otherwise give
        // aggregates that a smoother cannot serve: on the 10^5-DOF cantilever the node system
        // of the consistency correction took 213 CG iterations per solve without dropping,
        // 65 at 1 %, 52 at 2 %, 44 at 3 %; the stiffness 42, 41, 38, 38.
        PetscReal threshold[] = {0.03};
        check(PCGAMGSetThreshold(pc, threshold, 1), "PCGAMGSetThreshold");
      }
      // A coarsest level of up to 5000 equations, solved directly: the node system of the
      // consistency correction (a fourth-order operator) keeps its smooth error there. CG
      // iterations per node-system solve at 10^5 DOFs: 44 with PETSc's default of 50, 30
      // with 1000, 21 with 5000; the stiffness's stayed at 38.
      check(PCGAMGSetCoarseEqLim(pc, 5000), "PCGAMGSetCoarseEqLim");
      // In space a node couples with about 410 others (1237 nonzeros a row of the Lamé
      // sphere's stiffness), smoothing the prolongators makes the coarse operators nearly
      // dense, and Jacobi-Chebyshev smoothing stalls: GMRES on that stiffness (12 051
      // unknowns, one thread) took 220 iterations, 4.5 s set-up + 15 s. Plain aggregation and
      // two SOR-Chebyshev sweeps a level: 40 iterations, 1.6 s + 5.2 s (four sweeps: 26
      // iterations, 1.7 s + 6.7 s; SOR with smoothed aggregation: 31, 4.9 s + 6.3 s).
      p.smoother_defaults.clear();
      if (std::holds_alternative<std::span<const Point<3>>>(system_.nodes)) {
        check(PCGAMGSetNSmooths(pc, 0), "PCGAMGSetNSmooths");
        p.smoother_defaults = {{"mg_levels_pc_type", "sor"}, {"mg_levels_ksp_max_it", "2"}};
      }
      break;
    case Preconditioner::boomeramg:
      check(PCSetType(pc, PCHYPRE), "PCSetType");
      check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
      break;
    case Preconditioner::jacobi:
      check(PCSetType(pc, PCJACOBI), "PCSetType");
      break;
  }
  check(KSPSetFromOptions(p.ksp), "KSPSetFromOptions");
  // What runs, after PETSC_OPTIONS: the description names it when the options changed it.
  KSPType ksp_type = nullptr;
  PCType pc_type = nullptr;
  check(KSPGetType(p.ksp, &ksp_type), "KSPGetType");
  check(PCGetType(pc, &pc_type), "PCGetType");
  const std::string chosen = fmt::format("{} + {}", to_string(kind_), to_string(preconditioner_));
  std::string running = fmt::format("{} + {}", ksp_type, pc_type);
  if (running == fmt::format("{} + hypre", to_string(kind_)) && preconditioner_ == Preconditioner::boomeramg)
    running = chosen;
  p.overridden = running == chosen ? "" : running;
  analyzed_ = true;
  factorized_ = false;
}

void KrylovSolver::factorize(const SparseMatrix& m) {
  Impl& p = *impl_;
  if (!analyzed_ || m.rows() != p.size || static_cast<std::size_t>(m.nonZeros()) != p.nonzeros)
    throw Error(fmt::format("{}: factorize() needs analyze() of a matrix of the same pattern first", description()));
  p.set_values(m);
  check(KSPSetOperators(p.ksp, p.a, p.a), "KSPSetOperators");
  const ScopedOptionDefaults smoothers(p.prefix, p.smoother_defaults);
  check(KSPSetUp(p.ksp), "KSPSetUp (the preconditioner's setup)");
  factorized_ = true;
}

Eigen::VectorXd KrylovSolver::solve(const Eigen::VectorXd& b) {
  Impl& p = *impl_;
  if (!factorized_) throw Error(fmt::format("{}: solve() before factorize()", description()));
  if (b.size() != p.size)
    throw Error(fmt::format("{}: a right-hand side of {} entries for {} unknowns", description(), b.size(), p.size));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.size);
  const double bn = b.norm();
  ++statistics_.solves;
  if (bn == 0.0) return x;
  if (!std::isfinite(bn))
    throw NumericalError(fmt::format("{}: the right-hand side of the {} system is not finite", description(), system_.name));
  Vec vb = nullptr, vx = nullptr;
  check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, p.size, b.data(), &vb), "VecCreateSeqWithArray");
  check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, p.size, x.data(), &vx), "VecCreateSeqWithArray");
  const PetscErrorCode solved = KSPSolve(p.ksp, vb, vx);
  VecDestroy(&vb);
  VecDestroy(&vx);
  check(solved, "KSPSolve");
  KSPConvergedReason reason;
  PetscInt iterations = 0;
  PetscReal residual = 0.0;
  check(KSPGetConvergedReason(p.ksp, &reason), "KSPGetConvergedReason");
  check(KSPGetIterationNumber(p.ksp, &iterations), "KSPGetIterationNumber");
  check(KSPGetResidualNorm(p.ksp, &residual), "KSPGetResidualNorm");
  const double relative = residual / bn;
  statistics_.iterations += iterations;
  statistics_.most_iterations = std::max(statistics_.most_iterations, static_cast<int>(iterations));
  statistics_.worst_residual = std::max(statistics_.worst_residual, relative);
  if (reason < 0)
    throw NumericalError(fmt::format(
        "{} on the {} system ({} unknowns): no convergence after {} iterations, |b - A x| / |b| = {:.3e} ({}){}",
        description(), system_.name, p.size, iterations, relative, KSPConvergedReasons[reason],
        reason == KSP_DIVERGED_INDEFINITE_MAT || reason == KSP_DIVERGED_INDEFINITE_PC
            ? ": the matrix is not positive definite (missing boundary conditions, a Nitsche penalty too small, "
              "or too few quadrature points)"
            : "; raise [solver] max_iterations or use a direct solver"));
  if (!x.allFinite()) throw NumericalError(fmt::format("{}: the solution of the {} system is not finite", description(), system_.name));
  return x;
}

}  // namespace mfree

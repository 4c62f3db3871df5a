#pragma once
// Every linear solve of mfree goes through one interface, made by one factory from the
// scene's [solver] table:
//
//   cholmod    supernodal Cholesky (SuiteSparse), symmetric positive definite systems
//   umfpack    sparse LU (SuiteSparse), any non-singular system
//   cg         conjugate gradients (PETSc), symmetric positive definite systems
//   gmres      restarted GMRES (PETSc, right-preconditioned), any system
//
// The Krylov methods take a preconditioner: gamg (PETSc's smoothed-aggregation algebraic
// multigrid, given the rigid-body modes of the nodes as its near-null space), boomeramg
// (hypre's classical algebraic multigrid), or jacobi. By default gamg for symmetric systems
// and for nearly symmetric ones (SystemDescription::nearly_symmetric), boomeramg for the
// others: GAMG's Chebyshev smoothers assume a symmetric positive definite matrix. A linear-RK
// VCI stiffness is a small skew correction of one, and GMRES + GAMG solves it in 20
// iterations at every size on the cantilever lattice (10^6 DOFs: 47.5 s end to end against
// 133 s with BoomerAMG, whose setup dominates); quadratic VCI's correction is not small, and
// GMRES + GAMG there took 2000 iterations to 1e-8 where BoomerAMG converges. Their tolerance is on the true
// residual, |b - A x| <= tolerance |b|, for both methods (CG on the unpreconditioned norm,
// GMRES preconditioned on the right); a solve that does not reach it within max_iterations
// is a NumericalError naming the method, the system, the iterations and the residual.
//
// `auto` picks a direct method up to direct_limit unknowns (CHOLMOD for symmetric systems,
// UMFPACK otherwise) and a Krylov method above it (CG, GMRES): a factorisation's fill grows
// faster than the matrix, an AMG cycle does not. On the cantilever (2 threads; PETSc runs on
// one) CHOLMOD is ahead at 10^5 DOFs and CG + GAMG at 5 * 10^5, in time and memory
// (verification/benchmarks/README.md): the default limit in the plane, 2 * 10^5, is where they
// cross. In space a node couples with about 410 others (the projected gradients of linear RK
// reach about 4.6 h; 1237 nonzeros a row against 110 or so in the plane), and the fill of a
// factorisation grows much faster: on the Lamé sphere (one thread) UMFPACK took 26 s and 2.8 GB
// at 12 051 unknowns where GMRES + GAMG took 6.8 s and 1.1 GB; the default limit in space is
// 3000 unknowns for the systems GAMG serves (default_direct_limit), 20 000 for a matrix that
// serves many solves or a mass: Newmark's effective tangent K + 4 M / dt^2 on the vibrating
// cube at 14 739 unknowns took 15 s a GMRES + GAMG solve (80 iterations) where one UMFPACK
// factorisation (19 s) serves the steps until modified Newton refactorises (0.2 s a solve).
//
// The life of a solver follows Newton's: analyze() once per sparsity pattern (orderings,
// symbolic factorisation; for Krylov methods the matrix structure), factorize() whenever
// the values change (numeric factorisation; for Krylov methods the preconditioner's setup),
// solve() for every right-hand side. Matrices are Eigen's compressed columns holding every
// entry (both triangles, also for symmetric systems).

#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"

namespace mfree {

using SparseMatrix = Eigen::SparseMatrix<double>;  ///< compressed columns, int indices

enum class SolverKind { cholmod, umfpack, cg, gmres };
/// cholmod, umfpack, cg, gmres: the names scenes use.
const NameTable<SolverKind>& solver_kind_names();
std::string_view to_string(SolverKind kind);
[[nodiscard]] constexpr bool is_direct(SolverKind k) { return k == SolverKind::cholmod || k == SolverKind::umfpack; }

enum class Preconditioner { gamg, boomeramg, jacobi };
/// gamg, boomeramg, jacobi: the names scenes use.
const NameTable<Preconditioner>& preconditioner_names();
std::string_view to_string(Preconditioner p);

/// A scene's [solver] table.
struct SolverSettings {
  std::optional<SolverKind> kind;         ///< nullopt: auto
  std::optional<Preconditioner> preconditioner;  ///< nullopt: gamg if (nearly) symmetric, else boomeramg
  double tolerance = 1e-10;               ///< |b - A x| / |b| of the Krylov methods
  int max_iterations = 2000;              ///< per Krylov solve
  std::optional<Index>
      direct_limit;  ///< auto: direct up to this many unknowns (nullopt: default_direct_limit)
};

/// What a solve knows of its system beyond the matrix.
struct SystemDescription {
  std::string name;                       ///< "stiffness", "mass", ...: for messages and summaries
  bool symmetric = true;                  ///< symmetric positive definite
  /// Unknowns per node (dim: displacements, unknown dim I + c; 1: a scalar field), and the
  /// node coordinates, plane or space, whose rigid-body modes (rigid_body_modes.hpp: dim
  /// translations and 1 or 3 rotations; 1, x, y (, z) for a scalar) AMG takes as its
  /// near-null space. Empty: constants only.
  int block_size = 1;
  std::variant<std::span<const Point<2>>, std::span<const Point<3>>> nodes;
  /// A non-symmetric matrix that is a small skew correction of a symmetric positive definite
  /// one (the stiffness with linear-order VCI test gradients): GAMG is its default.
  bool nearly_symmetric = false;
  /// A system a factorisation serves well, so that `auto` stays direct longer in space
  /// (default_direct_limit): one matrix for many right-hand sides (Newmark's effective
  /// tangent, kept by modified Newton over the steps), or a consistent mass (on the vibrating
  /// cube at 14 739 unknowns the projection of the initial velocity took 5.5 s with CHOLMOD,
  /// 9.1 s with CG + Jacobi, 17.5 s with CG + GAMG).
  bool favours_direct = false;
};

/// What the solves of one solver did, for run summaries.
struct SolveStatistics {
  int solves = 0;
  long iterations = 0;                    ///< Krylov iterations, all solves together
  int most_iterations = 0;                ///< of one solve
  double worst_residual = 0.0;            ///< largest |b - A x| / |b| of one solve (Krylov)
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;

  [[nodiscard]] virtual SolverKind kind() const = 0;
  /// "cholmod", "cg + gamg (tolerance 1e-10)", ...
  [[nodiscard]] virtual std::string description() const = 0;
  [[nodiscard]] bool analyzed() const { return analyzed_; }
  [[nodiscard]] bool factorized() const { return factorized_; }
  [[nodiscard]] const SolveStatistics& statistics() const { return statistics_; }

  /// Symbolic work for a's pattern (a compressed square matrix with real values).
  virtual void analyze(const SparseMatrix& a) = 0;
  /// Numeric work for a, of the analysed pattern. Throws NumericalError when a direct
  /// method finds the matrix singular or (CHOLMOD) not positive definite.
  virtual void factorize(const SparseMatrix& a) = 0;
  /// x with A x = b for the last factorised matrix. Throws NumericalError when a Krylov
  /// method does not converge, or the solution is not finite.
  [[nodiscard]] virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) = 0;

 protected:
  bool analyzed_ = false, factorized_ = false;
  SolveStatistics statistics_;
};

/// auto's limit unless [solver] gives one: 2 * 10^5 unknowns in the plane; in space 3000 for a
/// symmetric or nearly symmetric system (above), 20 000 for one that favours direct (above) and for
/// another, where neither multigrid does well: quadratic VCI's stiffness of the Lamé sphere (3414 unknowns, 2
/// threads) took UMFPACK 1.2 s, GMRES + GAMG 137 iterations and 7.3 s, GMRES + BoomerAMG 261 and about 50 s.
[[nodiscard]] Index default_direct_limit(const SystemDescription& system);

/// The method `settings` choose for a system of `size` unknowns: its kind, or by the auto
/// rule. Throws InputError when CHOLMOD or CG is asked for a non-symmetric system.
[[nodiscard]] SolverKind choose_solver(const SolverSettings& settings, const SystemDescription& system, Index size);

/// The solver of choose_solver(settings, system, size). `system.nodes` is viewed, not
/// copied: it must outlive the solver.
[[nodiscard]] std::unique_ptr<LinearSolver> make_linear_solver(const SolverSettings& settings,
                                                               const SystemDescription& system, Index size);

/// What one solver was and did, kept by results after the solver is gone.
struct SolverReport {
  SolverKind kind = SolverKind::cholmod;
  std::string method;                     ///< LinearSolver::description()
  SolveStatistics statistics;
  /// One line for run summaries: "cholmod, 1 solves" or "cg + gamg (tolerance 1e-10), 1
  /// solves, 38 iterations (at most 38 in one), |b - A x| / |b| <= 9.5e-11".
  [[nodiscard]] std::string text() const;
};
[[nodiscard]] SolverReport report(const LinearSolver& solver);

}  // namespace mfree

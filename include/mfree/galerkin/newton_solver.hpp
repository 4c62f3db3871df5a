#pragma once
// Newton–Raphson for the nonlinear systems of the total-Lagrangian solver, and the static
// solve by load stepping built on it.
//
//   newton()        R(d) = 0 from a start d: K(d) delta = -R(d), d += alpha delta, with a
//                   line search on the energy slope delta . R(d + alpha delta) (secant steps
//                   until it is below 0.8 of its value at alpha = 0; a trial state with J <= 0
//                   halves alpha). Converged when |R| <= max(tolerance |R_0|,
//                   absolute_tolerance) (R_0: the residual at the start), or when |R| has
//                   stagnated at round-off (below 1e-8 |R_0| and not halved by the last
//                   iteration; NewtonOutcome::stagnated). The tangent's
//                   pattern is analysed once (the first tangent); each iteration factorises
//                   numerically.
//   solve_static()  load factors 0 < lambda_1 < ... < 1 scale every load and prescribed
//                   displacement (LoadState::factor). Without an absolute_tolerance it
//                   takes tolerance |R(0)| at the full load, one scale for every step. A step whose Newton fails (no
//                   convergence, no decrease, J <= 0) is cut back: the increment is halved
//                   from the last converged state, up to max_cutbacks times in a row, then
//                   the solve gives up with a NumericalError saying where and why.
//                   A law with history is committed after every converged step (and only
//                   then: a failed attempt leaves the history of the last converged step).
//
// Observed order of convergence (seed 004): p_k = log(r_{k+1} / r_k) / log(r_k / r_{k-1}),
// 2 for Newton with an exact tangent near the solution. The log prints it per iteration.

#include <functional>
#include <iosfwd>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "mfree/core/stage_timer.hpp"
#include "mfree/galerkin/total_lagrangian.hpp"
#include "mfree/linalg/linear_solver.hpp"

namespace mfree {

struct NewtonSettings {
  double tolerance = 1e-10;            ///< on |R| / |R_0|
  double absolute_tolerance = 0.0;     ///< on |R| (force units); 0: solve_static chooses (above)
  int max_iterations = 25;
  bool line_search = true;
  int max_line_search_steps = 8;       ///< line search: trials after the full step
  /// Modified Newton: keep the last factorised tangent (from earlier solves too) while each
  /// iteration cuts |R| at least tenfold; refactorise when one does not. Converges linearly,
  /// and pays where the tangent hardly changes (Newmark steps, dominated by 4 M / dt^2).
  bool reuse_tangent = false;
  std::vector<double> load_factors;    ///< static: increasing, ending at 1 (empty: uniform steps)
  int load_steps = 10;                 ///< static: uniform steps when load_factors is empty
  int max_cutbacks = 8;                ///< static: consecutive halvings of a failed increment
  SolverSettings solver;               ///< the linear solver of every iteration ([solver])
  bool nearly_symmetric = false;       ///< the tangent's (Discretisation::nearly_symmetric)
  std::ostream* log = nullptr;         ///< one line per iteration, if set
};

struct NewtonIterate {
  int iteration = 0;
  double residual = 0.0;  ///< |R| after the iteration (iteration 0: at the start)
  double alpha = 1.0;     ///< line-search step taken
  double order = 0.0;     ///< observed order p_k (0 where not defined)
};

struct NewtonOutcome {
  bool converged = false;
  bool stagnated = false;  ///< converged by stagnation at round-off
  std::string failure;  ///< why not, when not
  int factorisations = 0;
  std::vector<NewtonIterate> history;
};

/// The equations of one Newton solve.
struct NonlinearSystem {
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> residual;  ///< may throw NumericalError (J <= 0)
  std::function<void(const Eigen::VectorXd&, SparseMatrix&)> tangent;
};

/// Newton from d (updated in place); k holds the tangent's pattern. The solver analyses the
/// first tangent it sees and keeps that analysis for every later one.
/// Stages "assembly", "factorisation", "solve", "residual" are timed on `timer`.
NewtonOutcome newton(const NonlinearSystem& system, Eigen::VectorXd& d, SparseMatrix& k, LinearSolver& solver,
                     const NewtonSettings& settings, StageTimer& timer);

struct LoadStepRecord {
  double factor = 0.0;
  int cutbacks = 0;  ///< failed attempts before this step converged
  std::vector<NewtonIterate> history;
};

struct StaticSolution {
  Eigen::VectorXd coefficients;
  std::vector<LoadStepRecord> steps;
  SolverReport solver;  ///< the linear solver of the iterations and what it did
};

/// Solves the static problem of `model` (on `nodes`, whose rigid-body modes an AMG
/// preconditioner takes) by load stepping; on_step(record, d) after every converged load
/// step, once the model's history is committed there.
/// Instantiated for dim = 2, 3 (dim from the model).
template <int dim>
StaticSolution solve_static(
    TotalLagrangian<dim>& model, std::type_identity_t<std::span<const Point<dim>>> nodes,
    const NewtonSettings& settings, StageTimer& timer,
    const std::function<void(const LoadStepRecord&, const Eigen::VectorXd&)>& on_step = {});

}  // namespace mfree

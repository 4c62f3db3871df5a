#pragma once
// Time integration of the total-Lagrangian meshfree equations of motion
//
//   M d_tt + f_int(d) + f_c(d) = f_ext(t)      (f_c: Nitsche's terms of the walls)
//
// for the coefficients d (u^h = sum phi_I d_I), two schemes:
//
//   central_difference  explicit, lumped (row-sum) mass m_I = rho0 sum_K w_K phi_I(X_K),
//                       every one checked positive. Leapfrog form: v_{n+1/2} = v_{n-1/2} +
//                       dt a_n, d_{n+1} = d_n + dt v_{n+1/2}. Stable for dt <= 2 / omega_max;
//                       omega_max^2 = largest eigenvalue of M_L^-1 K(d_0), estimated by power
//                       iteration on M_L^-1/2 K M_L^-1/2 (critical_time_step()). A requested
//                       step above that limit is refused; without one, dt = stability_factor x
//                       the limit.
//   newmark             implicit average acceleration (beta = 1/4, gamma = 1/2) with the
//                       consistent mass and modified Newton in every step on the effective
//                       tangent K(d) + 4 / dt^2 M (one symbolic factorisation for the whole
//                       run; a numeric one only when an iteration cuts |R| less than tenfold).
//                       Unconditionally stable for linear problems; energy conserving there.
//
// Both take dt = end_time / ceil(end_time / requested): steps of equal length that end at
// end_time. Energy through time: kinetic 1/2 v.M v (the scheme's mass), strain sum_K w_K W(F_K),
// the work of the external forces f_ext - f_c (wall reactions included) accumulated by the
// trapezoidal rule, and the plastic work dissipated (laws with history, committed after
// every step); total = kinetic + strain + dissipated - work is constant for the exact motion.

#include <functional>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/galerkin/newton_solver.hpp"
#include "mfree/galerkin/total_lagrangian.hpp"

namespace mfree {

enum class TimeScheme { central_difference, newmark };
/// central_difference, newmark: the names scenes use.
const NameTable<TimeScheme>& time_scheme_names();
std::string_view to_string(TimeScheme s);

struct DynamicsSettings {
  TimeScheme scheme = TimeScheme::newmark;
  double end_time = 0.0;
  std::optional<double> time_step;      ///< requested dt (required for newmark)
  double stability_factor = 0.5;        ///< explicit without time_step: dt = factor x limit
  int energy_every = 1;                 ///< steps between energy records (work is summed every step); 0: none
  NewtonSettings newton;                ///< newmark; newton.solver: every linear solve
  std::ostream* progress = nullptr;     ///< a line per tenth of the run
};

struct EnergyRecord {
  double time = 0.0;
  double kinetic = 0.0;
  double strain = 0.0;
  double external_work = 0.0;
  double dissipated = 0.0;  ///< plastic work (laws with history)
  [[nodiscard]] double total() const { return kinetic + strain + dissipated - external_work; }
};

/// The state handed to the caller after every step (and at t = 0, step 0).
struct DynamicState {
  int step = 0;
  double time = 0.0;
  const Eigen::VectorXd& d;
  const Eigen::VectorXd& v;
  const Eigen::VectorXd& a;                 ///< accelerations: u_tt^h = sum phi_I a_I
  const Eigen::VectorXd* lumped = nullptr;  ///< the scheme's mass: lumped (per DOF), or
  const SparseMatrix* mass = nullptr;       ///< consistent
  /// M a with the scheme's mass: the inertia forces of the equations of motion (their sum
  /// over the nodes in a direction is the rate of momentum, d/dt int rho0 u_t^h).
  [[nodiscard]] Eigen::VectorXd inertia() const {
    return lumped ? Eigen::VectorXd(lumped->cwiseProduct(a)) : Eigen::VectorXd(*mass * a);
  }
};

struct DynamicsResult {
  double time_step = 0.0;
  int steps = 0;
  std::optional<double> stability_limit;  ///< explicit: 2 / omega_max
  long newton_iterations = 0;             ///< newmark: summed over the steps
  long factorisations = 0;                ///< newmark: tangents factorised (modified Newton)
  std::vector<EnergyRecord> energy;       ///< empty when energy_every = 0
  Eigen::VectorXd d, v;                   ///< at end_time
  std::optional<SolverReport> solver;     ///< newmark: the linear solver and what it did
};

/// The integrator's state after a step: all that the next step starts from, so that a run
/// saved here and resumed gives the steps an uninterrupted run gives, bit for bit.
template <int dim>
struct DynamicsProgress {
  int step = 0;
  Eigen::VectorXd d, v, a;      ///< coefficients of displacement, velocity, acceleration
  Eigen::VectorXd v_half;       ///< central differences: v_{n+1/2}
  Eigen::VectorXd g;            ///< f_ext - f_c at d (the work term's), when energy is recorded
  double work = 0.0;            ///< work of f_ext - f_c so far
  std::vector<EnergyRecord> energy;
  long newton_iterations = 0;
  long factorisations = 0;
  /// Newmark: the values of the effective tangent factorised last (modified Newton keeps it
  /// across steps), on the pattern of TotalLagrangian<dim>::zero_matrix().
  Eigen::VectorXd tangent;
  PointHistory<dim> history;  ///< the model's committed material states (laws with history)
};

/// Saving and resuming a run (a checkpoint's part that the integrator owns).
template <int dim>
struct DynamicsCheckpoints {
  int every = 0;                                          ///< steps between saves (0: none)
  std::function<void(const DynamicsProgress<dim>&)> save;  ///< after every `every`-th step but the last
  const DynamicsProgress<dim>* resume = nullptr;           ///< continue from this state
  /// Refuses a part of `resume` that does not fit the run, naming it as DynamicsProgress
  /// does ("v_half", "energy", ...) and saying what is wrong; must throw (an InputError naming
  /// where the state came from: CheckpointState::refuse). Empty: an InputError of its own.
  std::function<void(const std::string& name, const std::string& what)> refuse;
  /// Called once `resume` passed its checks, before the first step, with the run's step
  /// count and dt: the caller restores (and checks) its own records of the run so far.
  std::function<void(int steps, double dt)> resumed;
};

/// Coefficients v with u^h = sum phi_I v_I the L2 projection of a field: M v = int rho0 phi v0
/// (the model's densities), M solved by the solver of `solver` (on `nodes`).
template <int dim>
Eigen::VectorXd project_velocity(
    const TotalLagrangian<dim>& model, std::type_identity_t<std::span<const Point<dim>>> nodes,
    const std::type_identity_t<std::function<Point<dim>(const Point<dim>&)>>& field,
    const SolverSettings& solver);

/// 2 / omega_max for the lumped mass m (per DOF) and the tangent at d (power iteration).
template <int dim>
double critical_time_step(const TotalLagrangian<dim>& model, const Eigen::VectorXd& lumped,
                          const Eigen::VectorXd& d);

/// Integrates from (d0, v0) at t = 0 to end_time; on_step after every step (and at step 0),
/// the steps a resumed run takes only. Stages "residual", "assembly", "factorisation",
/// "solve", "energy" are timed on timer. A resumed state must come from the same model,
/// (d0, v0) and settings (the step and the masses are derived from them again); before any
/// of it is used it is checked against the run (checkpoints.refuse when it does not fit): its
/// step one of the run's, d, v, a, v_half of the model's DOFs, g too when the energy is
/// recorded (empty otherwise), the tangent empty or on the pattern (Newmark; empty for
/// central differences), the history of the model's points, as many energy records as the
/// run wrote by the step, at times of the run so far with kinetic energies of 0 or more, and
/// det F > 0 at every quadrature point of d. The model's history (laws with history) is
/// committed at d0 and after every step.
/// Instantiated for dim = 2, 3 (dim from the model).
template <int dim>
DynamicsResult integrate_dynamics(TotalLagrangian<dim>& model, const std::vector<Point<dim>>& node_positions,
                                  Eigen::VectorXd d0, Eigen::VectorXd v0, const DynamicsSettings& settings,
                                  StageTimer& timer,
                                  const std::function<void(const DynamicState&)>& on_step = {},
                                  const DynamicsCheckpoints<dim>& checkpoints = {});

}  // namespace mfree

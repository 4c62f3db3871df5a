#pragma once
// The sections plane and solid elasticity scenes share (io/elasticity_scene.hpp,
// io/solid_scene.hpp), each read by one function; `dimension` (2 or 3) sets what a section
// takes in a solid:
//
//   [nodes]       cloud (lattice | perturbed | random), spacing, perturbation, seed
//   [kernel]      order (linear | quadratic), window, support (circular | tensor), factor,
//                 irregular_factor_scale, support_rule (plane: geodesic | visibility | plain,
//                 default geodesic; solid: plain | visibility, default plain), allow_bridging
//   [quadrature]  scheme, ratio, cloud, order, factor, lattice_refinement, consistency,
//                 gauss_points. A solid integrates by the projected scheme only (its default),
//                 with ratio default 8 (quadrature points per node), the quadrature cloud's
//                 order default the RK order, consistency vci (default) or none
//   [nitsche]     beta
//   [solver]      kind, preconditioner, tolerance, max_iterations, direct_limit
//   [newton]      tolerance, absolute_tolerance, max_iterations, line_search, load_steps or
//                 load_factors, max_cutbacks
//   [dynamics]    error_times (fractions of end_time at which errors against an exact motion
//                 are measured; default [1.0])
//   [study]       of a dynamics run: time_schemes (default the scene's scheme), time_steps (one
//                 per scheme; default [dynamics] time_step, else the explicit scheme's step from
//                 its stability limit), time_step_check (rerun the finest level with dt / 2)
//
// Every key is type- and range-checked and each table finished (unknown keys refused), as in
// scene_reader.hpp.

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/galerkin/newton_solver.hpp"
#include "mfree/galerkin/total_lagrangian.hpp"
#include "mfree/io/read_choice.hpp"
#include "mfree/io/scene_reader.hpp"
#include "mfree/problems/formula.hpp"

namespace mfree {

/// The condition types of a [[boundary]] table by name: displacement, slip, traction, pressure.
template <int dim>
const NameTable<typename BoundaryCondition<dim>::Type>& condition_types();

/// No formula of a static run may use t (it would be evaluated at t = 0 only): an error at
/// `key` unless the run is `dynamics`.
void check_static(const SceneTable& t, const std::string& key, const Formula& f, bool dynamics);

/// [domain] interfaces: "tied" (true: supports end at the faces between regions and Nitsche's
/// method ties them) or "smooth" (false: one set of functions across).
const NameTable<bool>& interface_choices();

/// [nodes] into s.nodes.
void read_nodes_section(const SceneTable& t, ElasticitySettings& s);
/// [kernel] into s (order, window, support, factors, the support rule of the dimension).
void read_kernel_section(const SceneTable& t, ElasticitySettings& s, int dimension);
/// [quadrature] (an empty table when absent) into s; s.order must be read first.
void read_quadrature_section(const SceneTable& t, ElasticitySettings& s, int dimension);
/// [nitsche] beta (the Nitsche penalty), `beta` when the key is absent.
double read_nitsche_section(const SceneTable& t, double beta);
/// [solver] into s.solver; a symmetric solver with VCI's non-symmetric stiffness is refused.
void read_solver_section(const SceneTable& t, ElasticitySettings& s);
/// [newton], its linear solves by `solver`.
NewtonSettings read_newton_section(const SceneTable& t, const SolverSettings& solver);

/// The time schemes of a dynamics study and their steps.
struct TimeStudy {
  std::vector<TimeScheme> schemes;
  std::vector<double> steps;  ///< one per scheme; 0: the explicit scheme's step from its stability limit
  bool step_check = false;    ///< rerun the finest level with dt / 2
};
/// [study]'s time keys (above) of a scene whose [dynamics] is `dynamics` (none: the keys are
/// refused).
TimeStudy read_time_study(const SceneTable& t, const DynamicsSettings* dynamics);
/// [dynamics] error_times.
std::vector<double> read_error_times(const SceneTable& t);

}  // namespace mfree

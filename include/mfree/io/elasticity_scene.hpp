#pragma once
// Elasticity scenes: one TOML file describes a run (see verification/cantilever/*.toml).
//
//   [domain]      rectangle = [[x0, y0], [x1, y1]]  or  mesh = "path/to.wkt" or a gmsh file
//                 (.geo, .msh, .step, ...; relative to the scene); for a mesh of several
//                 regions (Domain::from_regions): regions = ["a", "b"] (names of a WKT file's
//                 polygons), interfaces = "tied" (default: the edges regions share are tied
//                 interfaces) | "smooth" (one set of functions across them)
//   [nodes]       cloud (lattice | perturbed | random), spacing, perturbation, seed
//   [kernel]      order (linear | quadratic), window, support (circular | tensor), factor
//   [quadrature]  (optional) scheme (gauss_cells | projected | nodal; default gauss_cells), ratio, cloud
//                 (lattice | like_nodes), order, factor, lattice_refinement (the projected
//                 scheme's), consistency (symmetric | vci | none; vci is of the RK order:
//                 quadratic RK gets quadratic VCI; default by scheme: vci for gauss_cells,
//                 symmetric for projected, none for nodal), gauss_points (per direction per
//                 cell, default 3 for linear RK and 4 for quadratic: default_gauss_points)
//   [material]    model (plane_stress | plane_strain | neo_hookean | st_venant_kirchhoff),
//                 youngs_modulus, poisson_ratio (at most 0.49 in plane strain: max_poisson_ratio,
//                 galerkin/total_lagrangian.hpp; allow_locking = true lifts that), density (dynamics);
//                 or [[material]] tables, one law per region: name, regions = ["a", ...]
//                 (every region in exactly one), and the keys of [material] (any law; a
//                 density in every table or in none, and the densities may differ)
//   [constants]   name = number: constants for every formula of the scene
//   [loads]       body_force = [fx, fy] (per unit volume; numbers or formulas in X, Y, t),
//                 gravity = [gx, gy] (per unit mass, times [material] density)   optional
//   [exact]       solution = a built-in one (problems/builtin_solutions.hpp: timoshenko_beam:
//                 load; linear: offset, gradient; quadratic: offset, gradient, hessian_x,
//                 hessian_y (symmetric, of u_x and u_y); vibration (dynamics): amplitude), or the formulas
//                 displacement = [ux, uy] with stress = [sxx, syy, sxy] or gradient = [dux/dx, dux/dy,
//                 duy/dx, duy/dy] (statics; the body force is [loads]')   optional
//   [[boundary]]  name, type (displacement | slip | traction | pressure), one selector:
//                 part = "name" (a named part: gmsh physical curve, rectangle bottom | right |
//                 top | left), ring = k (0 outer, k hole k), edges = [i, ...] (of ring, default
//                 0; numbered as written), region = [[x0, y0], [x1, y1]] (clips segments);
//                 value = "exact", [vx, vy] (numbers or formulas in X, Y, t), or for pressure
//                 p (a number or formula, positive into the body). A selector that selects
//                 nothing, and two conditions on one part of the boundary, are errors; so is
//                 a displacement or slip region selecting below 1% of its extent in the
//                 domain's bounding box (slivers), and a region that clips the edges it
//                 crosses at a corner (geometry/boundary_selection.hpp: corner_slivers),
//                 unless allow_small_selection = true.
//   [nitsche]     beta (default 100: penalty beta M / h, M = lambda + 2 mu the P-wave modulus
//                 of the law at the point)
//   [solver]      every linear solve (linalg/linear_solver.hpp): kind (auto | cholmod |
//                 umfpack | cg | gmres; auto: direct up to direct_limit unknowns, default
//                 200000 in the plane, 3000 in space (20000 for quadratic VCI's stiffness),
//                 Krylov above), and for the Krylov
//                 methods preconditioner (gamg | boomeramg | jacobi; default gamg, boomeramg
//                 for a non-symmetric stiffness other than linear VCI's), tolerance (on
//                 |b - A x| / |b|, default 1e-10),
//                 max_iterations (default 2000)
//   [newton]      total-Lagrangian statics (default for the finite-strain models): tolerance
//                 (on |R| / |R_0|), absolute_tolerance (on |R|; default tolerance times the
//                 residual of the full load on the undeformed body), max_iterations,
//                 line_search, load_steps or load_factors, max_cutbacks
//   [dynamics]    scheme (central_difference | newmark), end_time, time_step,
//                 stability_factor, energy_every (steps between energy records; 0: no
//                 energy balance computed), frames (VTK frames over the run),
//                 error_times (fractions of end_time at which errors are measured),
//                 initial_displacement, initial_velocity = [fx, fy] (formulas in X, Y; default 0)
//   [output]      folder, fields (displacement, velocity, stress, von_mises, error, weights),
//                 vtk, probe = [x, y] (u^h there at every load or time step),
//                 eigenvalues = n (the n smallest eigenvalues of the free stiffness; linear statics),
//                 checkpoint_every = n (dynamics: steps between checkpoints, io/checkpoint.hpp)
//   [study]       for `mfree converge`: spacings, clouds, orders, schemes (each with the scene's
//                 consistency, or its own default), betas, probe, reference, quadratic_factor,
//                 quadratic_gauss_points (default the scene's gauss_points, else 4); time_schemes,
//                 time_steps, time_step_check (dynamics)
//
// Every key is type- and range-checked; unknown keys are errors (scene_reader.hpp).

#include <array>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/io/elasticity_sections.hpp"
#include "mfree/io/scene_reader.hpp"
#include "mfree/io/scene_sections.hpp"
#include "mfree/problems/formula.hpp"

namespace mfree {

/// An exact static solution given as formulas in X, Y: u and either sigma (Voigt xx, yy,
/// xy) or grad u (du_x/dx, du_x/dy, du_y/dx, du_y/dy, stress by the small-strain law).
struct ExactFormulas {
  VectorFormula displacement;
  std::vector<Formula> stress;    ///< 3 formulas, or empty
  std::vector<Formula> gradient;  ///< 4 formulas, or empty
};

/// [exact]: a built-in solution, or formulas.
struct ExactSpec {
  std::optional<BuiltinChoice> builtin;
  std::optional<ExactFormulas> formulas;
};

struct OutputSettings {
  std::filesystem::path folder;
  std::set<std::string> fields;  ///< empty: nothing computed or written
  bool vtk = true;
  std::optional<Vec2> probe;
  int eigenvalues = 0;  ///< smallest free-stiffness eigenvalues to report (linear statics; 0: none)
  int checkpoint_every = 0;  ///< dynamics: steps between checkpoints (io/checkpoint.hpp; 0: none)
  [[nodiscard]] bool wants(const std::string& f) const { return fields.count(f) > 0; }
};

struct StudySettings {
  std::vector<double> spacings;
  std::vector<CloudKind> clouds;
  std::vector<RKOrder> orders;
  std::vector<QuadratureScheme> schemes;
  std::vector<double> betas;  ///< Nitsche penalties to sweep (default: the scene's)
  std::optional<Vec2> probe;
  std::optional<double> reference;  ///< reference u_y at the probe
  double quadratic_factor = 3.0;
  std::optional<int> quadratic_gauss_points;  ///< default: the scene's gauss_points (or the order's default)
  TimeStudy time;                             ///< dynamics: the time schemes and their steps
};

struct DynamicsScene {
  DynamicsSettings settings;
  std::optional<VectorFormula> initial_displacement;  ///< u(X, 0), L2-projected onto the RK functions
  std::optional<VectorFormula> initial_velocity;      ///< v(X, 0), likewise
  int frames = 0;                   ///< VTK frames written, evenly over the run (plus t = 0)
  std::vector<double> error_times;  ///< fractions of end_time
};

/// What a [[boundary]] table selected, for the run's report.
struct SelectedPart {
  std::string name, type, selector;
  double length = 0.0;
};

struct ElasticityScene {
  std::filesystem::path file;
  Constants constants;                   ///< [constants]
  std::optional<VectorFormula> body_force;  ///< [loads] body_force, per unit volume
  std::optional<Vec2> gravity;           ///< [loads] gravity, per unit mass (times density)
  std::vector<SelectedPart> selected;    ///< per [[boundary]], in order
  Domain domain;
  ElasticitySettings settings;  ///< settings.problem.material: the small-strain law (or the linearisation)
  Material material;            ///< the law of [material] model (of the first region with [[material]])
  double density = 0.0;         ///< rho0; 0 when not given (of the first region with [[material]])
  std::vector<Material>
      region_materials;  ///< [[material]]: the law of each region (Domain::regions()); else empty
  std::vector<double> region_densities;  ///< [[material]]: rho0 of each region; else empty
  std::optional<NewtonSettings> newton;
  std::optional<DynamicsScene> dynamics;
  std::optional<ExactSpec> exact_spec;
  OutputSettings output;
  std::optional<StudySettings> study;

  /// The exact solution of the scene, if any, for its domain and material (statics).
  [[nodiscard]] std::optional<ExactElasticity> exact() const;
  /// The exact motion of a built-in solution that is one (dynamics).
  [[nodiscard]] std::optional<ExactMotion<2>> motion() const;
  /// What a built-in solution is posed on: the domain's box, the material, the density.
  [[nodiscard]] SolutionSetting solution_setting() const;
  /// The finite-strain (or small-strain) problem of the scene; loads are those of statics
  /// with the exact body force, or the body force rho0 b(X, t) of an exact motion.
  [[nodiscard]] SolidProblem<2> solid_problem() const;
  /// rho0 b(X, t) of [loads]: body_force plus density times gravity.
  [[nodiscard]] BodyForce<2> loads_body_force() const;
  /// The body force of statics: [loads], or the one a built-in exact solution needs.
  [[nodiscard]] VectorField static_body_force() const;
  /// A line per [[boundary]]: name, type, what it selects and the length selected.
  [[nodiscard]] std::string describe_conditions() const;
  /// The law at X (its region's; on the boundary, the nearest region's).
  [[nodiscard]] const Material& law_at(const Vec2& x) const;
  /// The first law with the property (is_linear, has_history, ...), or null when none has it.
  [[nodiscard]] const Material* law_with(bool (*property)(const Material&)) const;
  /// The laws by name, for messages: "j2 material", or "materials j2 in 'matrix', plane_strain in 'fibre'".
  [[nodiscard]] std::string law_names() const;
  /// True when the scene is solved by the total-Lagrangian path (Newton or dynamics).
  [[nodiscard]] bool nonlinear() const {
    return newton || dynamics || law_with([](const Material& m) { return !is_linear(m); });
  }
};

/// Parses and checks a scene; `want_study` makes [study] required (mfree converge);
/// `overrides` as Scene::load.
ElasticityScene read_elasticity_scene(const std::filesystem::path& file, bool want_study,
                                      const std::vector<std::string>& overrides = {});

}  // namespace mfree

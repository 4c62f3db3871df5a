#pragma once
// Solid scenes: one TOML file describes a three-dimensional elasticity run (see
// verification/lame-sphere/lame_sphere.toml). A scene is a solid scene when its [domain]
// gives `box` or `solid`; `rectangle` and `mesh` make a plane scene (elasticity_scene.hpp).
//
//   [domain]      box = [[x0, y0, z0], [x1, y1, z1]] (its faces are the parts x_min, x_max,
//                 y_min, y_max, z_min, z_max), or solid = "part.geo" (a gmsh file: .geo, .msh,
//                 .step, .stp, .brep, .iges, .igs, relative to the scene, meshed into
//                 tetrahedra; its parts are the physical surfaces, its regions the physical
//                 volumes: geometry/gmsh_solid.hpp); interfaces = "tied" (default: the
//                 faces two regions share end the supports and Nitsche's method ties the
//                 sides) or "smooth" (one set of RK functions across), for a part of regions
//   [nodes], [kernel], [quadrature], [nitsche], [solver], [newton]: io/elasticity_sections.hpp
//                 (a solid integrates by the projected scheme, with VCI by default)
//   [material]    model (linear_elastic | neo_hookean | st_venant_kirchhoff | j2 |
//                 drucker_prager), youngs_modulus, poisson_ratio, the plastic laws' keys
//                 (io/scene_sections.hpp), density (with gravity)
//   [[material]]  instead of [material] in a solid of several regions: name, regions = ["r",
//                 ...] (each region in one table) and the keys of [material]; each quadrature
//                 point takes its region's law ([domain] interfaces: tied or smooth).
//   [constants]   name = number: constants for every formula of the scene
//   [loads]       body_force = [fx, fy, fz] (per unit reference volume; numbers or formulas in
//                 x, y, z), gravity = [gx, gy, gz] (per unit mass, times density)
//   [exact]       statics: displacement = [ux, uy, uz] and gradient = [dux/dx, dux/dy, dux/dz,
//                 duy/dx, ..., duz/dz] (9 formulas, row by row): errors in L2 and in energy
//                 (the small-strain law's) over an independent rule; needs linear_elastic.
//                 dynamics: solution = "vibration", amplitude = A: the axis-aligned vibration
//                 of SPEC section 6 on the cube [0, L]^3 (problems/axis_aligned_vibration.hpp;
//                 neo_hookean, slip walls), which sets the body force and the initial velocity
//                 (u = 0 at t = 0); RMS errors of u, v and the Cauchy stress at error_times
//   [[boundary]]  name, type (displacement | slip | traction | pressure), one selector: part =
//                 "name" or region = [[x0, y0, z0], [x1, y1, z1]] (the surface triangles' parts
//                 inside the box); value = "exact", [vx, vy, vz] (numbers or formulas), or for
//                 pressure p (positive into the body). A selector that selects no area, and two
//                 conditions on one part of the surface, are errors; so is a region thin across
//                 one axis (below 5 % of its largest side in the solid's box) that clips
//                 pieces off faces turned from that axis (strips of the faces round the one
//                 meant), unless allow_small_selection = true.
//   [dynamics]    scheme (central_difference | newmark), end_time, time_step (newmark's, or the
//                 explicit one's instead of stability_factor times the limit), energy_every,
//                 frames (field frames over the run), initial_displacement, initial_velocity =
//                 [fx, fy, fz] (formulas in x, y, z), error_times (with an [exact] motion:
//                 fractions of end_time, default [1]); needs [material] density. Loads and
//                 boundary values may then use t.
//   [output]      folder, fields (displacement, velocity, stress, von_mises, plastic_strain,
//                 error), vtk, probe = [x, y, z] (u^h there after every load step or frame;
//                 dynamics: probe.csv of every step),
//                 checkpoint_every (steps between checkpoints of a [dynamics] run; 0: none)
//   [study]       for `mfree converge`: spacings, orders (default the scene's), probe = [x, y,
//                 z] (default [output]'s; needed without [exact]), quadratic_factor (the
//                 support factor of an order the scene does not run, default 3); of a
//                 [dynamics] run with an [exact] motion: spacings, time_schemes, time_steps,
//                 time_step_check (io/elasticity_sections.hpp)
//
// Statics by Newton with load steps (a linear law: one step, one iteration): its formulas take
// no t (it scales its loads by the load factor); dynamics by central differences or Newmark.
// Every key is type- and
// range-checked; unknown keys are errors (scene_reader.hpp).

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mfree/core/exact_motion.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/galerkin/newton_solver.hpp"
#include "mfree/galerkin/total_lagrangian.hpp"
#include "mfree/geometry/solid.hpp"
#include "mfree/io/elasticity_sections.hpp"
#include "mfree/problems/formula.hpp"

namespace mfree {

/// [exact] of a solid scene: u and grad u (row i: the gradient of u_i) as formulas.
struct SolidExact {
  SpaceVectorFormula displacement;
  std::vector<Formula> gradient;  ///< 9 formulas, row by row
  [[nodiscard]] Tensor2<3> gradient_at(const Point<3>& x) const;
};

/// [dynamics] of a solid scene.
struct SolidDynamics {
  DynamicsSettings settings;
  std::optional<SpaceVectorFormula> initial_displacement;  ///< u(X, 0), L2-projected onto the RK functions
  std::optional<SpaceVectorFormula> initial_velocity;      ///< v(X, 0), likewise
  int frames = 0;                   ///< field frames written, evenly over the run (plus t = 0)
  std::vector<double> error_times;  ///< fractions of end_time (with an exact motion)
};

struct SolidStudy {
  std::vector<double> spacings;
  std::vector<RKOrder> orders;
  std::optional<Point<3>> probe;
  double quadratic_factor = 3.0;
  TimeStudy time;  ///< dynamics
};

struct SolidOutput {
  std::filesystem::path folder;
  std::set<std::string> fields;  ///< empty: nothing computed or written
  bool vtk = true;
  std::optional<Point<3>> probe;
  int checkpoint_every = 0;  ///< steps between checkpoints of a dynamic run (0: none)
  [[nodiscard]] bool wants(const std::string& f) const { return fields.count(f) > 0; }
};

/// What a [[boundary]] table selected, for the run's report.
struct SelectedSurface {
  std::string name, type, selector;
  double area = 0.0;
};

struct SolidScene {
  std::filesystem::path file;
  Solid solid;
  std::string model;            ///< [material] model, as the scene names it ("a + b": [[material]] laws)
  ElasticitySettings settings;  ///< nodes, kernel, quadrature, solver (settings.problem unused)
  SolidProblem<3> problem;      ///< the law, the loads, the conditions, Nitsche's beta, the spacing
  NewtonSettings newton;        ///< [newton], or one load step (and Newmark's iterations)
  std::optional<SolidDynamics> dynamics;
  std::optional<SolidExact> exact;       ///< statics
  std::optional<ExactMotion<3>> motion;  ///< dynamics
  SolidOutput output;
  std::vector<SelectedSurface> selected;  ///< per [[boundary]], in order
  std::optional<SolidStudy> study;

  /// The Lamé constants of the linear law at x (scenes with [exact]: every law linear_elastic).
  [[nodiscard]] Lame lame_at(const Point<3>& x) const;
  /// A line per [[boundary]]: name, type, what it selects and the area selected.
  [[nodiscard]] std::string describe_conditions() const;
};

/// The solid of a [domain] table: box = [[x0, y0, z0], [x1, y1, z1]] or solid = "part" (a gmsh
/// file relative to the scene) with its interfaces; InputError naming the key.
Solid read_solid_domain(const SceneTable& t);

/// True when the scene's [domain] gives `box` or `solid`.
bool is_solid_scene(const std::filesystem::path& file);

/// Parses and checks a solid scene (reading and meshing its part); `want_study` makes [study]
/// required (mfree converge); `overrides` as Scene::load.
SolidScene read_solid_scene(const std::filesystem::path& file, bool want_study = false,
                            const std::vector<std::string>& overrides = {});

}  // namespace mfree

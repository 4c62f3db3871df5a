#pragma once
// Elasticity scenes: one TOML file describes a run (see verification/cantilever/*.toml).
//
//   [domain]      rectangle = [[x0, y0], [x1, y1]]  or  mesh = "path/to.wkt" (relative to the scene)
//   [nodes]       cloud (lattice | perturbed | random), spacing, perturbation, seed
//   [kernel]      order (linear | quadratic), window, support (circular | tensor), factor
//   [quadrature]  scheme (projected | gauss_cells | nodal), ratio, cloud (lattice | like_nodes),
//                 order, factor,
//                 lattice_refinement, consistency (symmetric | vci | none), gauss_points
//   [material]    model (plane_stress | plane_strain), youngs_modulus, poisson_ratio
//   [exact]       solution (timoshenko_beam: load; linear: offset, gradient)   optional
//   [[boundary]]  name, type (displacement | traction), region = [[x0, y0], [x1, y1]],
//                 value = "exact" or [vx, vy]
//   [nitsche]     beta (default 100: penalty beta E / h)
//   [solver]      kind (auto | cholmod | umfpack)
//   [output]      folder, fields (displacement, stress, von_mises, error, weights), vtk
//   [study]       for `mfree converge`: spacings, clouds, orders, schemes, betas, probe, reference,
//                 quadratic_factor, quadratic_gauss_points
//
// Every key is type- and range-checked; unknown keys are errors (scene_reader.hpp).

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/io/scene_reader.hpp"

namespace mfree {

struct ExactSpec {
  std::string solution;  ///< timoshenko_beam | linear
  double load = 0.0;
  Vec2 offset = Vec2::Zero();
  Mat2 gradient = Mat2::Zero();
};

struct OutputSettings {
  std::filesystem::path folder;
  std::set<std::string> fields;  ///< empty: nothing computed or written
  bool vtk = true;
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
  int quadratic_gauss_points = 6;
};

struct ElasticityScene {
  std::filesystem::path file;
  Domain domain;
  ElasticitySettings settings;
  std::optional<ExactSpec> exact_spec;
  OutputSettings output;
  std::optional<StudySettings> study;

  /// The exact solution of the scene, if any, for its domain and material.
  [[nodiscard]] std::optional<ExactElasticity> exact() const;
};

/// Parses and checks a scene; `want_study` makes [study] required (mfree converge).
ElasticityScene read_elasticity_scene(const std::filesystem::path& file, bool want_study);

}  // namespace mfree

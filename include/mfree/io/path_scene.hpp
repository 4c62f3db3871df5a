#pragma once
// Material-point path scenes: one material driven along a prescribed deformation gradient
// F(t) (materials/strain_path.hpp), run by `mfree run SCENE` (apps/path_app.hpp). A scene
// with a [path] section is such a scene (see verification/material-point/*.toml):
//
//   [material]   model and its constants, the keys of an elasticity scene's [material]
//                (io/scene_sections.hpp): plane_stress, plane_strain, neo_hookean,
//                st_venant_kirchhoff; j2 (yield_stress, isotropic_modulus, kinematic_modulus,
//                saturation_stress, saturation_rate; materials/j2_plasticity.hpp) and
//                drucker_prager (friction_angle, dilatancy_angle, cohesion, tension_cutoff;
//                materials/drucker_prager.hpp), both with kinematics = "multiplicative"
//                (default), "logarithmic" or "small_strain" (materials/material_state.hpp). No density: a material point has no mass here.
//   [constants]  names for the formulas (optional)
//   [path]       deformation_gradient = [F_xx, F_xy, F_yx, F_yy]: numbers or formulas of t and
//                the constants, never of x, y, X, Y (a material point has no position);
//                end_time (> 0), increments (N >= 1 equal increments, t_n = n end_time / N),
//                record_every (k >= 1, default 1: increments 0, k, 2k, ... and N are recorded)
//   [output]     folder
//
// Every key is type- and range-checked; unknown keys are errors (scene_reader.hpp).

#include <filesystem>
#include <string>
#include <vector>

#include "mfree/io/scene_sections.hpp"
#include "mfree/materials/strain_path.hpp"
#include "mfree/problems/formula.hpp"

namespace mfree {

struct PathScene {
  std::filesystem::path file;
  MaterialSection material;
  std::vector<Formula> deformation_gradient;  ///< F_xx, F_xy, F_yx, F_yy: formulas of t
  StrainPathSettings path;
  std::filesystem::path folder;  ///< [output] folder

  /// F(t) of the four formulas (InputError, naming the key, where one is NaN or infinite).
  [[nodiscard]] Mat2 deformation(double t) const;
  /// The path as the driver takes it (holds copies of the formulas: outlives the scene).
  [[nodiscard]] DeformationPath deformation_path() const;
};

/// True when the scene file has a [path] section (then `mfree run` takes this path).
bool is_path_scene(const std::filesystem::path& file);

/// Parses and checks a material-point path scene; `overrides` as Scene::load. F is evaluated
/// at t = 0 and t = end_time, so that a formula that is not finite there fails here.
PathScene read_path_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

}  // namespace mfree

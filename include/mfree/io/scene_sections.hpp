#pragma once
// Sections that elasticity scenes and MPM scenes share, read the same way in both:
//
//   [material]  model (plane_stress | plane_strain | neo_hookean | st_venant_kirchhoff),
//               youngs_modulus, poisson_ratio, density (dynamics and MPM)
//   a box       [[x0, y0], [x1, y1]] (corners in any order)

#include <string>

#include "mfree/core/types.hpp"
#include "mfree/io/scene_reader.hpp"
#include "mfree/materials/material.hpp"

namespace mfree {

struct MaterialSection {
  std::string model;
  LinearElastic linear;  ///< the small-strain law of the same E and nu (the linearisation)
  Material material;     ///< the law of `model`
  double density = 0.0;  ///< rho0; 0 when not given
};

/// Reads [material] (every key range-checked, unknown keys refused).
MaterialSection read_material(const SceneTable& root);

/// The box of two corners under `key`.
Box read_box(const SceneTable& t, const std::string& key);

}  // namespace mfree

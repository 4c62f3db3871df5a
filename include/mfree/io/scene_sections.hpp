#pragma once
// Sections that elasticity scenes and MPM scenes share, read the same way in both:
//
//   [material]  model (plane_stress | plane_strain | neo_hookean | st_venant_kirchhoff),
//               youngs_modulus, poisson_ratio, density (dynamics and MPM)
//   a box       [[x0, y0], [x1, y1]] (corners in any order)
//   [constants] name = number, ...: named constants every formula of the scene may use
//   [exact]     solution = "name" of problems/builtin_solutions.hpp and that entry's parameters
//   a value     a number or a formula string in x, y, X, Y, t (problems/formula.hpp); a
//               vector value is an array of two of them, e.g. ["0", "-rho * g * (H - y)"]

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/solid.hpp"
#include "mfree/io/scene_reader.hpp"
#include "mfree/materials/material.hpp"
#include "mfree/problems/builtin_solutions.hpp"
#include "mfree/problems/formula.hpp"

namespace mfree {

struct MaterialSection {
  std::string model;
  LinearElastic linear;  ///< the small-strain law of the same E and nu (the linearisation)
  Material material;     ///< the law of `model`
  double density = 0.0;  ///< rho0; 0 when not given
};

/// Reads [material] (every key range-checked, unknown keys refused).
MaterialSection read_material(const SceneTable& root);
/// The keys of [material] from a table holding them (e.g. one of [[material]]), then
/// t.finish(): read any other key of t first. In a solid (dimension 3) the models are
/// linear_elastic (the 3D small-strain law) and the finite-strain and plastic laws, without
/// the logarithmic kinematics.
MaterialSection read_material_keys(const SceneTable& t, int dimension = 2);

/// [[material]] tables giving the named regions of a domain their laws: each table's `name`
/// (unique) and `regions` (each region in exactly one table), the rest of it read by `read`
/// (plane or solid keys). Returns the section of each region, in the order of
/// `region_names`. InputError naming the key: a name twice, a region in two tables or in none,
/// a density in some tables and not in others.
std::vector<MaterialSection> read_region_materials(
    const std::vector<SceneTable>& tables, const std::vector<std::string>& region_names,
    const std::function<MaterialSection(const SceneTable&)>& read);

/// The box of two corners under `key`.
Box read_box(const SceneTable& t, const std::string& key);

/// The box in space of two corners [[x0, y0, z0], [x1, y1, z1]] under `key` (any order).
AlignedBox<3> read_space_box(const SceneTable& t, const std::string& key);

/// Reads [constants] (optional; empty when absent).
Constants read_constants(const SceneTable& root);

/// The number or formula under `key`, parsed (errors name the key); dimension 3: in x, y, z.
Formula read_formula(const SceneTable& t, const std::string& key, const Constants& constants,
                     int dimension = 2);

/// The two numbers or formulas under `key`.
VectorFormula read_vector_formula(const SceneTable& t, const std::string& key, const Constants& constants);
/// The three numbers or formulas (in x, y, z) under `key`.
SpaceVectorFormula read_space_vector_formula(const SceneTable& t, const std::string& key,
                                             const Constants& constants);

/// [output] folder: a folder of its own (not "", ".", ".." or a root), relative to the
/// working directory; the run creates it and replaces what it held.
std::filesystem::path read_output_folder(const SceneTable& t);

/// A built-in solution as a scene names it, with its parameters' values.
struct BuiltinChoice {
  std::string name;
  SolutionValues values;
  [[nodiscard]] const BuiltinSolution& solution() const { return builtin_solutions().value(name); }
};

/// The key `solution` of t and the parameters its entry lists, checked by building the
/// solution on `setting`: a mismatch is an error at `solution` saying what the solution
/// needs, as is a static solution where a motion is wanted (`motion`) or the reverse.
BuiltinChoice read_builtin_solution(const SceneTable& t, const SolutionSetting& setting, bool motion);

}  // namespace mfree

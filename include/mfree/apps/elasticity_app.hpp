#pragma once
// `mfree run SCENE` and `mfree converge SCENE` for elasticity scenes (io/elasticity_scene.hpp).

#include <filesystem>
#include <string>
#include <vector>

namespace mfree {

/// One solve: summary, errors when an exact solution is known, VTK fields the scene asks for.
int run_elasticity(const std::filesystem::path& scene, const std::vector<std::string>& overrides = {},
                   const std::filesystem::path& restart = {});

/// A refinement study of the scene over [study]: CSV, PNG plots, observed rates.
int converge_elasticity(const std::filesystem::path& scene, const std::vector<std::string>& overrides = {});

}  // namespace mfree

#pragma once
// `mfree run` for solid scenes (io/solid_scene.hpp): the discretisation of the solid, the
// check that no rigid-body motion is free, Newton with load steps (a linear law: one step),
// the errors against [exact], the probe, summary.json and the fields for ParaView
// (io/solid_scene_output.hpp).

#include <filesystem>
#include <string>
#include <vector>

namespace mfree {

int run_solid_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides);

}  // namespace mfree

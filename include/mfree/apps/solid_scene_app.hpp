#pragma once
// `mfree run` and `mfree converge` for solid scenes (io/solid_scene.hpp). A run: the
// discretisation of the solid, the check that no rigid-body motion is free, Newton with load
// steps (a linear law: one step), the errors against [exact], the probe, the reactions and
// their balance, summary.json and the fields for ParaView (io/solid_scene_output.hpp). A
// dynamic run ([dynamics]): central differences or Newmark, frames, energy.csv, the errors
// against an [exact] motion at the error times, checkpoints and --restart (io/checkpoint.hpp).
// A study ([study]): the same solve at every
// spacing and RK order, the errors and their rates (or the probe's change between levels
// without [exact]), convergence.csv and its plots; of a dynamic run with an exact motion, every
// spacing for each time scheme (apps/dynamics_study.hpp).

#include <filesystem>
#include <string>
#include <vector>

namespace mfree {

/// `study`: mfree converge (needs [study]); else mfree run, continuing a dynamic run from the
/// newest checkpoint in `restart` when it is given.
int run_solid_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                    bool study = false, const std::filesystem::path& restart = {});

}  // namespace mfree

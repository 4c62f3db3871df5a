#pragma once
// `mfree run` and `mfree converge` for total-Lagrangian scenes: statics by Newton with load
// steps (finite-strain materials or a [newton] section) and dynamics ([dynamics]).

#include <optional>
#include <utility>
#include <vector>

#include "mfree/apps/dynamics_study.hpp"
#include "mfree/core/stage_timer.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/galerkin/motion_errors.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/elasticity_scene.hpp"
#include "mfree/io/reaction_output.hpp"

namespace mfree {

/// Newton with load steps: the iteration log, load_steps.csv (probe displacement and the
/// difference from small-strain theory at every step), a load-deflection plot, VTK frames.
int run_static(const ElasticityScene& scene);

/// One dynamic run: progress, errors at [dynamics] error_times, energy.csv, VTK frames;
/// checkpoints (io/checkpoint.hpp) when given.
int run_dynamics(const ElasticityScene& scene, const Checkpoints* checkpoints = nullptr);

/// Refinement study of a vibration scene over [study] spacings and time_schemes: errors at
/// every error time, observed rates, run times, CSV and PNG plots.
int converge_dynamics(const ElasticityScene& scene);

struct DynamicRun {
  Index nodes = 0;
  double spacing = 0.0;
  DynamicsResult result;
  std::vector<MotionErrors> errors;             ///< at the scene's error times
  std::vector<std::pair<double, Vec2>> probe;   ///< (t, u^h at the probe) every step
  std::optional<ReactionTable<2>> reactions;    ///< verbose runs: at the energy records' steps
  std::optional<Reactions<2>> last_reactions;   ///< verbose runs: at the last step
  StageTimer timer;
};

/// The run behind run_dynamics and converge_dynamics (verbose: progress and VTK frames).
DynamicRun simulate(const ElasticityScene& scene, const DynamicsSettings& settings, bool verbose,
                    const Checkpoints* checkpoints = nullptr);

}  // namespace mfree

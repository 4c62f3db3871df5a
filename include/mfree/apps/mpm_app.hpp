#pragma once
// `mfree run` and `mfree converge` for MPM scenes (io/mpm_scene.hpp).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mfree/io/checkpoint.hpp"
#include "mfree/io/mpm_scene.hpp"
#include "mfree/mpm/particle_errors.hpp"

namespace mfree {

/// One run: progress, errors at the error times, energy.csv, VTK frames, stage table;
/// checkpoints (io/checkpoint.hpp) when given: written as they fall due, and the run
/// continues from the one they restart from.
int run_mpm(const MPMScene& scene, const Checkpoints* checkpoints = nullptr);

/// Refinement study over [study] cells x methods x updates x particles per cell: errors at
/// every error time, observed rates, run times, mpm_convergence.csv (and mpm_energy.csv when
/// energy_every > 0), PNG plots. A run that fails (J <= 0, a particle leaving the grid) is
/// recorded with its message and the study goes on.
int converge_mpm(const MPMScene& scene);

struct MPMRun {
  Index particles = 0;
  int steps = 0;
  int resumed_at = 0;                  ///< the checkpoint's step a restarted run continued from
  double time_step = 0.0;
  double seconds = 0.0;                ///< wall time of the whole run, set-up included
  std::vector<ParticleErrors> errors;  ///< at the scene's error times reached
  std::vector<MPMEnergy> energy;       ///< every energy_every steps (and t = 0)
  std::vector<std::pair<double, Vec2>> probe;  ///< (t, u^h at the scene's probe) every step
  double max_mass_defect = 0.0;
  double max_reconstruction_defect = 0.0;  ///< bspline_mls, before its correction (MPMSolver)
  Index max_demoted_cells = 0;         ///< bspline_mls: most cells integrated by their particles in a step
  int demoted_steps = 0;               ///< steps with such cells
  std::optional<std::string> failure;  ///< what stopped the run early
  std::string particle_table;          ///< particles.csv of the end state (when the scene asks)
  StageTimer timer;
};

/// The run behind run_mpm and converge_mpm (verbose: run_mpm's single run, with progress,
/// VTK frames and, when the scene does not set energy_every, about 500 energy records).
MPMRun simulate_mpm(const MPMScene& scene, const MPMSettings& settings, bool verbose,
                    const Checkpoints* checkpoints = nullptr);

}  // namespace mfree

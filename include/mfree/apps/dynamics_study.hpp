#pragma once
// The refinement study of a dynamics scene with an exact motion, plane or solid (`mfree
// converge`): every time scheme at every spacing, the errors at the scene's error times and
// their observed rates between consecutive spacings, the run times (the solve, not the error
// measure) and the energy drift; optionally the finest level again with dt / 2 (space
// dominates when that changes little). Prints the table, writes convergence.csv and its plots
// (verification/plot_dynamics.py).

#include <filesystem>
#include <functional>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/galerkin/motion_errors.hpp"
#include "mfree/io/elasticity_sections.hpp"

namespace mfree {

/// What one run of a study gives.
struct DynamicsLevel {
  double spacing = 0.0;
  Index nodes = 0, dofs = 0;
  DynamicsResult result;
  std::vector<MotionErrors> errors;  ///< at the scene's error times
  double seconds = 0.0;              ///< the run without the error measure (StageTimer::total_without)
};

/// One run at node spacing h with the time settings given.
using SimulateLevel = std::function<DynamicsLevel(double h, const DynamicsSettings&)>;

/// The study over `spacings` and the time schemes of `time`, each run with `settings` (the
/// scene's) changed to the scheme and its step.
void dynamics_study(const std::vector<double>& spacings, const TimeStudy& time,
                    const DynamicsSettings& settings, const SimulateLevel& simulate,
                    const std::filesystem::path& folder);

/// max_t |E(t) - E(0)| / max_t (kinetic + strain): the energy error of a run; NaN when no
/// energy was recorded (energy_every = 0).
double energy_drift(const std::vector<EnergyRecord>& energy);

}  // namespace mfree

#pragma once
// The part of a checkpoint (checkpoint.hpp) that a total-Lagrangian dynamics run owns, in the
// plane (dim = 2) and in solids (dim = 3): the integrator's state and the errors against an
// exact motion measured so far. Arrays of the state:
//
//   step                     the step of the checkpoint
//   d, v, a, v_half, g       the integrator's vectors (DynamicsProgress), one value a DOF
//   work, energy             the work so far; energy records of 5 numbers (time, kinetic,
//                            strain, external work, dissipated)
//   history.domain,          material states of the domain's and the boundary's points,
//   history.boundary         dim^2 + 3 numbers each: E_p (column by column: xx, yx, xy, yy in
//                            the plane), E_p,zz (0 in 3D), alpha, dissipation
//   newton_iterations,       counts of the run so far
//   factorisations
//   tangent                  Newmark: the values of the effective tangent kept across steps
//   errors                   4 numbers an error time passed: time, RMS errors of u, v, stress
//   probe                    1 + dim numbers a record (a run with a probe: t = 0 and every
//                            step): time, u^h at the probe
//
// Explicitly instantiated for dim = 2 and 3.

#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <vector>

#include "mfree/core/stage_timer.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/galerkin/motion_errors.hpp"
#include "mfree/io/checkpoint.hpp"

namespace mfree {

/// A run's checkpoints wired to the integrator (DynamicsCheckpoints<dim>): with `checkpoints`
/// resuming, its newest state is restored (restore_progress) and, once the integrator accepted
/// it, restore(state, step, time) takes the run's own records back; with checkpoints due,
/// every checkpoints->every() steps the state (save_progress) and the run's records (save) are
/// written into `staging` (the run's output folder), timed as "checkpoints" on `timer`. Lines
/// saying so go to `log` when given. Not copyable: hooks() points into it.
template <int dim>
class DynamicsCheckpointing {
 public:
  using Save = std::function<void(CheckpointState&)>;
  using Restore = std::function<void(const CheckpointState&, long long step, double time)>;
  DynamicsCheckpointing(const Checkpoints* checkpoints, std::filesystem::path staging, StageTimer& timer,
                        Save save, Restore restore, std::ostream* log);
  DynamicsCheckpointing(const DynamicsCheckpointing&) = delete;
  DynamicsCheckpointing& operator=(const DynamicsCheckpointing&) = delete;
  [[nodiscard]] const DynamicsCheckpoints<dim>& hooks() const { return hooks_; }

 private:
  std::optional<DynamicsProgress<dim>> resume_;
  DynamicsCheckpoints<dim> hooks_;
  Save save_;
  Restore restore_;
};

template <int dim>
void save_progress(CheckpointState& s, const DynamicsProgress<dim>& p);

/// The integrator's state of checkpoint `s` of step `step`, as save_progress() wrote it: its
/// "step" that of the checkpoint, whole energy and history records, equivalent plastic strains
/// and counts of 0 or more. The rest (sizes against the model) is checked by
/// integrate_dynamics (DynamicsCheckpoints<dim>::refuse). InputError naming the array.
template <int dim>
DynamicsProgress<dim> restore_progress(const CheckpointState& s, long long step);

void save_errors(CheckpointState& s, const std::vector<MotionErrors>& errors);

/// The error records of checkpoint `s` at `time` (step `step`): whole records, at most
/// `most` (the error times), none after `time`, errors 0 or more. InputError naming the value.
std::vector<MotionErrors> restore_errors(const CheckpointState& s, long long step, double time,
                                         std::size_t most);

/// A probe's history: (time, u^h at the probe) at t = 0 and after every step.
template <int dim>
using ProbeHistory = std::vector<std::pair<double, Point<dim>>>;

template <int dim>
void save_probe(CheckpointState& s, const ProbeHistory<dim>& probe);

/// The probe records of checkpoint `s` at `time` (step `step`): step + 1 of them when the run
/// has a probe (none otherwise), each time within the run so far. InputError naming the value.
template <int dim>
ProbeHistory<dim> restore_probe(const CheckpointState& s, long long step, double time, bool probe);

}  // namespace mfree

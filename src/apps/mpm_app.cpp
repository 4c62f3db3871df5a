#include "mfree/apps/mpm_app.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include "mfree/apps/probe_study.hpp"
#include "mfree/apps/report.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/csv.hpp"
#include "mfree/io/run_summary.hpp"
#include "mfree/mpm/particle_probe.hpp"

namespace mfree {

namespace {

/// Step numbers of the scene's error times (fractions of end_time).
std::vector<int> error_steps(const MPMScene& scene, int steps) {
  std::vector<int> out;
  for (double f : scene.error_times) out.push_back(static_cast<int>(std::lround(f * steps)));
  return out;
}

/// Before anything is written: a particle state that is not finite is a NumericalError
/// naming the particle, never output. (The solver stops at the first such value where it
/// arises; this is the last guard of what the output reads.)
void check_finite(const MPMSolver& solver) {
  const Particles& P = solver.particles();
  for (Index p = 0; p < P.size(); ++p)
    if (!P.velocity[p].allFinite() || !P.position[p].allFinite() || !P.deformation[p].allFinite() ||
        !P.stress[p].allFinite())
      throw NumericalError(
          fmt::format("MPM: {} has a velocity, position, F or stress that is not finite at t = {:.6g} "
                      "s: the run is unstable; use a smaller time step",
                      particle_name(P, p), solver.time()));
}

/// max_t |E(t) - E(0)| / max_t (kinetic + strain), E = kinetic + strain - work of the body
/// forces of all the particles.
double energy_drift(const std::vector<MPMEnergy>& energy) {
  if (energy.empty()) return 0.0;
  double drift = 0.0, scale = 0.0;
  for (const MPMEnergy& e : energy) {
    drift = std::max(drift, std::abs(e.sum.total() - energy.front().sum.total()));
    scale = std::max(scale, e.sum.kinetic + e.sum.strain);
  }
  return drift / scale;
}

/// The largest gain of E = kinetic + strain + dissipated - work of the body forces, max_t
/// (E(t) - E(0)) / max_t (kinetic + strain), and the time of it: energy the discretisation
/// created (an exact undamped motion keeps E; damping and dissipative schemes lower it).
struct EnergyGrowth {
  double relative = 0.0, time = 0.0;
};
EnergyGrowth energy_growth(const std::vector<MPMEnergy>& energy) {
  EnergyGrowth out;
  if (energy.empty()) return out;
  double scale = 0.0, largest = 0.0;
  for (const MPMEnergy& e : energy) {
    scale = std::max(scale, e.sum.kinetic + e.sum.strain);
    const double gain = e.sum.total() - energy.front().sum.total();
    if (gain > largest) {
      largest = gain;
      out.time = e.time;
    }
  }
  out.relative = scale > 0.0 ? largest / scale : 0.0;
  return out;
}

/// The largest |total momentum| over the records.
double largest_momentum(const std::vector<MPMEnergy>& energy) {
  double m = 0.0;
  for (const MPMEnergy& e : energy) m = std::max(m, e.sum.momentum.norm());
  return m;
}

/// kinetic, strain, dissipated, external_work, total (the columns of a study's
/// mpm_energy.csv) ...
std::string energy_columns(const BodyEnergy& e) {
  return fmt::format("{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}", e.kinetic, e.strain, e.dissipated, e.external, e.total());
}
/// ... and the momentum, for every body of a run's energy.csv.
std::string energy_and_momentum(const BodyEnergy& e) {
  return fmt::format("{},{:.9e},{:.9e}", energy_columns(e), e.momentum.x(), e.momentum.y());
}

std::string energy_csv_rows(const std::string& prefix, const std::vector<MPMEnergy>& energy) {
  std::string out;
  for (const MPMEnergy& e : energy) out += fmt::format("{}{:.9e},{}\n", prefix, e.time, energy_columns(e.sum));
  return out;
}

/// energy.csv of a run: time, the totals over every particle (the columns of mpm_energy.csv,
/// then momentum_x, momentum_y), then the same per body, prefixed "NAME.".
std::string energy_csv(const MPMProblem& problem, const std::vector<MPMEnergy>& energy) {
  const auto columns = {"kinetic", "strain", "dissipated", "external_work", "total", "momentum_x", "momentum_y"};
  std::string out = "time";
  for (const char* c : columns) out += fmt::format(",{}", c);
  for (const MPMBody& b : problem.bodies)
    for (const char* c : columns) out += fmt::format(",{}.{}", b.name, c);
  out += "\n";
  for (const MPMEnergy& e : energy) {
    out += fmt::format("{:.9e},{}", e.time, energy_and_momentum(e.sum));
    for (const BodyEnergy& b : e.bodies) out += fmt::format(",{}", energy_and_momentum(b));
    out += "\n";
  }
  return out;
}

/// Per body (and in total) at the first and last record: kinetic, strain, work, momentum.
void print_energy(const MPMProblem& problem, const std::vector<MPMEnergy>& energy) {
  const MPMEnergy &first = energy.front(), &last = energy.back();
  std::cout << fmt::format("  {:<16} {:>11} {:>11} {:>11} {:>11} {:>12} {:>11} {:>11}   (0: t = {:.4g} s, T: t = {:.4g} s)\n",
                           "body", "kinetic(0)", "kinetic(T)", "strain(0)", "strain(T)", "dissipated(T)", "work(T)",
                           "|momentum(T)|", first.time, last.time);
  const auto row = [](const std::string& name, const BodyEnergy& a, const BodyEnergy& b) {
    std::cout << fmt::format("  {:<16} {:11.4e} {:11.4e} {:11.4e} {:11.4e} {:12.4e} {:11.4e} {:11.4e}\n", name, a.kinetic,
                             b.kinetic, a.strain, b.strain, b.dissipated, b.external, b.momentum.norm());
  };
  for (std::size_t k = 0; k < first.bodies.size(); ++k) row(problem.bodies[k].name, first.bodies[k], last.bodies[k]);
  if (first.bodies.size() > 1) row("total", first.sum, last.sum);
}

/// The bodies and walls of a run, as the scene names them.
void print_bodies(const MPMProblem& problem, const MPMSettings& s, const Particles& P) {
  std::vector<Index> count(problem.bodies.size(), 0);
  for (Index p = 0; p < P.size(); ++p) ++count[P.body[p]];
  for (std::size_t k = 0; k < problem.bodies.size(); ++k) {
    const MPMBody& b = problem.bodies[k];
    std::cout << fmt::format("  body '{}': {}, material '{}', {} particles\n", b.name, shape_names().name(b.shape),
                             problem.materials[b.material].name, count[k]);
  }
  std::string walls;
  for (const std::string& side : side_names().names())
    walls += fmt::format(" {} {}", side, wall_names().name(s.walls[static_cast<std::size_t>(side_names().value(side))]));
  std::cout << fmt::format("  walls:{}{}\n", walls, s.damping > 0.0 ? fmt::format("; damping {:.4g} 1/s", s.damping) : "");
}

/// The largest particle spacing h / n over the bodies (n their particles per side).
double particle_spacing(const MPMScene& scene, const MPMSettings& s, double h) {
  int per_side = s.particles_per_side;
  for (const MPMBody& b : scene.problem.bodies) per_side = std::min(per_side, b.particles_per_side > 0 ? b.particles_per_side : s.particles_per_side);
  return h / per_side;
}

// Checkpoints: the solver's state (the particles, the time, the work of the body forces) and
// the run's records so far (energy, errors, frames).

void save_energy(CheckpointState& state, const std::vector<MPMEnergy>& energy) {
  std::vector<double> flat;
  for (const MPMEnergy& e : energy) {
    flat.push_back(e.time);
    for (const BodyEnergy* b : {&e.sum}) flat.insert(flat.end(), {b->kinetic, b->strain, b->dissipated, b->external, b->momentum.x(), b->momentum.y()});
    for (const BodyEnergy& b : e.bodies) flat.insert(flat.end(), {b.kinetic, b.strain, b.dissipated, b.external, b.momentum.x(), b.momentum.y()});
  }
  state.put("energy", std::move(flat));
}

/// The energy records of a checkpoint: `count` records (1 + 6 (bodies + 1) numbers each) at
/// times in [0, time], with kinetic energies of 0 or more.
std::vector<MPMEnergy> restore_energy(const CheckpointState& state, std::size_t bodies, std::size_t count,
                                      double time) {
  const std::size_t record = 1 + 6 * (bodies + 1);
  const std::vector<double>& flat = state.get("energy", count * record);
  std::vector<MPMEnergy> out;
  for (std::size_t at = 0; at < flat.size();) {
    MPMEnergy e;
    if (!(flat[at] >= 0.0 && flat[at] <= time))
      state.refuse("energy", fmt::format("value {} is {}, not a time of the run so far (0 to {} s)", at,
                                         flat[at], time));
    e.time = flat[at++];
    const auto next = [&] {
      if (!(flat[at] >= 0.0))
        state.refuse("energy", fmt::format("value {} is {}, not a kinetic energy (0 or more)", at, flat[at]));
      BodyEnergy b;
      b.kinetic = flat[at];
      b.strain = flat[at + 1];
      b.dissipated = flat[at + 2];
      b.external = flat[at + 3];
      b.momentum = Vec2(flat[at + 4], flat[at + 5]);
      at += 6;
      return b;
    };
    e.sum = next();
    for (std::size_t k = 0; k < bodies; ++k) e.bodies.push_back(next());
    out.push_back(std::move(e));
  }
  return out;
}

CheckpointState save_run(const MPMSolver& solver, const MPMRun& run, const std::optional<MPMFrames>& frames) {
  CheckpointState s;
  const Particles& P = solver.particles();
  s.put("particles.mass", P.mass);
  s.put("particles.volume0", P.volume0);
  s.put("particles.volume", P.volume);
  s.put_values("particles.reference", P.reference);
  s.put_values("particles.position", P.position);
  s.put_values("particles.velocity", P.velocity);
  s.put_values("particles.deformation", P.deformation);
  s.put_values("particles.stress", P.stress);
  s.put("particles.stress_zz", P.stress_zz);
  std::vector<Mat2> plastic;
  std::vector<double> plastic_zz, alpha, dissipation;
  for (const MaterialState<2>& m : P.state) {
    plastic.push_back(m.plastic_strain);
    plastic_zz.push_back(m.plastic_strain_zz);
    alpha.push_back(m.alpha);
    dissipation.push_back(m.dissipation);
  }
  s.put_values("particles.plastic_strain", plastic);
  s.put("particles.plastic_strain_zz", std::move(plastic_zz));
  s.put("particles.alpha", std::move(alpha));
  s.put("particles.dissipation", std::move(dissipation));
  s.put_values("particles.half_size", P.half_size);
  std::vector<double> corners;  // CPDI2: x, y of the 4 corners per particle (none otherwise)
  corners.reserve(8 * P.corners.size());
  for (const DomainCorners& c : P.corners)
    for (const Vec2& x : c) corners.insert(corners.end(), {x.x(), x.y()});
  s.put("particles.corners", std::move(corners));
  s.put_ints("particles.body", P.body);
  s.put_ints("particles.material", P.material);
  s.put("time", solver.time());
  s.put("external_work", solver.external_work());
  save_energy(s, run.energy);
  std::vector<double> errors;
  for (const ParticleErrors& e : run.errors)
    errors.insert(errors.end(), {e.time, e.displacement, e.velocity, e.grid_velocity, e.stress});
  s.put("errors", std::move(errors));
  s.put("max_mass_defect", run.max_mass_defect);
  s.put("max_reconstruction_defect", run.max_reconstruction_defect);
  s.put("demoted", std::vector<double>{static_cast<double>(run.max_demoted_cells),
                                       static_cast<double>(run.demoted_steps)});
  std::vector<double> probe;
  for (const auto& [t, u] : run.probe) probe.insert(probe.end(), {t, u.x(), u.y()});
  s.put("probe", std::move(probe));
  if (frames) frames->save(s);
  return s;
}

// Restoring a checkpoint: every array is checked against this run before it is used
// (io/checkpoint.hpp), so that a checkpoint that is whole but wrong is refused, naming the
// array and the value, instead of indexing past the scene's lists or running past its end.

constexpr double unbounded = std::numeric_limits<double>::infinity();
constexpr double smallest_positive = std::numeric_limits<double>::denorm_min();

/// The particles of checkpoint `s`: every array of the scene's particle count n (half sizes
/// for the methods with domains, corners for CPDI2, none otherwise); mass, volumes, half sizes
/// and det F positive; alpha 0 or more; body and material indices of the scene's lists.
Particles restore_particles(const CheckpointState& s, const MPMSolver& solver, std::size_t materials) {
  const auto n = static_cast<std::size_t>(solver.particles().size());
  const MPMMethod method = solver.settings().method;
  Particles P;
  P.mass = s.within("particles.mass", smallest_positive, unbounded, "positive", n);
  P.volume0 = s.within("particles.volume0", smallest_positive, unbounded, "positive", n);
  P.volume = s.within("particles.volume", smallest_positive, unbounded, "positive", n);
  P.reference = s.values<Vec2>("particles.reference", n);
  P.position = s.values<Vec2>("particles.position", n);
  P.velocity = s.values<Vec2>("particles.velocity", n);
  P.deformation = s.values<Mat2>("particles.deformation", n);
  for (std::size_t p = 0; p < n; ++p)
    if (const double J = P.deformation[p].determinant(); !(J > 0.0))
      s.refuse("particles.deformation", fmt::format("particle {} has det F = {}, not positive", p, J));
  P.stress = s.values<Mat2>("particles.stress", n);
  P.stress_zz = s.get("particles.stress_zz", n);
  const std::vector<Mat2> plastic = s.values<Mat2>("particles.plastic_strain", n);
  const std::vector<double>& plastic_zz = s.get("particles.plastic_strain_zz", n);
  const std::vector<double>& alpha =
      s.within("particles.alpha", 0.0, unbounded, "an equivalent plastic strain (0 or more)", n);
  const std::vector<double>& dissipation = s.get("particles.dissipation", n);
  for (std::size_t k = 0; k < n; ++k)
    P.state.push_back({plastic[k], plastic_zz[k], alpha[k], dissipation[k]});
  (void)s.within("particles.half_size", smallest_positive, unbounded, "positive",
                 uses_domains(method) ? 2 * n : 0);
  P.half_size = s.values<Vec2>("particles.half_size");
  if (s.has("particles.corners") || method == MPMMethod::cpdi2) {  // checkpoints from before CPDI2 have none
    const std::vector<double>& corners = s.get("particles.corners", method == MPMMethod::cpdi2 ? 8 * n : 0);
    P.corners.resize(corners.size() / 8);
    for (std::size_t k = 0; k < corners.size(); k += 2) P.corners[k / 8][(k % 8) / 2] = Vec2(corners[k], corners[k + 1]);
  }
  const auto indices = [&](const std::string& name, std::size_t count, const char* of) {
    const std::vector<long long> v =
        s.integers(name, 0, static_cast<long long>(count) - 1,
                   fmt::format("one of this scene's {} {} (0 to {})", count, of, count - 1), n);
    return std::vector<int>(v.begin(), v.end());
  };
  P.body = indices("particles.body", static_cast<std::size_t>(solver.bodies()), "bodies");
  P.material = indices("particles.material", materials, "materials");
  return P;
}

/// The records of the run up to `step` (at `time`), each as many as the run wrote by then.
void restore_records(const CheckpointState& s, long long step, double time, const MPMScene& scene,
                     std::size_t bodies, const std::vector<int>& error_at, int energy_every, MPMRun& run) {
  const std::size_t records = energy_every > 0 ? static_cast<std::size_t>(step / energy_every) + 1 : 0;
  run.energy = restore_energy(s, bodies, records, time);
  std::size_t errors_due = 0;
  if (scene.exact)
    for (const int at : error_at) errors_due += at >= 1 && at <= step ? 1 : 0;
  const std::vector<double>& errors =
      s.within("errors", 0.0, unbounded, "a time or an error (0 or more)", 5 * errors_due);
  for (std::size_t at = 0; at < errors.size(); at += 5) {
    if (errors[at] > time)
      s.refuse("errors", fmt::format("value {} is {}, after the run's time {} s", at, errors[at], time));
    run.errors.push_back({errors[at], errors[at + 1], errors[at + 2], errors[at + 3], errors[at + 4]});
  }
  run.max_mass_defect = s.within("max_mass_defect", 0.0, unbounded, "a defect (0 or more)", 1)[0];
  run.max_reconstruction_defect =
      s.within("max_reconstruction_defect", 0.0, unbounded, "a defect (0 or more)", 1)[0];
  const std::vector<long long> demoted =
      s.integers("demoted", 0, std::numeric_limits<int>::max(), "a count", 2);
  if (demoted[1] > step)
    s.refuse("demoted", fmt::format("value 1 is {}, more steps than the run's {} so far", demoted[1], step));
  run.max_demoted_cells = static_cast<Index>(demoted[0]);
  run.demoted_steps = static_cast<int>(demoted[1]);
  // One probe record at t = 0 and one after every step.
  const std::vector<double>& probe = s.get("probe", scene.probe ? 3 * static_cast<std::size_t>(step + 1) : 0);
  for (std::size_t at = 0; at < probe.size(); at += 3) {
    if (!(probe[at] >= 0.0 && probe[at] <= time))
      s.refuse("probe",
               fmt::format("value {} is {}, not a time of the run so far (0 to {} s)", at, probe[at], time));
    run.probe.emplace_back(probe[at], Vec2(probe[at + 1], probe[at + 2]));
  }
}

/// Continues `solver` and `run` from checkpoint `s` of step `step` (see above): the step one
/// of the run's, the time that of the step, then the particles and the records.
void restore_run(const CheckpointState& s, long long step, const MPMScene& scene,
                 const std::vector<int>& error_at, int energy_every, MPMSolver& solver, MPMRun& run,
                 std::optional<MPMFrames>& frames) {
  if (step < 0 || step >= run.steps)
    throw InputError(
        fmt::format("checkpoint {}: step {} is not one of this run's steps (0 to {}): the checkpoint is "
                    "damaged; restart from an earlier checkpoint or without --restart",
                    s.source.string(), step, run.steps - 1));
  // time_ += dt at every step: within half a step of step dt, plus the round-off of the sum.
  const double end = solver.settings().end_time, dt = solver.time_step();
  const double time =
      s.within("time", 0.0, end, fmt::format("a time of this run (0 to end_time {} s)", end), 1)[0];
  const double slack = 0.5 * dt + static_cast<double>(step) * std::numeric_limits<double>::epsilon() * end;
  if (std::abs(time - static_cast<double>(step) * dt) > slack)
    s.refuse("time", fmt::format("value 0 is {} s, not the time of step {} ({} s, dt = {} s)", time, step,
                                 static_cast<double>(step) * dt, dt));
  const std::vector<double>& work = s.get("external_work", static_cast<std::size_t>(solver.bodies()));
  Particles P = restore_particles(s, solver, scene.problem.materials.size());
  restore_records(s, step, time, scene, static_cast<std::size_t>(solver.bodies()), error_at, energy_every,
                  run);
  if (frames) frames->restore(s, time, static_cast<std::size_t>(step) + 1);
  solver.resume(std::move(P), time, work);
}

}  // namespace

MPMRun simulate_mpm(const MPMScene& scene, const MPMSettings& settings, bool verbose, const Checkpoints* checkpoints) {
  const auto t0 = std::chrono::steady_clock::now();
  MPMRun run;
  // The solver's own input errors ("MPM: ...": settings, time step, particles) get the scene
  // file; those about a key already name it.
  MPMSolver solver = [&] {
    try {
      return MPMSolver(scene.problem, settings);
    } catch (const InputError& e) {
      if (!std::string_view(e.what()).starts_with("MPM: ")) throw;
      throw InputError(fmt::format("{}: {}", scene.file.string(), e.what()));
    }
  }();
  run.particles = solver.particles().size();
  run.steps = solver.steps();
  run.time_step = solver.time_step();
  if (verbose)
    std::cout << fmt::format("  {} particles, grid {} x {} nodes (h = {:.5g}), {} steps of dt = {:.4e} s "
                             "({:.3f} of the Courant limit{})\n",
                             run.particles, solver.grid().nx(), solver.grid().ny(), solver.grid().spacing(), run.steps,
                             run.time_step, run.time_step / solver.courant_limit(),
                             settings.mapping == GridMapping::pseudo_inverse
                                 ? ", which the pseudo-inverse mapping's consistent mass lowers below h / c"
                                 : " h / c");
  if (verbose) print_bodies(scene.problem, settings, solver.particles());
  std::optional<MPMFrames> frames;
  const bool any_field = scene.fields.displacement || scene.fields.velocity || scene.fields.stress ||
                         scene.fields.von_mises || scene.fields.plastic_strain || scene.fields.body ||
                         scene.fields.error || scene.fields.grid || scene.fields.domains;
  const CheckpointState* resume = checkpoints ? checkpoints->resume() : nullptr;
  if (verbose && scene.vtk && any_field && scene.frames > 0) {
    frames.emplace(scene.folder, scene.fields, scene.exact ? &*scene.exact : nullptr, scene.problem.materials);
    if (!resume) frames->write(solver);
  }
  const std::vector<int> at = error_steps(scene, run.steps);
  // A single run records its energy unless the scene says otherwise (about 500 records), so
  // that a balance that grows is reported (run_mpm); a study records what the scene asks.
  const int energy_every = scene.energy_every >= 0 ? scene.energy_every : verbose ? std::max(1, run.steps / 500) : 0;
  if (energy_every > 0 && !resume) run.energy.push_back(solver.energy());
  std::optional<ParticleProbe> probe;
  if (scene.probe) {
    probe.emplace(solver.particles(), *scene.probe, particle_spacing(scene, settings, solver.grid().spacing()));
    if (!resume) run.probe.emplace_back(solver.time(), probe->displacement(solver.particles()));
  }
  int first = 1;
  if (resume) {
    restore_run(*resume, checkpoints->resume_step(), scene, at, energy_every, solver, run, frames);
    first = static_cast<int>(checkpoints->resume_step()) + 1;  // checked: a step of the run
    run.resumed_at = first - 1;
    if (verbose) std::cout << fmt::format("  continuing from step {} (t = {:.6g} s) of {}\n", first - 1, solver.time(),
                                          resume->source.parent_path().string());
  }
  if (verbose && checkpoints && checkpoints->every() > 0)
    std::cout << fmt::format("  checkpoints every {} steps in {}\n", checkpoints->every(), checkpoints->folder().string());
  const int report_every = std::max(1, run.steps / 10);
  try {
    for (int n = first; n <= run.steps; ++n) {
      solver.step();
      run.max_mass_defect = std::max(run.max_mass_defect, solver.mass_defect());
      run.max_reconstruction_defect = std::max(run.max_reconstruction_defect, solver.reconstruction_defect());
      run.max_demoted_cells = std::max(run.max_demoted_cells, solver.demoted_cells());
      run.demoted_steps += solver.demoted_cells() > 0 ? 1 : 0;
      if (scene.exact)
        for (int s : at)
          if (s == n) run.errors.push_back(particle_errors(solver, *scene.exact));
      if (energy_every > 0 && (n % energy_every == 0 || n == run.steps)) run.energy.push_back(solver.energy());
      if (probe) run.probe.emplace_back(solver.time(), probe->displacement(solver.particles()));
      if (n % report_every == 0 || n == run.steps) {
        check_finite(solver);
        if (verbose)
          std::cout << fmt::format("  step {:>7}/{}  t = {:.6f} s  ({:.1f} s)\n", n, run.steps, solver.time(),
                                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count())
                    << std::flush;
      }
      if (frames && (static_cast<long long>(n) * scene.frames) % run.steps < scene.frames) {
        check_finite(solver);
        frames->write(solver);
      }
      if (checkpoints && checkpoints->due(n, run.steps)) {
        check_finite(solver);
        checkpoints->write(n, save_run(solver, run, frames), scene.folder);
      }
    }
  } catch (const NumericalError& e) {
    if (verbose) throw;
    run.failure = e.what();
  }
  if (verbose && scene.particles_csv && !run.failure) run.particle_table = particle_table(solver.particles(), scene.problem.bodies);
  run.timer = solver.timer();
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (verbose && frames) std::cout << fmt::format("  wrote {} frames, {} (open in ParaView)\n", frames->frames(), frames->series().filename().string());
  return run;
}

int run_mpm(const MPMScene& scene, const Checkpoints* checkpoints) {
  const MPMSettings& s = scene.settings;
  std::cout << fmt::format(
      "mfree run: {} (MPM, {} weights, {}, {} mapping{}, {} thread(s))\n", scene.file.string(),
      method_name(method_of(s)), to_string(s.update), grid_mapping_names().name(s.mapping),
      s.mass_filter > 0.0 ? fmt::format(" with mass_filter {}", s.mass_filter) : "", thread_count());
  if (checkpoints) checkpoints->restore_output(scene.folder);
  const MPMRun run = simulate_mpm(scene, s, true, checkpoints);
  if (!run.errors.empty()) {
    std::cout << fmt::format("  {:>10} {:>12} {:>12} {:>12} {:>12}   (RMS over the particles, seed 000 eq. 43)\n",
                             "t [s]", "u [m]", "v_p [m/s]", "v_grid [m/s]", "stress [Pa]");
    std::string csv = "time,displacement,velocity,grid_velocity,stress\n";
    for (const ParticleErrors& e : run.errors) {
      std::cout << fmt::format("  {:10.6f} {:12.4e} {:12.4e} {:12.4e} {:12.4e}\n", e.time, e.displacement, e.velocity,
                               e.grid_velocity, e.stress);
      csv += fmt::format("{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n", e.time, e.displacement, e.velocity, e.grid_velocity, e.stress);
    }
    std::cout << "  v_p: the particles' own (FLIP) velocities; v_grid: sum_i S_ip v_i at the particles\n";
    write_file_atomically(scene.folder / "errors.csv", csv);
    std::cout << "  wrote errors.csv\n";
  }
  if (s.method == MPMMethod::bspline_mls)
    std::cout << fmt::format("  MLS reconstruction: its mass differed from the particles' by up to {:.3e} (relative) before "
                             "the densities were scaled; the grid mass then differs by up to {:.3e}\n",
                             run.max_reconstruction_defect, run.max_mass_defect);
  if (run.demoted_steps > 0)
    std::cout << fmt::format(
        "  MLS reconstruction: up to {} interior cell(s) in {} step(s) integrated by their particles, a "
        "Gauss point there having too few particles around it for the moment matrix\n",
        run.max_demoted_cells, run.demoted_steps);
  if (!run.energy.empty()) {
    std::cout << fmt::format("  energy: kinetic + strain + dissipated - work of body forces drifts by {:.3e} of the largest "
                             "kinetic + strain\n", energy_drift(run.energy));
    const EnergyGrowth growth = energy_growth(run.energy);
    if (growth.relative > 0.05)  // a warning, not an error: MPM schemes drift by a few per cent
      std::cerr << fmt::format(
          "mfree: warning: the energy balance grew by {:.3g} of the largest kinetic + strain (at "
          "t = {:.6g} s): the discretisation created that energy. Plain B-splines with the lumped "
          "mapping and USF or Verlet keep it within 1 % on bodies that bounce "
          "(verification/mpm-vibration/README.md, \"Bodies that do not fill the grid\")\n",
          growth.relative, growth.time);
    print_energy(scene.problem, run.energy);
    std::cout << fmt::format("  total momentum: largest |sum m_p v_p| {:.3e} kg m/s\n", largest_momentum(run.energy));
    write_file_atomically(scene.folder / "energy.csv", energy_csv(scene.problem, run.energy));
    std::cout << "  wrote energy.csv\n";
  }
  if (!run.probe.empty()) {
    const Vec2& u = run.probe.back().second;
    std::cout << fmt::format("  probe ({:.6g}, {:.6g}): u^h = ({:.9e}, {:.9e}) at t = {:.6g} s\n", scene.probe->x(),
                             scene.probe->y(), u.x(), u.y(), run.probe.back().first);
    std::string csv = "time,probe_ux,probe_uy\n";
    for (const auto& [t, p] : run.probe) csv += fmt::format("{:.9e},{:.9e},{:.9e}\n", t, p.x(), p.y());
    write_file_atomically(scene.folder / "probe.csv", csv);
    std::cout << "  wrote probe.csv\n";
  }
  if (scene.particles_csv) {
    write_file_atomically(scene.folder / "particles.csv", run.particle_table);
    std::cout << "  wrote particles.csv\n";
  }
  const double throughput = run.particles * static_cast<double>(run.steps - run.resumed_at) / run.timer.total();
  std::cout << fmt::format("  {:.3e} particle-steps per second\n", throughput);
  print_stages(run.timer);
  RunSummary summary("mpm", scene.file);
  summary.text("method", method_name(method_of(s)));
  summary.text("update", std::string(to_string(s.update)));
  summary.text("mapping", grid_mapping_names().name(s.mapping));
  summary.number("mass_filter", s.mass_filter);
  summary.number("particles", static_cast<double>(run.particles));
  summary.number("steps", run.steps);
  summary.number("time_step", run.time_step);
  summary.number("particle_steps_per_second", throughput);
  summary.number("mass_defect", run.max_mass_defect);
  summary.number("reconstruction_defect", run.max_reconstruction_defect);
  summary.number("demoted_cells", static_cast<double>(run.max_demoted_cells));
  summary.number("demoted_steps", run.demoted_steps);
  if (!run.probe.empty()) summary.numbers("probe_displacement", {run.probe.back().second.x(), run.probe.back().second.y()});
  if (!run.energy.empty()) {
    summary.number("energy_drift", energy_drift(run.energy));
    summary.number("energy_growth", energy_growth(run.energy).relative);
    summary.number("largest_momentum", largest_momentum(run.energy));
    // Per body and in total, at the last record.
    std::vector<RunSummary::Record> bodies;
    const MPMEnergy& last = run.energy.back();
    const auto record = [&](const BodyEnergy& e) -> RunSummary::Record {
      return {{"kinetic", e.kinetic}, {"strain", e.strain}, {"dissipated", e.dissipated}, {"external_work", e.external},
              {"total", e.total()},
              {"momentum_x", e.momentum.x()}, {"momentum_y", e.momentum.y()}};
    };
    std::string names;
    for (std::size_t k = 0; k < last.bodies.size(); ++k) {
      bodies.push_back(record(last.bodies[k]));
      names += fmt::format("{}{}", k ? "," : "", scene.problem.bodies[k].name);
    }
    summary.text("bodies", names);  // the order of body_energy
    summary.records("body_energy", bodies);
    summary.records("total_energy", {record(last.sum)});
  }
  std::vector<RunSummary::Record> errors;
  for (const ParticleErrors& e : run.errors)
    errors.push_back({{"time", e.time}, {"displacement", e.displacement}, {"velocity", e.velocity},
                      {"grid_velocity", e.grid_velocity}, {"stress", e.stress}});
  summary.records("errors", errors);
  summary.stages(run.timer);
  summary.write(scene.folder);
  return 0;
}

int converge_mpm(const MPMScene& scene) {
  const MPMStudy& st = *scene.study;
  const std::size_t runs =
      st.cells.size() * st.methods.size() * st.updates.size() * st.mappings.size() * st.particles_per_side.size();
  std::cout << fmt::format("mfree converge: {} ({} runs, {} thread(s))\n", scene.file.string(), runs, thread_count());
  std::string csv =
      "method,update,mapping,particles_per_cell,cells,spacing,particles,steps,time_step,seconds,time_fraction,time,"
      "displacement,velocity,grid_velocity,stress,mass_defect,reconstruction_defect,energy_drift,probe_ux,probe_uy,status\n";
  std::string energy_csv =
      "method,update,mapping,particles_per_cell,cells,time,kinetic,strain,dissipated,external_work,total\n";
  // (series, error time index) -> (h, errors) over the grids, for the rate table.
  std::map<std::string, std::vector<std::pair<double, std::vector<ParticleErrors>>>> series;
  // Without [exact]: (series) -> (h, u^h at the probe at end_time) over the grids.
  std::map<std::string, std::vector<std::pair<double, Vec2>>> probes;
  std::size_t done = 0;
  for (int side : st.particles_per_side)
    for (const MPMMethodChoice& m : st.methods)
      for (UpdateScheme u : st.updates)
        for (GridMapping mapping : st.mappings)
          for (int cells : st.cells) {
            MPMSettings s = scene.settings;
            s.method = m.method;
            s.degree = m.degree == 1 ? 2 : m.degree;
            s.update = u;
            s.mapping = mapping;
            s.cells = cells;
            s.particles_per_side = side;
            const MPMRun run = simulate_mpm(scene, s, false);
            const double h = scene.problem.box.size().x() / cells;
            const std::string name =
                fmt::format("{},{},{},{}", method_name(m), to_string(u), grid_mapping_names().name(mapping), side * side);
            const std::string status = csv_status(run.failure);
            const double drift = energy_drift(run.energy);
            const double nan = std::nan("");
            const Vec2 at_probe = run.failure || run.probe.empty() ? Vec2(nan, nan) : run.probe.back().second;
            // One row per error time (with [exact]), else one row with the probe.
            const std::size_t rows = std::max<std::size_t>(run.errors.size(), scene.exact ? 0 : 1);
            for (std::size_t k = 0; k < rows; ++k) {
              const ParticleErrors e = k < run.errors.size() ? run.errors[k] : ParticleErrors{run.steps * run.time_step, nan, nan, nan, nan};
              csv += fmt::format("{},{},{:.9e},{},{},{:.9e},{:.6f},{:.6f},{:.9e},{},{},{},{},{},{},{},{},{},{}\n", name, cells, h,
                                 run.particles, run.steps, run.time_step, run.seconds,
                                 k < run.errors.size() ? scene.error_times[k] : 1.0, e.time,
                                 csv_number(e.displacement, "{:.9e}"), csv_number(e.velocity, "{:.9e}"),
                                 csv_number(e.grid_velocity, "{:.9e}"), csv_number(e.stress, "{:.9e}"),
                                 csv_number(run.max_mass_defect, "{:.6e}"),
                                 csv_number(run.max_reconstruction_defect, "{:.6e}"), csv_number(drift, "{:.6e}"),
                                 csv_number(at_probe.x(), "{:.9e}"), csv_number(at_probe.y(), "{:.9e}"), status);
            }
            energy_csv += energy_csv_rows(fmt::format("{},{},", name, cells), run.energy);
            if (!run.failure) series[name].emplace_back(h, run.errors);
            std::string line = fmt::format("{:<14} {:<6} {:<14} {:>2} ppc {:>4} cells: {:8.2f} s", method_name(m),
                                           to_string(u), grid_mapping_names().name(mapping), side * side, cells, run.seconds);
            if (!run.errors.empty()) {
              const ParticleErrors& e = run.errors.front();
              line += fmt::format("  at t = {:.4f}: u {:.3e} v_p {:.3e} v_grid {:.3e} stress {:.3e}", e.time,
                                  e.displacement, e.velocity, e.grid_velocity, e.stress);
            }
            if (!scene.exact && !run.failure) {
              probes[name].emplace_back(h, at_probe);
              const ProbeLevel level = probe_level(probes[name]);
              line += fmt::format("  probe u = ({:.9e}, {:.9e}), |change| {}, rate {}, extrapolated u = ({}, {})",
                                  at_probe.x(), at_probe.y(), level.change, level.rate, level.extrapolated_x,
                                  level.extrapolated_y);
            }
            if (scene.energy_every > 0) line += fmt::format("  energy drift {:.2e}", drift);
            if (run.failure) line += "  FAILED: " + *run.failure;
            std::cout << fmt::format("  [{}/{}] {}\n", ++done, runs, line) << std::flush;
          }
  // Observed rates log2(e(h) / e(h/2)) between successive grids, at every error time.
  if (scene.exact)
    std::cout << fmt::format("\n{:<40} {:>6} {:>8}  {:>10} {:>6}  {:>10} {:>6}  {:>10} {:>6}  {:>10} {:>6}\n",
                             "method,update,mapping,ppc", "t/T", "h", "u", "rate", "v_p", "rate", "v_grid", "rate", "stress", "rate");
  for (const auto& entry : series) {
    const std::string& name = entry.first;
    const auto& levels = entry.second;  // a plain reference: lambdas below capture it
    for (std::size_t k = 0; k < scene.error_times.size(); ++k)
      for (std::size_t l = 0; l < levels.size(); ++l) {
        if (levels[l].second.size() <= k) continue;
        const ParticleErrors& e = levels[l].second[k];
        auto rate = [&](double ParticleErrors::*f) -> std::string {
          if (l == 0 || levels[l - 1].second.size() <= k) return "-";
          const double r = std::log(levels[l - 1].second[k].*f / e.*f) / std::log(levels[l - 1].first / levels[l].first);
          return fmt::format("{:.2f}", r);
        };
        std::cout << fmt::format("{:<40} {:>6.3f} {:>8.5f}  {:>10.3e} {:>6}  {:>10.3e} {:>6}  {:>10.3e} {:>6}  {:>10.3e} {:>6}\n",
                                 name, scene.error_times[k], levels[l].first, e.displacement,
                                 rate(&ParticleErrors::displacement), e.velocity, rate(&ParticleErrors::velocity),
                                 e.grid_velocity, rate(&ParticleErrors::grid_velocity), e.stress,
                                 rate(&ParticleErrors::stress));
      }
  }
  const std::filesystem::path csv_path = scene.folder / "mpm_convergence.csv";
  write_file_atomically(csv_path, csv);
  std::cout << fmt::format("wrote {}\n", csv_path.filename().string());
  if (scene.energy_every > 0) {
    write_file_atomically(scene.folder / "mpm_energy.csv", energy_csv);
    std::cout << "wrote mpm_energy.csv\n";
  }
  if (scene.exact) plot("plot_mpm.py", csv_path, scene.folder);  // the plots draw errors
  return 0;
}

}  // namespace mfree

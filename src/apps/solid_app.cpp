#include "mfree/apps/solid_app.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "mfree/apps/report.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/galerkin/motion_errors.hpp"
#include "mfree/galerkin/newton_solver.hpp"
#include "mfree/galerkin/reactions.hpp"
#include "mfree/galerkin/rigid_body_modes.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/csv.hpp"
#include "mfree/io/dynamics_checkpoint.hpp"
#include "mfree/io/run_summary.hpp"
#include "mfree/io/solid_output.hpp"
#include "mfree/quadrature/gauss_cells.hpp"

namespace mfree {

namespace {

/// The static exact solution scaled by the load factor (small-strain theory), as a motion
/// whose "time" is the load factor.
std::optional<ExactMotion<2>> scaled_static(const ElasticityScene& scene) {
  const std::optional<ExactElasticity> e = scene.exact();
  if (!e) return std::nullopt;
  return ExactMotion<2>{[e = *e](const Vec2& x, double f) { return Vec2(f * e.displacement(x)); },
                        [](const Vec2&, double) { return Vec2(0.0, 0.0); },
                        [e = *e](const Vec2& x, double f) {
                          const Eigen::Vector3d s = f * e.stress(x);
                          Mat2 m;
                          m << s[0], s[2], s[2], s[1];
                          return m;
                        },
                        {}};  // the loads are the scene's
}

/// The trial functions at the scene's probe, sampled once for the whole run.
std::optional<GalerkinQuadrature<2>> probe_functions(const ElasticityScene& scene,
                                                     const Discretisation<2>& disc) {
  if (!scene.output.probe) return std::nullopt;
  return sample_shape_functions(*disc.trial, {*scene.output.probe}, false);
}

/// The law at X of the model's problem (its region's).
MaterialAt<2> law_at(const TotalLagrangian<2>& model, const Domain& domain) {
  return [&model, &domain](const Vec2& x) -> const Material& { return model.problem().law_at(domain, x); };
}

QuadratureRule<2> error_rule(const ElasticityScene& scene) {
  return gauss_cell_rule(scene.domain, 0.5 * scene.settings.nodes.spacing, scene.settings.error_gauss_points);
}

}  // namespace

int run_static(const ElasticityScene& scene) {
  std::cout << fmt::format("mfree run: {} (total-Lagrangian statics, {}, {} thread(s))\n",
                           scene.file.string(), scene.law_names(), thread_count());
  std::cout << scene.describe_conditions();
  StageTimer timer;
  timer.report_to(&std::cout);
  const Discretisation<2> disc = discretise(scene.domain, scene.settings, timer);
  TotalLagrangian<2> model(scene.solid_problem(), scene.domain, disc.node_count(), disc.quadrature,
                           disc.test(), disc.boundary, disc.at_boundary);
  timer.report_to(nullptr);
  {
    // Statics must be well posed: the reference tangent may leave no rigid-body motion free.
    SparseMatrix k0 = model.zero_matrix();
    model.tangent(Eigen::VectorXd::Zero(model.dofs()), {}, k0);
    check_rigid_body_modes(k0, disc.nodes);
  }
  std::cout << fmt::format("  {} nodes ({} DOFs), {} quadrature points, consistency defect {:.2e} -> {:.2e}, {} tangent\n",
                           disc.nodes.size(), model.dofs(), disc.quadrature.size(), disc.consistency_before,
                           disc.consistency_after, model.symmetric() ? "symmetric" : "non-symmetric");

  const std::optional<ExactMotion<2>> exact = scaled_static(scene);
  std::optional<MotionErrorSampler<2>> sampler;
  if (exact) sampler.emplace(*disc.trial, error_rule(scene), law_at(model, scene.domain));
  const OutputSettings& o = scene.output;
  std::optional<SolidFrames> frames;
  if (o.vtk && !o.fields.empty()) frames.emplace(scene, disc, exact ? &*exact : nullptr, &model);

  const std::optional<GalerkinQuadrature<2>> probe_at = probe_functions(scene, disc);
  NewtonSettings ns = scene.newton.value_or(NewtonSettings{});
  ns.solver = scene.settings.solver;
  ns.nearly_symmetric = disc.nearly_symmetric;
  ns.log = &std::cout;
  // Laws with history add the plastic work and the area of the plastic zone.
  const bool plastic = model.has_history();
  std::string csv = fmt::format("load_factor,iterations,cutbacks,probe_ux,probe_uy,linear_probe_uy,l2_displacement_vs_linear{}\n",
                                plastic ? ",dissipated,plastic_area" : "");
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.dofs());
  // The reactions of every converged step (reactions.csv), the last one reported.
  ReactionTable<2> reaction_table("load_factor", essential_parts(model.problem()), false);
  std::optional<Reactions<2>> last_reactions;
  const auto on_step = [&](const LoadStepRecord& step, const Eigen::VectorXd& d) {
    last_reactions = timer.time("reactions", [&] { return reactions(model, d, {step.factor, 0.0}); });
    reaction_table.add(static_cast<int>(reaction_table.size()) + 1, step.factor, *last_reactions);
    const int iterations = static_cast<int>(step.history.size()) - 1;
    Vec2 probe(std::nan(""), std::nan(""));
    double linear = std::nan(""), relative = std::nan("");
    if (probe_at) probe = displacement_at(*probe_at, 0, d);
    if (exact) {
      if (o.probe) linear = exact->displacement(*o.probe, step.factor).y();
      // Relative L2 difference from the small-strain solution at this load (independent
      // quadrature): the discretisation error at small loads, the nonlinearity at large ones.
      relative = (*sampler)(d, zero, step.factor, *exact).displacement / (*sampler)(zero, zero, step.factor, *exact).displacement;
    }
    std::cout << fmt::format("    converged: load factor {:.6g} in {} iteration(s){}{}{}{}\n", step.factor, iterations,
                             step.cutbacks ? fmt::format(" after {} cut-back(s)", step.cutbacks) : "",
                             o.probe ? fmt::format(", probe u = ({:.6g}, {:.6g})", probe.x(), probe.y()) : "",
                             exact ? fmt::format(", L2 difference from small strain {:.3e}", relative) : "",
                             plastic ? fmt::format(", plastic area {:.6g}, dissipated {:.6e}", model.plastic_area(),
                                                   model.dissipated())
                                     : "");
    // Cells without a probe or an exact solution stay empty (never "nan").
    csv += fmt::format("{:.9g},{},{},{},{},{},{}{}\n", step.factor, iterations, step.cutbacks, csv_number(probe.x(), "{:.9e}"),
                       csv_number(probe.y(), "{:.9e}"), csv_number(linear, "{:.9e}"), csv_number(relative, "{:.6e}"),
                       plastic ? fmt::format(",{:.9e},{:.9e}", model.dissipated(), model.plastic_area()) : "");
    if (frames) timer.time("output", [&] { frames->write(step.factor, d, nullptr); });
  };
  const StaticSolution sol = solve_static(model, disc.nodes, ns, timer, on_step);
  std::cout << fmt::format("  {} load steps, {} Newton iterations, solver {}\n", sol.steps.size(),
                           [&] {
                             int n = 0;
                             for (const auto& s : sol.steps) n += static_cast<int>(s.history.size()) - 1;
                             return n;
                           }(),
                           sol.solver.text());
  if (last_reactions) std::cout << reaction_lines(*last_reactions);
  const std::filesystem::path csv_path = o.folder / "load_steps.csv";
  write_file_atomically(csv_path, csv);
  write_file_atomically(o.folder / "reactions.csv", reaction_table.csv());
  std::cout << fmt::format("  wrote {}, reactions.csv\n", csv_path.filename().string());
  if (frames) std::cout << fmt::format("  wrote {} frames, {}\n", frames->frames(), frames->series().filename().string());
  if (o.probe) plot("plot_load_deflection.py", csv_path, o.folder);
  std::cout << "stages:\n";
  print_stages(timer);
  RunSummary summary("newton", scene.file);
  summary.number("dofs", static_cast<double>(model.dofs()));
  summary.text("solver", sol.solver.text());
  std::vector<RunSummary::Record> steps;
  for (const LoadStepRecord& step : sol.steps)
    steps.push_back({{"load_factor", step.factor},
                     {"iterations", static_cast<double>(step.history.size()) - 1},
                     {"cutbacks", static_cast<double>(step.cutbacks)}});
  summary.records("load_steps", steps);
  if (last_reactions) summarise_reactions(summary, *last_reactions);
  summary.stages(timer);
  summary.write(o.folder);
  return 0;
}

namespace {

// Checkpoints of a dynamic run: the integrator's state and the errors (io/dynamics_checkpoint)
// and the run's own records (probe history, frames, the next frame time).

/// The run's own records of checkpoint `s` of step `step`, at `time` (step dt) of a run to
/// `end` (end_time): the errors (restore_errors: at most one per error time), one probe record at t = 0 and
/// after every step when the scene has a probe, the next frame time within a frame interval past end_time.
void restore_records(const CheckpointState& s, long long step, double time, double end,
                     const ElasticityScene& scene, bool sampled, DynamicRun& run, double& next_frame) {
  const DynamicsScene& dyn = *scene.dynamics;
  run.errors = restore_errors(s, step, time, sampled ? dyn.error_times.size() : 0);
  const double interval = dyn.frames > 0 ? end / dyn.frames : 0.0;
  next_frame = s.within("next_frame", 0.0, (end + interval) * (1 + 1e-9),
                        fmt::format("a time within a frame interval past end_time ({} s)", end), 1)[0];
  run.probe = restore_probe<2>(s, step, time, scene.output.probe.has_value());
}

}  // namespace

DynamicRun simulate(const ElasticityScene& scene, const DynamicsSettings& settings, bool verbose,
                    const Checkpoints* checkpoints) {
  DynamicRun run;
  StageTimer& timer = run.timer;
  if (verbose) timer.report_to(&std::cout);
  const Discretisation<2> disc = discretise(scene.domain, scene.settings, timer);
  TotalLagrangian<2> model(scene.solid_problem(), scene.domain, disc.node_count(), disc.quadrature,
                           disc.test(), disc.boundary, disc.at_boundary);
  timer.report_to(nullptr);
  run.nodes = disc.node_count();
  run.spacing = scene.settings.nodes.spacing;

  const std::optional<ExactMotion<2>> exact = scene.motion();
  std::optional<MotionErrorSampler<2>> sampler;
  if (exact) sampler.emplace(*disc.trial, error_rule(scene), law_at(model, scene.domain));
  const DynamicsScene& dyn = *scene.dynamics;
  // Initial fields: of the exact motion, or the scene's formulas, L2-projected (the
  // coefficients of RK functions are not nodal values); zero otherwise.
  const auto initial = [&](const std::optional<VectorFormula>& f, bool velocity) -> Eigen::VectorXd {
    if (exact && velocity)
      return project_velocity(
          model, disc.nodes, [&](const Vec2& x) { return exact->velocity(x, 0.0); }, scene.settings.solver);
    if (f)
      return project_velocity(
          model, disc.nodes, [&](const Vec2& x) { return (*f)(x); }, scene.settings.solver);
    return Eigen::VectorXd::Zero(model.dofs());
  };
  const Eigen::VectorXd v0 = timer.time("initial velocity", [&] { return initial(dyn.initial_velocity, true); });
  const Eigen::VectorXd d0 = dyn.initial_displacement
                                 ? timer.time("initial displacement", [&] { return initial(dyn.initial_displacement, false); })
                                 : Eigen::VectorXd(Eigen::VectorXd::Zero(model.dofs()));

  const OutputSettings& o = scene.output;
  std::optional<SolidFrames> frames;
  if (verbose && o.vtk && !o.fields.empty() && dyn.frames > 0)
    frames.emplace(scene, disc, exact ? &*exact : nullptr, &model);
  const std::optional<GalerkinQuadrature<2>> probe_at = probe_functions(scene, disc);
  if (verbose) run.reactions.emplace("time", essential_parts(model.problem()), true);
  std::size_t next_error = 0;
  double next_frame = 0.0;
  const double end = settings.end_time;
  const auto on_step = [&](const DynamicState& s) {
    // The first step at or past each requested time; the exact motion is taken at the
    // step's own time.
    while (sampler && next_error < dyn.error_times.size() && s.time >= dyn.error_times[next_error] * end * (1 - 1e-12)) {
      run.errors.push_back(timer.time("errors", [&] { return (*sampler)(s.d, s.v, s.time, *exact); }));
      ++next_error;
    }
    if (frames && s.time >= next_frame * (1 - 1e-12)) {
      timer.time("output", [&] { frames->write(s.time, s.d, &s.v); });
      next_frame += end / dyn.frames;
    }
    if (probe_at) run.probe.emplace_back(s.time, displacement_at(*probe_at, 0, s.d));
    // Reactions with the inertia at the steps of the energy records (the first and last
    // steps when there are none).
    const bool last = s.time >= end * (1 - 1e-12);
    if (run.reactions &&
        (s.step == 0 || last || (settings.energy_every > 0 && s.step % settings.energy_every == 0))) {
      Reactions<2> re = timer.time("reactions", [&] {
        Reactions<2> r = reactions(model, s.d, {1.0, s.time});
        r.inertia = nodal_resultant(s.inertia(), disc.nodes, s.d, r.current_arm);
        return r;
      });
      run.reactions->add(s.step, s.time, re);
      if (last) run.last_reactions = std::move(re);
    }
  };
  DynamicsSettings ds = settings;
  ds.newton.nearly_symmetric = disc.nearly_symmetric;
  if (verbose) ds.progress = &std::cout;
  const DynamicsCheckpointing<2> cp(
      checkpoints, scene.output.folder, timer,
      [&](CheckpointState& s) {
        save_errors(s, run.errors);
        save_probe<2>(s, run.probe);
        s.put("next_frame", next_frame);
        if (run.reactions) run.reactions->save(s);
        if (frames) frames->save(s);
      },
      [&](const CheckpointState& s, long long step, double time) {
        restore_records(s, step, time, end, scene, sampler.has_value(), run, next_frame);
        if (run.reactions) run.reactions->restore(s, step, time);
        next_error = run.errors.size();
        if (frames) frames->restore(s, time, static_cast<std::size_t>(step) + 1);
      },
      verbose ? &std::cout : nullptr);
  run.result = integrate_dynamics(model, disc.nodes, d0, v0, ds, timer, on_step, cp.hooks());
  return run;
}

namespace {

std::string energy_csv(const std::vector<EnergyRecord>& energy) {
  std::string csv = "time,kinetic,strain,dissipated,external_work,total\n";
  for (const EnergyRecord& e : energy)
    csv += fmt::format("{:.9e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e}\n", e.time, e.kinetic, e.strain, e.dissipated,
                       e.external_work, e.total());
  return csv;
}

}  // namespace

int run_dynamics(const ElasticityScene& scene, const Checkpoints* checkpoints) {
  const DynamicsSettings& s = scene.dynamics->settings;
  std::cout << fmt::format("mfree run: {} (total-Lagrangian dynamics, {}, {}, {} thread(s))\n",
                           scene.file.string(), to_string(s.scheme), scene.law_names(), thread_count());
  std::cout << scene.describe_conditions();
  if (checkpoints) checkpoints->restore_output(scene.output.folder);
  const DynamicRun run = simulate(scene, s, true, checkpoints);
  const DynamicsResult& r = run.result;
  std::cout << fmt::format("  {} nodes ({} DOFs), {} steps of dt = {:.4e} s{}{}\n", run.nodes, 2 * run.nodes, r.steps,
                           r.time_step,
                           r.stability_limit ? fmt::format(" (stability limit {:.4e} s by power iteration)", *r.stability_limit) : "",
                           s.scheme == TimeScheme::newmark ? fmt::format(", {} Newton iterations, {} factorisations", r.newton_iterations, r.factorisations) : "");
  if (r.solver) std::cout << fmt::format("  solver: {}\n", r.solver->text());
  if (!run.errors.empty()) {
    std::cout << fmt::format("  {:>10} {:>12} {:>12} {:>12}   (RMS over the body, independent Gauss cells)\n", "t [s]",
                             "displacement", "velocity", "stress");
    for (const MotionErrors& e : run.errors)
      std::cout << fmt::format("  {:10.6f} {:12.4e} {:12.4e} {:12.4e}\n", e.time, e.displacement, e.velocity, e.stress);
  }
  const std::filesystem::path folder = scene.output.folder;
  if (r.energy.empty()) {
    std::cout << "  energy: not recorded ([dynamics] energy_every = 0)\n";
  } else {
    std::cout << fmt::format("  energy: total {:.6e} at t = 0, {:.6e} at the end; largest drift {:.3e} of the largest "
                             "kinetic + strain energy\n",
                             r.energy.front().total(), r.energy.back().total(), energy_drift(r.energy));
    write_file_atomically(folder / "energy.csv", energy_csv(r.energy));
    std::cout << "  wrote energy.csv\n";
  }
  if (run.last_reactions) std::cout << reaction_lines(*run.last_reactions);
  if (run.reactions) {
    write_file_atomically(folder / "reactions.csv", run.reactions->csv());
    std::cout << "  wrote reactions.csv\n";
  }
  if (!run.probe.empty()) {
    std::string csv = "time,probe_ux,probe_uy\n";
    for (const auto& [t, u] : run.probe) csv += fmt::format("{:.9e},{:.9e},{:.9e}\n", t, u.x(), u.y());
    write_file_atomically(folder / "probe.csv", csv);
    std::cout << "  wrote probe.csv\n";
  }
  if (scene.dynamics->frames > 0 && scene.output.vtk && !scene.output.fields.empty())
    std::cout << "  wrote series.pvd (open in ParaView)\n";
  std::cout << "stages:\n";
  print_stages(run.timer);
  RunSummary summary("dynamics", scene.file);
  summary.text("time_scheme", std::string(to_string(s.scheme)));
  summary.number("nodes", static_cast<double>(run.nodes));
  summary.number("steps", r.steps);
  summary.number("time_step", r.time_step);
  if (r.stability_limit) summary.number("stability_limit", *r.stability_limit);
  summary.number("energy_drift", energy_drift(r.energy));
  if (r.solver) summary.text("solver", r.solver->text());
  std::vector<RunSummary::Record> errors;
  for (const MotionErrors& e : run.errors)
    errors.push_back({{"time", e.time}, {"displacement", e.displacement}, {"velocity", e.velocity}, {"stress", e.stress}});
  summary.records("errors", errors);
  if (run.last_reactions) summarise_reactions(summary, *run.last_reactions);
  summary.stages(run.timer);
  summary.write(folder);
  return 0;
}

int converge_dynamics(const ElasticityScene& scene) {
  const StudySettings& st = *scene.study;
  if (!scene.motion())
    throw InputError(fmt::format("{}: a dynamics study needs an [exact] solution that is a motion", scene.file.string()));
  const std::size_t runs = st.time.schemes.size() * st.spacings.size();
  std::cout << fmt::format("mfree converge: {} ({} runs, {} thread(s))\n", scene.file.string(), runs, thread_count());
  std::cout << scene.describe_conditions();
  const auto simulate_level = [&](double h, const DynamicsSettings& ds) {
    ElasticityScene level = scene;
    level.settings.nodes.spacing = h;
    DynamicRun run = simulate(level, ds, false);
    return DynamicsLevel{h,
                         run.nodes,
                         2 * run.nodes,
                         std::move(run.result),
                         std::move(run.errors),
                         run.timer.total_without("errors")};
  };
  dynamics_study(st.spacings, st.time, scene.dynamics->settings, simulate_level, scene.output.folder);
  return 0;
}

}  // namespace mfree

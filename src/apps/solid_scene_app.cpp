#include "mfree/apps/solid_scene_app.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>

#include "mfree/apps/dynamics_study.hpp"
#include "mfree/apps/probe_study.hpp"
#include "mfree/apps/report.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/galerkin/motion_errors.hpp"
#include "mfree/galerkin/reactions.hpp"
#include "mfree/galerkin/rigid_body_modes.hpp"
#include "mfree/galerkin/small_strain_elasticity.hpp"
#include "mfree/galerkin/small_strain_errors.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/csv.hpp"
#include "mfree/io/dynamics_checkpoint.hpp"
#include "mfree/io/reaction_output.hpp"
#include "mfree/io/run_summary.hpp"
#include "mfree/io/solid_scene.hpp"
#include "mfree/io/solid_scene_output.hpp"
#include "mfree/io/vtk_output.hpp"
#include "mfree/quadrature/gauss_cells.hpp"

namespace mfree {

namespace {

std::string describe_solid(const Solid& solid) {
  const AlignedBox<3>& b = solid.bounding_box();
  const std::string what =
      solid.mesh() ? fmt::format("{} tetrahedra", solid.mesh()->size()) : std::string("a box");
  return fmt::format(
      "  solid: {}, volume {:.6g}, {} surface triangles, bounding box [[{:.6g}, {:.6g}, {:.6g}], "
      "[{:.6g}, {:.6g}, {:.6g}]]\n",
      what, solid.measure(), solid.surface().size(), b.min().x(), b.min().y(), b.min().z(), b.max().x(),
      b.max().y(), b.max().z());
}

/// The independent rule of the error measures: the solid's cells of the node spacing
/// (tetrahedra clipped to them where it is meshed), n^3 Gauss points on each piece, n = 3 for
/// linear RK and 4 for quadratic.
QuadratureRule<3> error_rule(const Solid& solid, const ElasticitySettings& s) {
  return gauss_cell_rule(solid, s.nodes.spacing, s.order == RKOrder::linear ? 3 : 4);
}

/// What one solve of a solid scene gives.
struct SolidLevel {
  Index nodes = 0, dofs = 0, quadrature_points = 0;
  double consistency_before = 0.0, consistency_after = 0.0;
  std::string solver;
  std::optional<SmallStrainErrors> errors;  ///< with [exact]
  std::optional<Point<3>> probe;            ///< u^h at the probe, when there is one
  double seconds = 0.0;                     ///< discretisation and solve (not the errors)
};

using StepReport = std::function<void(const LoadStepRecord&, const Eigen::VectorXd&,
                                      const TotalLagrangian<3>&, const std::optional<Point<3>>& probe)>;
using Finish =
    std::function<void(const Discretisation<3>&, const TotalLagrangian<3>&, const Eigen::VectorXd&)>;

/// One solve of the scene with settings s: the discretisation, the well-posedness check,
/// Newton with the scene's load steps (on_step after each), the errors against [exact] over
/// the error rule, then `finish` with the solution.
SolidLevel solve_level(const SolidScene& scene, const ElasticitySettings& s,
                       const std::optional<Point<3>>& probe, StageTimer& timer, bool verbose,
                       const StepReport& on_step, const Finish& finish) {
  const Solid& solid = scene.solid;
  SolidProblem<3> problem = scene.problem;
  problem.spacing = s.nodes.spacing;
  if (verbose) timer.report_to(&std::cout);
  const Discretisation<3> disc = discretise(solid, s, condition_parts(problem.conditions), timer);
  TotalLagrangian<3> model(problem, solid, disc.node_count(), disc.quadrature, disc.test(), disc.boundary,
                           disc.at_boundary);
  timer.report_to(nullptr);
  {
    // Statics must be well posed: the reference tangent may leave none of the six rigid-body
    // motions free.
    SparseMatrix k0 = model.zero_matrix();
    model.tangent(Eigen::VectorXd::Zero(model.dofs()), {}, k0);
    check_rigid_body_modes(k0, disc.nodes);
  }
  SolidLevel level{static_cast<Index>(disc.nodes.size()),
                   static_cast<Index>(model.dofs()),
                   disc.quadrature.size(),
                   disc.consistency_before,
                   disc.consistency_after,
                   {},
                   {},
                   {},
                   0.0};
  if (verbose)
    std::cout << fmt::format(
        "  {} nodes ({} DOFs), {} quadrature points, {} RK, {} cloud, spacing {}, consistency defect {:.2e} "
        "-> "
        "{:.2e}, {} tangent\n",
        level.nodes, level.dofs, level.quadrature_points, to_string(s.order), to_string(s.nodes.kind),
        s.nodes.spacing, level.consistency_before, level.consistency_after,
        model.symmetric() ? "symmetric" : "non-symmetric");
  std::optional<GalerkinQuadrature<3>> probe_at;
  if (probe) probe_at = sample_shape_functions(*disc.trial, std::vector<Point<3>>{*probe}, false);
  NewtonSettings newton = scene.newton;
  newton.solver = s.solver;
  newton.nearly_symmetric = disc.nearly_symmetric;
  const StaticSolution sol = solve_static(model, disc.nodes, newton, timer,
                                          [&](const LoadStepRecord& step, const Eigen::VectorXd& d) {
                                            if (probe_at) level.probe = displacement_at(*probe_at, 0, d);
                                            if (on_step) on_step(step, d, model, level.probe);
                                          });
  level.solver = sol.solver.text();
  level.seconds = timer.total();
  if (scene.exact) {
    const SolidExact& ex = *scene.exact;
    level.errors = timer.time("errors", [&] {
      return small_strain_errors(
          *disc.trial, sol.coefficients, error_rule(solid, s),
          [&](const Point<3>& x) { return scene.lame_at(x); },
          [&](const Point<3>& x) { return ex.displacement(x); },
          [&](const Point<3>& x) { return ex.gradient_at(x); });
    });
  }
  if (finish) finish(disc, model, sol.coefficients);
  return level;
}

int run(const SolidScene& scene) {
  const SolidOutput& o = scene.output;
  StageTimer timer;
  RunSummary summary("solid_statics", scene.file);
  std::vector<RunSummary::Record> steps;
  const auto on_step = [&](const LoadStepRecord& step, const Eigen::VectorXd&,
                           const TotalLagrangian<3>& model, const std::optional<Point<3>>& u) {
    RunSummary::Record r{{"factor", step.factor},
                         {"iterations", static_cast<double>(step.history.size())},
                         {"cutbacks", static_cast<double>(step.cutbacks)}};
    std::string line =
        fmt::format("  load factor {:.6g}: {} Newton iteration(s){}", step.factor, step.history.size(),
                    step.cutbacks > 0 ? fmt::format(" after {} cut-back(s)", step.cutbacks) : "");
    if (u) {
      line += fmt::format(", probe u^h = ({:.9e}, {:.9e}, {:.9e})", u->x(), u->y(), u->z());
      r.insert(r.end(), {{"probe_ux", u->x()}, {"probe_uy", u->y()}, {"probe_uz", u->z()}});
    }
    if (model.has_history()) line += fmt::format(", plastic volume {:.6g}", model.plastic_area());
    std::cout << line << '\n';
    steps.push_back(std::move(r));
  };
  std::vector<std::filesystem::path> files;
  std::optional<Reactions<3>> support;
  const auto finish = [&](const Discretisation<3>& disc, const TotalLagrangian<3>& model,
                          const Eigen::VectorXd& d) {
    support = timer.time("reactions", [&] { return reactions(model, d, {}); });
    if (o.vtk && !o.fields.empty())
      files = timer.time("output", [&] { return write_solid_fields(scene, disc, model, d); });
  };
  const SolidLevel level = solve_level(scene, scene.settings, o.probe, timer, true, on_step, finish);
  std::cout << fmt::format("  solver: {}\n", level.solver);
  summary.number("nodes", level.nodes);
  summary.number("dofs", level.dofs);
  summary.number("quadrature_points", level.quadrature_points);
  summary.number("volume", scene.solid.measure());
  summary.number("consistency_before", level.consistency_before);
  summary.number("consistency_after", level.consistency_after);
  summary.text("solver", level.solver);
  summary.records("load_steps", steps);
  if (level.errors) {
    std::cout << fmt::format("  relative errors: L2 displacement {:.4e}, energy {:.4e}\n", level.errors->l2,
                             level.errors->energy);
    summary.number("l2_displacement", level.errors->l2);
    summary.number("energy", level.errors->energy);
  }
  if (support) {
    std::cout << reaction_lines(*support);
    summarise_reactions(summary, *support);
  }
  for (const auto& f : files) std::cout << fmt::format("  wrote {}\n", f.filename().string());
  if (!files.empty())
    std::cout << "  open volume.vtu (or surface.vtu) in ParaView; warp by displacement\n";
  else
    std::cout << "  no output fields asked for: no field files (summary.json only)\n";
  std::cout << "stages:\n";
  print_stages(timer);
  summary.stages(timer);
  summary.write(o.folder);
  return 0;
}

/// What one dynamic run of a solid scene gives.
struct SolidDynamicRun {
  Index nodes = 0, dofs = 0;
  DynamicsResult result;
  std::vector<MotionErrors> errors;  ///< with an [exact] motion, at the error times
  StageTimer timer;
};

using OnState = std::function<void(const Discretisation<3>&, const TotalLagrangian<3>&, const DynamicState&,
                                   StageTimer&)>;

/// The checkpoints of a dynamic run and the caller's own records in them (beyond the
/// integrator's state and the errors): save() puts them, restore() takes them back (and checks
/// them) at step `step`, time `time`, before the first step of a resumed run.
struct RunCheckpoints {
  const Checkpoints* checkpoints = nullptr;
  std::function<void(CheckpointState&)> save;
  std::function<void(const CheckpointState&, long long step, double time)> restore;
};

/// One dynamic run of the scene with node settings s and time settings ds: the
/// discretisation, the initial fields L2-projected onto the RK functions (of the exact motion,
/// or the scene's formulas), central differences or Newmark to end_time, the errors against
/// the exact motion at the first step at or past each error time, on_state after every step;
/// checkpoints written and resumed from as `cp` says.
SolidDynamicRun simulate(const SolidScene& scene, const ElasticitySettings& s, DynamicsSettings ds,
                         bool verbose, const OnState& on_state, const RunCheckpoints& cp = {}) {
  const SolidDynamics& dyn = *scene.dynamics;
  SolidDynamicRun run;
  StageTimer& timer = run.timer;
  SolidProblem<3> problem = scene.problem;
  problem.spacing = s.nodes.spacing;
  if (verbose) timer.report_to(&std::cout);
  const Discretisation<3> disc = discretise(scene.solid, s, condition_parts(problem.conditions), timer);
  TotalLagrangian<3> model(problem, scene.solid, disc.node_count(), disc.quadrature, disc.test(),
                           disc.boundary, disc.at_boundary);
  timer.report_to(nullptr);
  run.nodes = static_cast<Index>(disc.nodes.size());
  run.dofs = static_cast<Index>(model.dofs());
  if (verbose)
    std::cout << fmt::format("  {} nodes ({} DOFs), {} quadrature points, {} RK, spacing {}, {}\n",
                             disc.nodes.size(), model.dofs(), disc.quadrature.size(), to_string(s.order),
                             s.nodes.spacing, to_string(ds.scheme));
  const ExactMotion<3>* motion = scene.motion ? &*scene.motion : nullptr;
  const auto project = [&](const std::function<Point<3>(const Point<3>&)>& f) -> Eigen::VectorXd {
    if (!f) return Eigen::VectorXd::Zero(model.dofs());
    return timer.time("initial fields", [&] { return project_velocity(model, disc.nodes, f, s.solver); });
  };
  const auto formula =
      [](const std::optional<SpaceVectorFormula>& f) -> std::function<Point<3>(const Point<3>&)> {
    if (!f) return {};
    return [f = *f](const Point<3>& x) { return f(x); };
  };
  const Eigen::VectorXd d0 = project(formula(dyn.initial_displacement));
  const Eigen::VectorXd v0 = motion
                                 ? project([motion](const Point<3>& x) { return motion->velocity(x, 0.0); })
                                 : project(formula(dyn.initial_velocity));
  std::optional<MotionErrorSampler<3>> sampler;
  if (motion)
    sampler.emplace(*disc.trial, error_rule(scene.solid, s),
                    [&](const Point<3>& x) -> const Material& { return problem.law_at(scene.solid, x); });
  ds.newton.solver = s.solver;
  ds.newton.nearly_symmetric = disc.nearly_symmetric;
  if (verbose) ds.progress = &std::cout;
  const double end = ds.end_time;
  std::size_t next_error = 0;
  const DynamicsCheckpointing<3> checkpointing(
      cp.checkpoints, scene.output.folder, timer,
      [&](CheckpointState& c) {
        save_errors(c, run.errors);
        if (cp.save) cp.save(c);
      },
      [&](const CheckpointState& c, long long step, double time) {
        run.errors = restore_errors(c, step, time, sampler ? dyn.error_times.size() : 0);
        next_error = run.errors.size();
        if (cp.restore) cp.restore(c, step, time);
      },
      verbose ? &std::cout : nullptr);
  const auto on_step = [&](const DynamicState& state) {
    // The first step at or past each error time; the exact motion at the step's own time.
    while (sampler && next_error < dyn.error_times.size() &&
           state.time >= dyn.error_times[next_error] * end * (1 - 1e-12)) {
      run.errors.push_back(
          timer.time("errors", [&] { return (*sampler)(state.d, state.v, state.time, *motion); }));
      ++next_error;
    }
    if (on_state) on_state(disc, model, state, timer);
  };
  run.result = integrate_dynamics(model, disc.nodes, d0, v0, ds, timer, on_step, checkpointing.hooks());
  return run;
}

/// A dynamic run: progress, frames of the fields (volume.pvd and surface.pvd), the probe at
/// every frame (probe.csv: every step), the errors against an exact motion, energy.csv and the
/// balance at the end, the reactions with the inertia (reactions.csv: at the energy records);
/// checkpoints every [output] checkpoint_every steps, or continuing from one.
int run_dynamics(const SolidScene& scene, const Checkpoints& checkpoints) {
  const SolidDynamics& dyn = *scene.dynamics;
  const SolidOutput& o = scene.output;
  checkpoints.restore_output(o.folder);
  const bool write = o.vtk && !o.fields.empty();
  std::vector<double> frame_times;  // frame k: volume_k.vtu and surface_k.vtu (k in 4 digits)
  const auto suffix = [](std::size_t k) { return fmt::format("_{:04d}", k); };
  const auto write_series = [&] {
    for (const char* kind : {"volume", "surface"}) {
      std::vector<std::pair<double, std::string>> series;
      for (std::size_t k = 0; k < frame_times.size(); ++k)
        series.emplace_back(frame_times[k], kind + suffix(k) + ".vtu");
      write_pvd(o.folder / (std::string(kind) + ".pvd"), series);
    }
  };
  std::optional<GalerkinQuadrature<3>> probe_at;
  ProbeHistory<3> probe;  // at t = 0 and after every step
  ReactionTable<3> reaction_table("time", essential_parts(scene.problem), true);
  std::optional<Reactions<3>> last_reactions;
  const double end = dyn.settings.end_time;
  const int energy_every = dyn.settings.energy_every;
  const auto on_state = [&](const Discretisation<3>& disc, const TotalLagrangian<3>& model,
                            const DynamicState& state, StageTimer& timer) {
    if (o.probe) {
      if (!probe_at) probe_at = sample_shape_functions(*disc.trial, std::vector<Point<3>>{*o.probe}, false);
      probe.emplace_back(state.time, displacement_at(*probe_at, 0, state.d));
    }
    // Reactions with the inertia at the steps of the energy records (the first and last steps
    // when there are none).
    const bool last = state.time >= end * (1 - 1e-12);
    if (state.step == 0 || last || (energy_every > 0 && state.step % energy_every == 0)) {
      Reactions<3> r = timer.time("reactions", [&] {
        Reactions<3> re = reactions(model, state.d, {1.0, state.time});
        re.inertia = nodal_resultant(state.inertia(), disc.nodes, state.d, re.current_arm);
        return re;
      });
      reaction_table.add(state.step, state.time, r);
      if (last) last_reactions = std::move(r);
    }
    // Frames at k end / frames (and t = 0): the first step at or past each.
    const auto wanted =
        dyn.frames > 0 ? static_cast<std::size_t>(std::floor(state.time / end * dyn.frames + 1e-9)) : 0;
    if (!(state.step == 0 || (dyn.frames > 0 && wanted >= frame_times.size()))) return;
    if (o.probe) {
      const Point<3>& u = probe.back().second;
      std::cout << fmt::format("  t = {:.6g}: probe u^h = ({:.9e}, {:.9e}, {:.9e})\n", state.time, u.x(),
                               u.y(), u.z());
    }
    frame_times.push_back(state.time);
    if (!write) return;
    timer.time("output", [&] {
      write_solid_fields(scene, disc, model, state.d, &state.v, suffix(frame_times.size() - 1));
      write_series();
    });
  };
  RunCheckpoints cp{&checkpoints,
                    [&](CheckpointState& c) {
                      c.put("frames", frame_times);
                      save_probe<3>(c, probe);
                      reaction_table.save(c);
                    },
                    [&](const CheckpointState& c, long long step, double time) {
                      // The frames written so far: their files came back with the output.
                      frame_times = c.times("frames", time, static_cast<std::size_t>(dyn.frames) + 1);
                      probe = restore_probe<3>(c, step, time, o.probe.has_value());
                      reaction_table.restore(c, step, time);
                    }};
  SolidDynamicRun run = simulate(scene, scene.settings, dyn.settings, true, on_state, cp);
  StageTimer& timer = run.timer;
  const DynamicsResult& r = run.result;
  std::cout << fmt::format(
      "  {} steps of dt = {:.6g}{}\n", r.steps, r.time_step,
      r.stability_limit ? fmt::format(" (stability limit {:.6g})", *r.stability_limit) : "");
  RunSummary summary("solid_dynamics", scene.file);
  summary.text("time_scheme", std::string(to_string(dyn.settings.scheme)));
  summary.number("nodes", static_cast<double>(run.nodes));
  summary.number("dofs", static_cast<double>(run.dofs));
  summary.number("time_step", r.time_step);
  summary.number("steps", r.steps);
  if (r.stability_limit) summary.number("stability_limit", *r.stability_limit);
  if (r.solver) summary.text("solver", r.solver->text());
  if (!r.energy.empty()) {
    std::string csv = "time,kinetic,strain,external_work,dissipated,balance\n";
    const EnergyRecord& first = r.energy.front();
    const double e0 = first.kinetic + first.strain;
    double scale = 0.0, worst = 0.0;
    for (const EnergyRecord& e : r.energy)
      scale = std::max({scale, e.kinetic, e.strain, std::abs(e.external_work)});
    for (const EnergyRecord& e : r.energy) {
      const double balance = e.kinetic + e.strain + e.dissipated - e.external_work - e0;
      worst = std::max(worst, std::abs(balance));
      csv += fmt::format("{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n", e.time, e.kinetic, e.strain,
                         e.external_work, e.dissipated, balance);
    }
    write_file_atomically(o.folder / "energy.csv", csv);
    std::cout << fmt::format(
        "  energy balance: largest |E_kin + E_strain + dissipated - work - E_0| {:.3e} of the "
        "largest energy {:.3e}; wrote energy.csv\n",
        worst, scale);
    summary.number("energy_balance_relative", scale > 0.0 ? worst / scale : 0.0);
  }
  if (!run.errors.empty()) {
    std::cout << fmt::format(
        "  {:>10} {:>12} {:>12} {:>12}   (RMS over the solid, independent Gauss cells)\n", "t",
        "displacement", "velocity", "stress");
    std::vector<RunSummary::Record> errors;
    for (const MotionErrors& e : run.errors) {
      std::cout << fmt::format("  {:10.6f} {:12.4e} {:12.4e} {:12.4e}\n", e.time, e.displacement, e.velocity,
                               e.stress);
      errors.push_back({{"time", e.time},
                        {"displacement", e.displacement},
                        {"velocity", e.velocity},
                        {"stress", e.stress}});
    }
    summary.records("errors", errors);
  }
  if (last_reactions) {
    std::cout << reaction_lines(*last_reactions);
    summarise_reactions(summary, *last_reactions);
  }
  write_file_atomically(o.folder / "reactions.csv", reaction_table.csv());
  std::cout << "  wrote reactions.csv\n";
  if (!probe.empty()) {
    std::string csv = "time,probe_ux,probe_uy,probe_uz\n";
    for (const auto& [t, u] : probe)
      csv += fmt::format("{:.9e},{:.9e},{:.9e},{:.9e}\n", t, u.x(), u.y(), u.z());
    write_file_atomically(o.folder / "probe.csv", csv);
    std::cout << "  wrote probe.csv\n";
  }
  if (write)
    std::cout << fmt::format("  wrote {} frames: open volume.pvd (or surface.pvd) in ParaView\n",
                             frame_times.size());
  std::cout << "stages:\n";
  print_stages(timer);
  summary.stages(timer);
  summary.write(o.folder);
  return 0;
}

/// The refinement study: every order at every spacing; errors and their rates with [exact],
/// else the probe's change (SPEC section 8); convergence.csv and its plots.
int converge(const SolidScene& scene) {
  const SolidStudy& st = *scene.study;
  if (scene.dynamics) {
    std::cout << fmt::format("mfree converge: {} ({} runs, {} thread(s))\n", scene.file.string(),
                             st.time.schemes.size() * st.spacings.size(), thread_count());
    const auto simulate_level = [&](double h, const DynamicsSettings& ds) {
      ElasticitySettings s = scene.settings;
      s.nodes.spacing = h;
      SolidDynamicRun run = simulate(scene, s, ds, false, {});
      return DynamicsLevel{h,
                           run.nodes,
                           run.dofs,
                           std::move(run.result),
                           std::move(run.errors),
                           run.timer.total_without("errors")};
    };
    dynamics_study(st.spacings, st.time, scene.dynamics->settings, simulate_level, scene.output.folder);
    return 0;
  }
  const std::optional<Point<3>> probe = st.probe ? st.probe : scene.output.probe;
  if (!scene.exact && !probe)
    throw InputError(
        fmt::format("{}: a study without an [exact] solution measures the displacement at a probe: give "
                    "[study] probe = [x, y, z] (or [output] probe)",
                    scene.file.string()));
  const std::size_t runs = st.orders.size() * st.spacings.size();
  std::cout << fmt::format("mfree converge: {} ({} runs, {} thread(s))\n", scene.file.string(), runs,
                           thread_count());
  std::string csv =
      "cloud,order,scheme,consistency,beta,spacing,nodes,dofs,quadrature_points,l2_displacement,energy,l2_"
      "stress,"
      "probe_uy,seconds,consistency_before,consistency_after,status\n";
  std::string table;
  std::size_t done = 0;
  const std::string_view cloud = to_string(scene.settings.nodes.kind);
  const std::string_view fix = to_string(scene.settings.consistency.value_or(Consistency::vci));
  const double beta = scene.problem.nitsche_beta;
  for (RKOrder order : st.orders) {
    std::optional<std::pair<double, SmallStrainErrors>> last;
    std::vector<std::pair<double, Point<3>>> probes;  // (h, u^h at the probe): the change between levels
    for (double h : st.spacings) {
      ElasticitySettings s = scene.settings;
      s.nodes.spacing = h;
      if (order != s.order) {
        s.order = order;
        s.support_factor = order == RKOrder::linear ? 2.0 : st.quadratic_factor;
      }
      s.quadrature_order = order;
      StageTimer timer;
      std::optional<SolidLevel> solved;
      try {
        solved = solve_level(scene, s, probe, timer, false, {}, {});
      } catch (const NumericalError& e) {
        // A study goes on past a run that fails (a sweep is meant to find where they do).
        const std::string line = fmt::format("{:<9} {:8.4f} FAILED: {}", to_string(order), h, e.what());
        table += line + "\n";
        csv += fmt::format("{},{},projected,{},{},{},,,,,,,,,,,{}\n", cloud, to_string(order), fix, beta, h,
                           csv_status(e.what()));
        std::cout << fmt::format("  [{}/{}] {}\n", ++done, runs, line) << std::flush;
        continue;
      }
      const SolidLevel& r = *solved;
      std::string line = fmt::format("{:<9} {:8.4f} {:8d}", to_string(order), h, r.dofs);
      if (r.errors) {
        std::string rates;
        if (last) {
          const double lr = std::log(last->first / h);
          rates = fmt::format("{:5.2f} {:5.2f}", std::log(last->second.l2 / r.errors->l2) / lr,
                              std::log(last->second.energy / r.errors->energy) / lr);
        }
        last.emplace(h, *r.errors);
        line += fmt::format(" {:10.3e} {:10.3e} {:11}", r.errors->l2, r.errors->energy, rates);
      }
      if (r.probe) {
        line += fmt::format(" {:>15.9e} {:>15.9e} {:>15.9e}", r.probe->x(), r.probe->y(), r.probe->z());
        if (!r.errors) {
          probes.emplace_back(h, *r.probe);
          const ProbeLevel p = probe_level(probes);
          line += fmt::format(" {:>10} {:>6}", p.change, p.rate);
        }
      }
      line += fmt::format(" {:8.3f}", r.seconds);
      table += line + "\n";
      csv += fmt::format("{},{},projected,{},{},{},{},{},{},{},{},,{},{:.6e},{:.3e},{:.3e},ok\n", cloud,
                         to_string(order), fix, beta, h, r.nodes, r.dofs, r.quadrature_points,
                         r.errors ? fmt::format("{:.9e}", r.errors->l2) : "",
                         r.errors ? fmt::format("{:.9e}", r.errors->energy) : "",
                         r.probe ? fmt::format("{:.12e}", r.probe->y()) : "", r.seconds, r.consistency_before,
                         r.consistency_after);
      std::cout << fmt::format("  [{}/{}] {}\n", ++done, runs, line) << std::flush;
    }
  }
  const std::filesystem::path csv_path = scene.output.folder / "convergence.csv";
  write_file_atomically(csv_path, csv);
  std::cout << fmt::format("\n{:<9} {:>8} {:>8}", "order", "h", "DOFs");
  if (scene.exact) std::cout << fmt::format(" {:>10} {:>10} {:>11}", "L2 disp", "energy", "rates (L2 E)");
  if (probe)
    std::cout << fmt::format(" {:>15} {:>15} {:>15}{}", "probe u_x", "u_y", "u_z",
                             scene.exact ? "" : fmt::format(" {:>10} {:>6}", "|change|", "rate"));
  std::cout << fmt::format(" {:>8}\n{}", "time [s]", table);
  if (probe)
    std::cout << fmt::format(
        "probe at ({:.6g}, {:.6g}, {:.6g}); time: discretisation and solve, not the errors\n", probe->x(),
        probe->y(), probe->z());
  std::cout << fmt::format("wrote {}\n", csv_path.filename().string());
  if (scene.exact) plot("plot_convergence.py", csv_path, scene.output.folder);
  return 0;
}

}  // namespace

int run_solid_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides, bool study,
                    const std::filesystem::path& restart) {
  SolidScene scene = read_solid_scene(file, study, overrides);
  if (!scene.dynamics && !restart.empty())
    throw InputError(fmt::format(
        "{}: --restart continues a [dynamics] run from its checkpoints; this scene is a static solve",
        file.string()));
  if (!study)
    std::cout << fmt::format("mfree run: {} (solid, {}, {} thread(s))\n", file.string(), scene.model,
                             thread_count());
  std::cout << describe_solid(scene.solid) << scene.describe_conditions();
  if (study) return in_staged_folder(scene.output.folder, [&] { return converge(scene); });
  if (!scene.dynamics) return in_staged_folder(scene.output.folder, [&] { return run(scene); });
  const Checkpoints checkpoints(scene.output.folder, scene.output.checkpoint_every,
                                scene_fingerprint(file, overrides), restart);
  return in_staged_folder(scene.output.folder, checkpoints, [&] { return run_dynamics(scene, checkpoints); });
}

}  // namespace mfree

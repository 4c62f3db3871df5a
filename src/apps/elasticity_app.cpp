#include "mfree/apps/elasticity_app.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <map>

#include "mfree/apps/probe_study.hpp"
#include "mfree/apps/report.hpp"
#include "mfree/apps/solid_app.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/io/csv.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/elasticity_output.hpp"
#include "mfree/io/elasticity_scene.hpp"
#include "mfree/io/reaction_output.hpp"
#include "mfree/io/run_summary.hpp"
#include "mfree/galerkin/stiffness_spectrum.hpp"

namespace mfree {

namespace {

int run_linear_statics(const ElasticityScene& scene) {
  const std::filesystem::path& path = scene.file;
  const std::optional<ExactElasticity> exact = scene.exact();
  std::cout << fmt::format("mfree run: {} ({} thread(s))\n", path.string(), thread_count());
  std::cout << scene.describe_conditions();
  ElasticitySettings s = scene.settings;
  s.progress = &std::cout;  // a large solve takes minutes: show each stage as it ends
  ElasticityResult r = solve_elasticity(scene.domain, s, exact ? &*exact : nullptr);
  r.timer.report_to(nullptr);
  std::cout << fmt::format("  {} nodes ({} DOFs), {} quadrature points ({}), {} RK, {} cloud, spacing {}\n",
                           r.nodes.size(), 2 * r.nodes.size(), r.quadrature.size(), to_string(s.scheme),
                           to_string(s.order), to_string(s.nodes.kind), s.nodes.spacing);
  std::cout << fmt::format(
      "  integration consistency defect: {:.2e} -> {:.2e} ({}{})\n  solver: {}\n", r.consistency_before,
      r.consistency_after,
      to_string(r.consistency),
      r.correction_solver ? ", node system: " + r.correction_solver->text() : "", r.solver.text());
  if (r.errors)
    std::cout << fmt::format(
        "  relative errors: L2 displacement {:.4e}, energy {:.4e}, L2 stress {:.4e}; strain energy {:.7g}\n",
        r.errors->l2_displacement, r.errors->energy, r.errors->l2_stress, r.errors->strain_energy);

  const Reactions<2> reactions =
      r.timer.time("reactions", [&] { return elastic_reactions(scene.domain, s, r); });
  std::cout << reaction_lines(reactions);
  for (const TipIntensity& t : r.tips)
    std::cout << (t.loaded_by.empty()
                      ? fmt::format(
                            "  crack '{}' tip ({:.6g}, {:.6g}): K_I = {:.6e}, K_II = {:.6e}, J = {:.6e} "
                            "(interaction integral, radius {:.4g})\n",
                            t.crack, t.frame.position.x(), t.frame.position.y(), t.k.k1, t.k.k2, t.k.j,
                            t.outer_radius)
                      : fmt::format(
                            "  crack '{}' tip ({:.6g}, {:.6g}): no K, its faces carry condition '{}' (the "
                            "interaction integral needs traction-free faces)\n",
                            t.crack, t.frame.position.x(), t.frame.position.y(), t.loaded_by));

  RunSummary summary("linear_statics", path);
  summarise_reactions(summary, reactions);
  if (!r.tips.empty()) {
    std::vector<RunSummary::Record> tips;
    for (const TipIntensity& t : r.tips)
      tips.push_back({{"x", t.frame.position.x()}, {"y", t.frame.position.y()}, {"k1", t.k.k1}, {"k2", t.k.k2},
                      {"j", t.k.j}, {"radius", t.outer_radius}});
    summary.records("crack_tips", tips);
  }
  if (scene.output.probe) {
    const Vec2 u = r.displacement({*scene.output.probe})[0];
    std::cout << fmt::format("  probe ({:.6g}, {:.6g}): u^h = ({:.9e}, {:.9e})\n", scene.output.probe->x(),
                             scene.output.probe->y(), u.x(), u.y());
    summary.numbers("probe_displacement", {u.x(), u.y()});
  }
  summary.number("nodes", static_cast<double>(r.nodes.size()));
  summary.number("dofs", 2.0 * static_cast<double>(r.nodes.size()));
  summary.number("quadrature_points", static_cast<double>(r.quadrature.size()));
  summary.number("consistency_before", r.consistency_before);
  summary.number("consistency_after", r.consistency_after);
  summary.text("solver", r.solver.text());
  if (r.correction_solver) summary.text("consistency_solver", r.correction_solver->text());
  {
    // Negative quadrature weights (quadratic RK on irregular quadrature clouds, SPEC 3).
    double negative = 0.0, most_negative = 0.0, largest = 0.0;
    for (double w : r.quadrature.weights) {
      negative += w < 0.0;
      most_negative = std::min(most_negative, w);
      largest = std::max(largest, w);
    }
    summary.number("negative_weights", negative);
    summary.number("most_negative_weight_relative", most_negative / largest);
  }
  if (r.errors) {
    summary.number("l2_displacement", r.errors->l2_displacement);
    summary.number("energy", r.errors->energy);
    summary.number("l2_stress", r.errors->l2_stress);
  }
  const OutputSettings& o = scene.output;
  if (o.eigenvalues > 0) {
    const StiffnessSpectrum sp = r.timer.time("stiffness eigenvalues", [&] {
      return stiffness_spectrum(s.problem, scene.domain, r, o.eigenvalues);
    });
    std::cout << fmt::format("  free stiffness: {} zero-energy modes (3 are rigid-body motions); smallest eigenvalues / "
                             "largest ({:.4e}):\n   ",
                             sp.zero_modes, sp.largest);
    for (double l : sp.smallest) std::cout << fmt::format(" {:.3e}", l);
    std::cout << '\n';
    summary.numbers("smallest_eigenvalues", sp.smallest);
    summary.number("largest_eigenvalue", sp.largest);
    summary.number("zero_modes", sp.zero_modes);
  }
  if (!o.fields.empty() && o.vtk) {
    const auto files = r.timer.time("output", [&] { return write_elasticity_fields(scene, r); });
    for (const auto& f : files) std::cout << fmt::format("  wrote {}\n", f.filename().string());
    std::cout << "  open field.vtu in ParaView for contour plots (see README)\n";
  } else {
    std::cout << "  no output fields asked for: stress recovery and field files skipped (summary.json only)\n";
  }
  std::cout << "stages:\n";
  print_stages(r.timer);
  summary.stages(r.timer);
  summary.write(o.folder);
  return 0;
}

int converge_linear_statics(const ElasticityScene& scene) {
  const std::filesystem::path& path = scene.file;
  const StudySettings& st = *scene.study;
  const std::optional<ExactElasticity> exact = scene.exact();
  const std::optional<Vec2> probe = st.probe ? st.probe : scene.output.probe;
  if (!exact && !probe)
    throw InputError(fmt::format("{}: a study without an [exact] solution measures the displacement at a probe: give "
                                 "[study] probe = [x, y] (or [output] probe)",
                                 path.string()));
  const std::size_t runs =
      st.clouds.size() * st.orders.size() * st.schemes.size() * st.betas.size() * st.spacings.size();
  std::cout << fmt::format("mfree converge: {} ({} runs, {} thread(s))\n", path.string(), runs,
                           thread_count());
  std::cout << scene.describe_conditions();

  std::string csv =
      "cloud,order,scheme,consistency,beta,spacing,nodes,dofs,quadrature_points,l2_displacement,energy,l2_stress,"
      "probe_uy,seconds,consistency_before,consistency_after,status\n";
  std::string table;
  std::size_t done = 0;
  for (CloudKind cloud : st.clouds)
    for (RKOrder order : st.orders)
      for (QuadratureScheme q : st.schemes)
        for (double beta : st.betas) {
          std::vector<std::pair<double, ElasticErrors>> series;
          std::vector<std::pair<double, Vec2>> probes;  // (h, u^h at the probe): studies without [exact]
          for (double h : st.spacings) {
            ElasticitySettings s = scene.settings;
            s.nodes.kind = cloud;
            s.nodes.spacing = h;
            s.order = order;
            s.scheme = q;
            s.problem.nitsche_beta = beta;
            const std::string_view fix = to_string(s.consistency.value_or(default_consistency(q)));
            if (order == RKOrder::quadratic) {
              s.support_factor = st.quadratic_factor;
              s.quadrature_order = RKOrder::quadratic;
              s.quadrature_factor = st.quadratic_factor;
              s.gauss_points = st.quadratic_gauss_points;
            }
            std::optional<ElasticityResult> solved;
            try {
              solved.emplace(solve_elasticity(scene.domain, s, exact ? &*exact : nullptr));
            } catch (const NumericalError& e) {
              // A study goes on past a run that fails (a sweep is meant to find where they do).
              const std::string line =
                  fmt::format("{:<9} {:<9} {:<11} {:<9} {:7.0f} {:8.4f} FAILED: {}", to_string(cloud),
                              to_string(order), to_string(q), fix, beta, h, e.what());
              table += line + "\n";
              csv += fmt::format("{},{},{},{},{},{},,,,,,,,,,,{}\n", to_string(cloud), to_string(order), to_string(q),
                                 fix, beta, h, csv_status(e.what()));
              std::cout << fmt::format("  [{}/{}] {}\n", ++done, runs, line) << std::flush;
              continue;
            }
            const ElasticityResult& r = *solved;
            double seconds = r.timer.total();  // the solve; the error measurement is not part of it
            for (const auto& [name, t] : r.timer.stages())
              if (name == "errors") seconds -= t;
            if (!exact) {
              // No exact solution: the probe values, their change between levels, the observed
              // rate of that change and the Richardson-extrapolated value (SPEC section 8).
              const Vec2 u = r.displacement({*probe})[0];
              probes.emplace_back(h, u);
              const ProbeLevel level = probe_level(probes);
              const std::string line = fmt::format("{:<9} {:<9} {:<11} {:<9} {:7.0f} {:8.4f} {:7d} {:>15.9e} {:>15.9e} "
                                                   "{:>10} {:>6} {:>16} {:8.3f}",
                                                   to_string(cloud), to_string(order), to_string(q), fix, beta, h,
                                                   2 * r.nodes.size(), u.x(), u.y(), level.change, level.rate,
                                                   level.extrapolated_y, seconds);
              table += line + "\n";
              csv += fmt::format("{},{},{},{},{},{},{},{},{},,,,{:.12e},{:.6e},{:.3e},{:.3e},ok\n", to_string(cloud),
                                 to_string(order), to_string(q), fix, beta, h, r.nodes.size(), 2 * r.nodes.size(),
                                 r.quadrature.size(), u.y(), seconds, r.consistency_before, r.consistency_after);
              std::cout << fmt::format("  [{}/{}] {}\n", ++done, runs, line) << std::flush;
              continue;
            }
            const double probe_uy = probe ? r.displacement({*probe})[0].y() : std::nan("");
            const ElasticErrors& e = *r.errors;
            std::string rates;
            if (!series.empty()) {
              const auto& [h0, e0] = series.back();
              const double lr = std::log(h0 / h);
              rates = fmt::format(
                  "{:5.2f} {:5.2f} {:5.2f}", std::log(e0.l2_displacement / e.l2_displacement) / lr,
                  std::log(e0.energy / e.energy) / lr, std::log(e0.l2_stress / e.l2_stress) / lr);
            }
            series.emplace_back(h, e);
            const std::string line = fmt::format(
                "{:<9} {:<9} {:<11} {:<9} {:7.0f} {:8.4f} {:7d} {:10.3e} {:10.3e} {:10.3e} {:17} {:11.7f} {:8.3f}",
                to_string(cloud), to_string(order), to_string(q), fix, beta, h, 2 * r.nodes.size(),
                e.l2_displacement, e.energy, e.l2_stress, rates, probe_uy, seconds);
            table += line + "\n";
            csv += fmt::format("{},{},{},{},{},{},{},{},{},{:.9e},{:.9e},{:.9e},{},{:.6e},{:.3e},{:.3e},ok\n",
                               to_string(cloud), to_string(order), to_string(q), fix, beta, h, r.nodes.size(),
                               2 * r.nodes.size(), r.quadrature.size(), e.l2_displacement, e.energy,
                               e.l2_stress, csv_number(probe_uy, "{:.9e}"), seconds, r.consistency_before,
                               r.consistency_after);
            std::cout << fmt::format("  [{}/{}] {}\n", ++done, runs, line) << std::flush;
          }
        }
  const std::filesystem::path csv_path = scene.output.folder / "convergence.csv";
  write_file_atomically(csv_path, csv);
  if (exact)
    std::cout << fmt::format(
        "\n{:<9} {:<9} {:<11} {:<9} {:>7} {:>8} {:>7} {:>10} {:>10} {:>10} {:>17} {:>11} {:>8}\n", "cloud", "order",
        "scheme", "correction", "beta", "h", "DOFs", "L2 disp", "energy", "L2 stress", "rates (L2 E S)", probe ? "probe u_y" : "-", "time [s]");
  else
    std::cout << fmt::format("\nno exact solution: u^h at the probe ({:.6g}, {:.6g}), |change| from the level before, "
                             "its observed rate and the Richardson-extrapolated u_y\n"
                             "{:<9} {:<9} {:<11} {:<9} {:>7} {:>8} {:>7} {:>15} {:>15} {:>10} {:>6} {:>16} {:>8}\n",
                             probe->x(), probe->y(), "cloud", "order", "scheme", "correction", "beta", "h", "DOFs", "u_x", "u_y",
                             "|change|", "rate", "extrapolated u_y", "time [s]");
  std::cout << table;
  if (st.reference) std::cout << fmt::format("reference probe u_y: {:.7f}\n", *st.reference);
  std::cout << fmt::format("wrote {}\n", csv_path.filename().string());
  // Plots: error against spacing and against run time (errors need an exact solution).
  if (exact) plot("plot_convergence.py", csv_path, scene.output.folder);
  return 0;
}

}  // namespace

int run_elasticity(const std::filesystem::path& path, const std::vector<std::string>& overrides,
                   const std::filesystem::path& restart) {
  ElasticityScene scene = read_elasticity_scene(path, false, overrides);
  if (!scene.dynamics && (!restart.empty() || scene.output.checkpoint_every > 0))
    throw InputError(fmt::format("{}: checkpoints and --restart are for dynamics and MPM runs; this scene is a static solve",
                                 path.string()));
  if (scene.dynamics) {
    const Checkpoints checkpoints(scene.output.folder, scene.output.checkpoint_every, scene_fingerprint(path, overrides),
                                  restart);
    return in_staged_folder(scene.output.folder, checkpoints, [&] { return run_dynamics(scene, &checkpoints); });
  }
  return in_staged_folder(scene.output.folder, [&] {
    return scene.nonlinear() ? run_static(scene) : run_linear_statics(scene);
  });
}

int converge_elasticity(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  ElasticityScene scene = read_elasticity_scene(path, true, overrides);
  if (scene.nonlinear() && !scene.dynamics)
    throw InputError(fmt::format("{}: mfree converge runs linear statics and dynamics; run a Newton scene with mfree run",
                                 path.string()));
  return in_staged_folder(scene.output.folder, [&] {
    return scene.dynamics ? converge_dynamics(scene) : converge_linear_statics(scene);
  });
}

}  // namespace mfree

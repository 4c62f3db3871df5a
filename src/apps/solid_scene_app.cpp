#include "mfree/apps/solid_scene_app.hpp"

#include <fmt/format.h>

#include <iostream>

#include "mfree/apps/report.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/galerkin/rigid_body_modes.hpp"
#include "mfree/galerkin/small_strain_elasticity.hpp"
#include "mfree/galerkin/small_strain_errors.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"
#include "mfree/io/run_summary.hpp"
#include "mfree/io/solid_scene.hpp"
#include "mfree/io/solid_scene_output.hpp"
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

int solve(const SolidScene& scene) {
  const Solid& solid = scene.solid;
  const ElasticitySettings& s = scene.settings;
  StageTimer timer;
  timer.report_to(&std::cout);
  const Discretisation<3> disc = discretise(solid, s, condition_parts(scene.problem.conditions), timer);
  TotalLagrangian<3> model(scene.problem, solid, disc.node_count(), disc.quadrature, disc.test(),
                           disc.boundary, disc.at_boundary);
  timer.report_to(nullptr);
  {
    // Statics must be well posed: the reference tangent may leave none of the six rigid-body
    // motions free.
    SparseMatrix k0 = model.zero_matrix();
    model.tangent(Eigen::VectorXd::Zero(model.dofs()), {}, k0);
    check_rigid_body_modes(k0, disc.nodes);
  }
  std::cout << fmt::format(
      "  {} nodes ({} DOFs), {} quadrature points, {} RK, {} cloud, spacing {}, consistency defect {:.2e} -> "
      "{:.2e}, {} tangent\n",
      disc.nodes.size(), model.dofs(), disc.quadrature.size(), to_string(s.order), to_string(s.nodes.kind),
      s.nodes.spacing, disc.consistency_before, disc.consistency_after,
      model.symmetric() ? "symmetric" : "non-symmetric");

  const SolidOutput& o = scene.output;
  std::optional<GalerkinQuadrature<3>> probe_at;
  if (o.probe) probe_at = sample_shape_functions(*disc.trial, std::vector<Point<3>>{*o.probe}, false);
  std::vector<RunSummary::Record> steps;
  const StaticSolution sol = solve_static(
      model, disc.nodes, scene.newton, timer, [&](const LoadStepRecord& step, const Eigen::VectorXd& d) {
        RunSummary::Record r{{"factor", step.factor},
                             {"iterations", static_cast<double>(step.history.size())},
                             {"cutbacks", static_cast<double>(step.cutbacks)}};
        std::string line =
            fmt::format("  load factor {:.6g}: {} Newton iteration(s){}", step.factor, step.history.size(),
                        step.cutbacks > 0 ? fmt::format(" after {} cut-back(s)", step.cutbacks) : "");
        if (probe_at) {
          const Point<3> u = displacement_at(*probe_at, 0, d);
          line += fmt::format(", probe u^h = ({:.9e}, {:.9e}, {:.9e})", u.x(), u.y(), u.z());
          r.insert(r.end(), {{"probe_ux", u.x()}, {"probe_uy", u.y()}, {"probe_uz", u.z()}});
        }
        if (model.has_history()) line += fmt::format(", plastic volume {:.6g}", model.plastic_area());
        std::cout << line << '\n';
        steps.push_back(std::move(r));
      });
  std::cout << fmt::format("  solver: {}\n", sol.solver.text());

  RunSummary summary("solid_statics", scene.file);
  summary.number("nodes", static_cast<double>(disc.nodes.size()));
  summary.number("dofs", static_cast<double>(model.dofs()));
  summary.number("quadrature_points", static_cast<double>(disc.quadrature.size()));
  summary.number("volume", solid.measure());
  summary.number("consistency_before", disc.consistency_before);
  summary.number("consistency_after", disc.consistency_after);
  summary.text("solver", sol.solver.text());
  summary.records("load_steps", steps);
  if (scene.exact) {
    const auto* law = std::get_if<LinearElastic>(&scene.problem.material);
    const SolidExact& ex = *scene.exact;
    // An independent rule: the solid's cells of the node spacing (tetrahedra clipped to them
    // where it is meshed), n^3 Gauss points on each piece.
    const int n = s.order == RKOrder::linear ? 3 : 4;
    const SmallStrainErrors e = timer.time("errors", [&] {
      return small_strain_errors(
          *disc.trial, sol.coefficients, gauss_cell_rule(solid, s.nodes.spacing, n),
          lame_constants(law->youngs_modulus, law->poisson_ratio),
          [&](const Point<3>& x) { return ex.displacement(x); },
          [&](const Point<3>& x) { return ex.gradient_at(x); });
    });
    std::cout << fmt::format("  relative errors: L2 displacement {:.4e}, energy {:.4e}\n", e.l2, e.energy);
    summary.number("l2_displacement", e.l2);
    summary.number("energy", e.energy);
  }
  if (o.vtk && !o.fields.empty()) {
    const auto files =
        timer.time("output", [&] { return write_solid_fields(scene, disc, model, sol.coefficients); });
    for (const auto& f : files) std::cout << fmt::format("  wrote {}\n", f.filename().string());
    if (!files.empty()) std::cout << "  open volume.vtu (or surface.vtu) in ParaView; warp by displacement\n";
  } else {
    std::cout << "  no output fields asked for: no field files (summary.json only)\n";
  }
  std::cout << "stages:\n";
  print_stages(timer);
  summary.stages(timer);
  summary.write(o.folder);
  return 0;
}

}  // namespace

int run_solid_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  SolidScene scene = read_solid_scene(file, overrides);
  std::cout << fmt::format("mfree run: {} (solid, {}, {} thread(s))\n", file.string(), scene.model,
                           thread_count());
  std::cout << describe_solid(scene.solid) << scene.describe_conditions();
  return in_staged_folder(scene.output.folder, [&] { return solve(scene); });
}

}  // namespace mfree

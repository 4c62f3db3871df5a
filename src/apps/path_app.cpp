#include "mfree/apps/path_app.hpp"

#include <fmt/format.h>

#include <iostream>

#include "mfree/apps/report.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"
#include "mfree/core/stage_timer.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/csv.hpp"
#include "mfree/io/run_summary.hpp"

namespace mfree {

namespace {

std::string matrix_text(const Mat2& f) {
  return fmt::format("[[{:.6g}, {:.6g}], [{:.6g}, {:.6g}]]", f(0, 0), f(0, 1), f(1, 0), f(1, 1));
}

/// One line of the table: t, F_yy, F_xy, sigma_xx, sigma_yy, sigma_xy, sigma_zz, alpha.
std::string table_line(const PathRecord& r) {
  return fmt::format("  {:>10.5g} {:>11.7f} {:>11.7f} {:>12.5e} {:>12.5e} {:>12.5e} {:>12.5e} {:>12.5e}\n", r.time,
                     r.deformation(1, 1), r.deformation(0, 1), r.cauchy(0, 0), r.cauchy(1, 1), r.cauchy(0, 1),
                     r.stress_zz, r.state.alpha);
}

constexpr const char* csv_header =
    "time,F_xx,F_xy,F_yx,F_yy,sigma_xx,sigma_yy,sigma_xy,sigma_zz,alpha,Ep_xx,Ep_yy,Ep_xy,Ep_zz,dissipation,"
    "stored_energy\n";
constexpr double csv_bytes_per_row = 16 * 20.0;  // 16 cells of "-1.234567890123e+05,"

/// The CSV of the rows; Ep_* is the plastic strain of plastic_strain() (materials/material.hpp).
std::string path_csv(const Material& law, const std::vector<PathRecord>& rows) {
  std::string out = csv_header;
  out.reserve(out.size() + static_cast<std::size_t>(csv_bytes_per_row) * rows.size());
  const auto cell = [&](double v, bool last = false) {
    out += csv_number(v, "{:.12e}");
    out += last ? '\n' : ',';
  };
  for (const PathRecord& r : rows) {
    const Mat2& f = r.deformation;
    const auto [e, e_zz] = plastic_strain(law, r.state);  // one measure for every kinematics
    for (const double v : {r.time, f(0, 0), f(0, 1), f(1, 0), f(1, 1), r.cauchy(0, 0), r.cauchy(1, 1), r.cauchy(0, 1),
                           r.stress_zz, r.state.alpha, e(0, 0), e(1, 1), e(0, 1), e_zz, r.state.dissipation})
      cell(v);
    cell(r.stored_energy, true);
  }
  return out;
}

}  // namespace

int run_path(const PathScene& scene) {
  const Material& m = scene.material.material;
  const StrainPathSettings& s = scene.path;
  std::cout << fmt::format("mfree run: {} (material-point path: {}, {}; {} increments to t = {:.6g})\n",
                           scene.file.string(), name(m), is_small_strain(m) ? "small strain" : "finite strain",
                           s.increments, s.end_time);
  std::cout << fmt::format("  F(0) = {}, F({:.6g}) = {}; {} rows recorded (every {} increment(s))\n",
                           matrix_text(scene.deformation(0.0)), s.end_time, matrix_text(scene.deformation(s.end_time)),
                           s.recorded(), s.record_every);
  check_memory(csv_bytes_per_row * static_cast<double>(s.recorded()), "path.csv");

  StageTimer timer;
  const std::vector<PathRecord> rows =
      timer.time("material-point path", [&] { return run_strain_path(m, scene.deformation_path(), s); });

  // The table: the first recorded row at or past every tenth of the path, and the last.
  std::cout << "  stresses (Cauchy) in the unit of the moduli; alpha: the equivalent plastic strain\n";
  std::cout << fmt::format("  {:>10} {:>11} {:>11} {:>12} {:>12} {:>12} {:>12} {:>12}\n", "t", "F_yy", "F_xy",
                           "sigma_xx", "sigma_yy", "sigma_xy", "sigma_zz", "alpha");
  int tenth = 0;  // the next tenth of the path to show
  const auto due = [&](int k) { return s.end_time * k / 10.0 * (1.0 - 1e-12); };
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const bool last = i + 1 == rows.size();
    if (!last && rows[i].time < due(tenth)) continue;
    std::cout << table_line(rows[i]);
    while (tenth <= 10 && due(tenth) <= rows[i].time) ++tenth;
  }
  const PathRecord& end = rows.back();
  std::cout << fmt::format("  at t = {:.6g}: plastic work {:.6e}, stored energy {:.6e} (per unit reference volume)\n",
                           end.time, end.state.dissipation, end.stored_energy);

  timer.time("output", [&] { write_file_atomically(scene.folder / "path.csv", path_csv(m, rows)); });
  std::cout << "  wrote path.csv\n";
  std::cout << "stages:\n";
  print_stages(timer);

  RunSummary summary("material_point_path", scene.file);
  summary.text("model", std::string(name(m)));
  summary.number("increments", s.increments);
  summary.number("recorded", static_cast<double>(rows.size()));
  summary.number("end_time", s.end_time);
  summary.number("increments_per_second", s.increments / timer.stages().front().second);
  summary.numbers("final_stress", {end.cauchy(0, 0), end.cauchy(1, 1), end.cauchy(0, 1), end.stress_zz});
  summary.number("final_alpha", end.state.alpha);
  summary.number("dissipation", end.state.dissipation);
  summary.number("stored_energy", end.stored_energy);
  summary.stages(timer);
  summary.write(scene.folder);
  return 0;
}

int run_path_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                   const std::filesystem::path& restart) {
  if (!restart.empty())
    throw InputError(fmt::format("{}: --restart is for dynamics and MPM runs; a material-point path has no checkpoints",
                                 file.string()));
  PathScene scene = read_path_scene(file, overrides);
  return in_staged_folder(scene.folder, [&] { return run_path(scene); });
}

}  // namespace mfree

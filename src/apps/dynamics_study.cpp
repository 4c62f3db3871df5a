#include "mfree/apps/dynamics_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "mfree/apps/report.hpp"
#include "mfree/io/atomic_file.hpp"

namespace mfree {

double energy_drift(const std::vector<EnergyRecord>& energy) {
  if (energy.empty()) return std::numeric_limits<double>::quiet_NaN();
  double scale = 0.0, drift = 0.0;
  for (const EnergyRecord& e : energy) {
    scale = std::max(scale, e.kinetic + e.strain);
    drift = std::max(drift, std::abs(e.total() - energy.front().total()));
  }
  return scale > 0.0 ? drift / scale : drift;
}

void dynamics_study(const std::vector<double>& spacings, const TimeStudy& time,
                    const DynamicsSettings& settings, const SimulateLevel& simulate,
                    const std::filesystem::path& folder) {
  const std::size_t runs = time.schemes.size() * spacings.size();
  std::string csv =
      "time_scheme,spacing,nodes,dofs,time_step,steps,seconds,time,displacement,velocity,stress,energy_"
      "drift\n";
  std::string table;
  std::size_t done = 0;
  std::string checks;
  for (std::size_t m = 0; m < time.schemes.size(); ++m) {
    const TimeScheme scheme = time.schemes[m];
    DynamicsSettings ds = settings;
    ds.scheme = scheme;
    ds.time_step = time.steps[m] > 0.0 ? std::optional<double>(time.steps[m]) : std::nullopt;
    std::vector<DynamicsLevel> series;
    for (double h : spacings) {
      DynamicsLevel run = simulate(h, ds);
      const double drift = energy_drift(run.result.energy);
      for (std::size_t k = 0; k < run.errors.size(); ++k) {
        const MotionErrors& e = run.errors[k];
        std::string rates;
        if (!series.empty()) {
          const MotionErrors& p = series.back().errors[k];
          const double lr = std::log(series.back().spacing / h);
          rates = fmt::format("{:5.2f} {:5.2f} {:5.2f}", std::log(p.displacement / e.displacement) / lr,
                              std::log(p.velocity / e.velocity) / lr, std::log(p.stress / e.stress) / lr);
        }
        const std::string line = fmt::format(
            "{:<18} {:8.5f} {:7d} {:10.3e} {:8.5f} {:10.3e} {:10.3e} {:10.3e} {:17} {:8.2f} {:>9}",
            to_string(scheme), h, run.dofs, run.result.time_step, e.time, e.displacement, e.velocity,
            e.stress, rates, run.seconds, std::isnan(drift) ? "off" : fmt::format("{:9.2e}", drift));
        table += line + "\n";
        if (k + 1 == run.errors.size())
          std::cout << fmt::format("  [{}/{}] {}\n", ++done, runs, line) << std::flush;
        // No energy record (energy_every = 0): an empty cell, not a NaN.
        csv += fmt::format("{},{},{},{},{:.6e},{},{:.6e},{:.9e},{:.9e},{:.9e},{:.9e},{}\n", to_string(scheme),
                           h, run.nodes, run.dofs, run.result.time_step, run.result.steps, run.seconds,
                           e.time, e.displacement, e.velocity, e.stress,
                           std::isnan(drift) ? "" : fmt::format("{:.3e}", drift));
      }
      series.push_back(std::move(run));
    }
    if (time.step_check) {
      // Space dominates when halving dt at the finest level leaves the errors nearly as they are.
      const DynamicsLevel& fine = series.back();
      DynamicsSettings half = ds;
      half.time_step = 0.5 * fine.result.time_step;
      const DynamicsLevel again = simulate(spacings.back(), half);
      double change = 0.0;
      for (std::size_t k = 0; k < fine.errors.size(); ++k) {
        const MotionErrors &a = fine.errors[k], &b = again.errors[k];
        change = std::max({change, std::abs(a.displacement - b.displacement) / a.displacement,
                           std::abs(a.velocity - b.velocity) / a.velocity,
                           std::abs(a.stress - b.stress) / a.stress});
      }
      const std::string line = fmt::format(
          "time-step check, {} at h = {}: dt {:.3e} -> {:.3e} changes the errors by at most {:.2f} %\n",
          to_string(scheme), spacings.back(), fine.result.time_step, again.result.time_step, 100.0 * change);
      checks += line;
      std::cout << "  " << line << std::flush;
    }
  }
  const std::filesystem::path csv_path = folder / "convergence.csv";
  write_file_atomically(csv_path, csv);
  std::cout << fmt::format("\n{:<18} {:>8} {:>7} {:>10} {:>8} {:>10} {:>10} {:>10} {:>17} {:>8} {:>9}\n",
                           "scheme", "h", "DOFs", "dt", "t", "RMS u", "RMS v", "RMS stress", "rates (u v s)",
                           "time [s]", "drift")
            << table << checks;
  std::cout << fmt::format("wrote {}\n", csv_path.filename().string());
  plot("plot_dynamics.py", csv_path, folder);
}

}  // namespace mfree

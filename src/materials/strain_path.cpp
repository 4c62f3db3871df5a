#include "mfree/materials/strain_path.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"

namespace mfree {

void StrainPathSettings::validate() const {
  if (!(end_time > 0.0) || !std::isfinite(end_time))
    throw InputError(fmt::format("material-point path: the end time must be positive and finite, got {}", end_time));
  if (increments < 1)
    throw InputError(fmt::format("material-point path: the number of increments must be at least 1, got {}", increments));
  if (record_every < 1)
    throw InputError(fmt::format("material-point path: record_every must be at least 1, got {}", record_every));
}

std::size_t StrainPathSettings::recorded() const {
  const auto n = static_cast<std::size_t>(increments), k = static_cast<std::size_t>(record_every);
  return n / k + 1 + (n % k != 0 ? 1 : 0);
}

std::vector<PathRecord> run_strain_path(const Material& m, const DeformationPath& path, const StrainPathSettings& s) {
  s.validate();
  const std::size_t rows = s.recorded();
  check_memory(static_cast<double>(rows) * sizeof(PathRecord),
               fmt::format("a material-point path of {} increments recording every {} ({} rows)", s.increments,
                           s.record_every, rows));
  std::vector<PathRecord> out;
  out.reserve(rows);
  MaterialState<2> state;  // virgin
  for (int n = 0; n <= s.increments; ++n) {
    // t_n = (t_end n) / N, not n dt: t_N = t_end exactly, and a turning point of the path at
    // a whole increment is met exactly (t_end = 3, N = 3000: t_1000 = 3000 / 3000 = 1).
    const double t = s.end_time * static_cast<double>(n) / static_cast<double>(s.increments);
    const auto failed = [&](const std::string& what) {
      return NumericalError(fmt::format("material-point path: increment {} of {} (t = {:.9g}): {}", n, s.increments, t, what));
    };
    const Mat2 f = path(t);
    if (!f.allFinite())
      throw failed(fmt::format("F = [[{}, {}], [{}, {}]] is not finite", f(0, 0), f(0, 1), f(1, 0), f(1, 1)));
    const MaterialUpdate<2> u = [&] {
      try {
        return update(m, f, state, false);
      } catch (const NumericalError& e) {
        throw failed(e.what());  // J <= 0, or a return mapping that did not converge
      }
    }();
    if (!u.stress.allFinite() || !std::isfinite(u.stress_zz))
      throw failed(fmt::format("the stress is not finite (P = [[{}, {}], [{}, {}]], sigma_zz = {}) at F = [[{}, {}], [{}, {}]]",
                               u.stress(0, 0), u.stress(0, 1), u.stress(1, 0), u.stress(1, 1), u.stress_zz, f(0, 0),
                               f(0, 1), f(1, 0), f(1, 1)));
    state = u.state;  // committed: the next increment starts from it
    if (n % s.record_every != 0 && n != s.increments) continue;
    PathRecord r;
    r.increment = n;
    r.time = t;
    r.deformation = f;
    r.first_piola = u.stress;
    r.cauchy = cauchy_stress(m, u.stress, f);
    r.stress_zz = u.stress_zz;
    r.state = state;
    // The plastic laws' energy() repeats the update from the committed state, which is
    // elastic at the same F: the energy 1/2 T : E_e of this increment's stress.
    r.stored_energy = energy(m, f, state);
    out.push_back(r);
  }
  return out;
}

}  // namespace mfree

#include "mfree/apps/probe_study.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mfree {

template <int dim>
ProbeLevel probe_level(const std::vector<std::pair<double, Point<dim>>>& levels) {
  ProbeLevel out;
  const std::size_t n = levels.size();
  if (n < 2) return out;
  const auto& [h, u] = levels[n - 1];
  const auto& [h1, u1] = levels[n - 2];
  out.change = fmt::format("{:.3e}", (u - u1).norm());
  if (n < 3) return out;
  const auto& [h2, u2] = levels[n - 3];
  const double p = std::log((u1 - u2).norm() / (u - u1).norm()) / std::log(h2 / h1);
  if (std::isfinite(p) && p > 0.0) {
    out.rate = fmt::format("{:.2f}", p);
    const Point<dim> extrapolated = u + (u - u1) / (std::pow(h1 / h, p) - 1.0);
    out.extrapolated_x = fmt::format("{:.9g}", extrapolated.x());
    out.extrapolated_y = fmt::format("{:.9g}", extrapolated.y());
    if constexpr (dim == 3) out.extrapolated_z = fmt::format("{:.9g}", extrapolated.z());
  }
  return out;
}

template ProbeLevel probe_level(const std::vector<std::pair<double, Point<2>>>&);
template ProbeLevel probe_level(const std::vector<std::pair<double, Point<3>>>&);

}  // namespace mfree

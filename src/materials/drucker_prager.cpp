#include "mfree/materials/drucker_prager.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "drucker_prager_return.hpp"
#include "mfree/core/error.hpp"

namespace mfree {

namespace {

/// 3 tan(a) / sqrt(9 + 12 tan^2 a) and 3 / sqrt(9 + 12 tan^2 a): the plane-strain match to
/// Mohr–Coulomb (de Souza Neto et al. 2008, eq. 6.121).
double slope(double angle) {
  const double t = std::tan(angle);
  return 3.0 * t / std::sqrt(9.0 + 12.0 * t * t);
}
double intercept(double angle) {
  const double t = std::tan(angle);
  return 3.0 / std::sqrt(9.0 + 12.0 * t * t);
}

}  // namespace

double DruckerPrager::eta() const { return slope(friction_angle); }
double DruckerPrager::xi() const { return intercept(friction_angle); }
double DruckerPrager::eta_bar() const { return slope(dilatancy_angle); }

double DruckerPrager::largest_mean_stress() const {
  return eta() > 0.0 ? std::min(tension_cutoff, xi() * cohesion / eta()) : tension_cutoff;
}

void DruckerPrager::validate() const {
  if (!(friction_angle >= 0.0 && friction_angle < 0.5 * std::numbers::pi))
    throw InputError(fmt::format("Drucker–Prager: the friction angle must lie in [0, 90) degrees, got {} degrees",
                                 friction_angle * 180.0 / std::numbers::pi));
  if (!(dilatancy_angle >= 0.0 && dilatancy_angle <= friction_angle))
    throw InputError(fmt::format("Drucker–Prager: the dilatancy angle must lie in [0, friction angle], got {} degrees",
                                 dilatancy_angle * 180.0 / std::numbers::pi));
  if (!(cohesion >= 0.0) || !std::isfinite(cohesion))
    throw InputError(fmt::format("Drucker–Prager: the cohesion must be >= 0, got {}", cohesion));
  if (eta() == 0.0 && !(cohesion > 0.0))
    throw InputError("Drucker–Prager: with a zero friction angle the cohesion must be positive");
  if (std::isnan(tension_cutoff)) throw InputError("Drucker–Prager: the tension cutoff is not a number");
}

template double DruckerPrager::energy(const Tensor2<2>&, const MaterialState<2>&) const;
template MaterialUpdate<2> DruckerPrager::update(const Tensor2<2>&, const MaterialState<2>&, bool) const;

}  // namespace mfree

#include "mfree/materials/drucker_prager.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mfree/core/error.hpp"
#include "plastic_update.hpp"

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

/// The return of drucker_prager.hpp in the scalar type S.
struct DPReturn {
  const DruckerPrager& law;

  template <class S>
  plastic::Sym<S> return_map(const plastic::Sym<S>& trial, const MaterialState&, S& dalpha) const {
    const double g = law.lame.mu, k = law.lame.lambda + 2.0 * law.lame.mu / 3.0;
    const double eta = law.eta(), eta_bar = law.eta_bar(), xi_c = law.xi() * law.cohesion;
    const double p_max = law.largest_mean_stress();
    const S p_tr = trial.trace() / 3.0;
    const plastic::Sym<S> s_tr = trial.deviator();
    const S q_tr = plastic::safe_sqrt(S(0.5 * plastic::dot(s_tr, s_tr)));  // sqrt(J2^tr)
    const S f_tr = q_tr + eta * p_tr - xi_c;
    const plastic::Sym<S> unit{S(1.0), S(1.0), S(0.0), S(1.0)};
    plastic::Sym<S> out = trial;
    if (plastic::value(f_tr) <= 0.0 && plastic::value(p_tr) <= p_max) return trial;  // 1. elastic
    bool done = false;
    if (plastic::value(f_tr) > 0.0) {  // 2. the cone
      const S dgamma = f_tr / (g + k * eta * eta_bar);
      const S q = q_tr - g * dgamma;
      const S p = p_tr - k * eta_bar * dgamma;
      if (plastic::value(q) >= 0.0 && plastic::value(p) <= p_max) {
        out = (q / q_tr) * s_tr + p * unit;
        done = true;
      }
    }
    if (!done) {  // 3. the cutoff plane, its corner with the cone, or the apex
      const double q_max = std::max(0.0, xi_c - eta * p_max);
      const plastic::Sym<S> s = plastic::value(q_tr) <= q_max ? s_tr : S(q_max / q_tr) * s_tr;
      out = s + S(p_max) * unit;
    }
    const plastic::Sym<S> dp = plastic::elastic_strain(law.lame, trial - out);
    dalpha = plastic::safe_sqrt(plastic::dot(dp, dp));
    return out;
  }
};

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

double DruckerPrager::energy(const Mat2& f, const MaterialState& state) const {
  return plastic::stored_energy(DPReturn{*this}, lame, kinematics, f, state);
}

MaterialUpdate DruckerPrager::update(const Mat2& f, const MaterialState& state, bool with_tangent) const {
  (void)checked_jacobian(f, "Drucker–Prager");
  return plastic::evaluate(DPReturn{*this}, lame, kinematics, f, state, with_tangent);
}

}  // namespace mfree

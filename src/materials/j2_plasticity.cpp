#include "mfree/materials/j2_plasticity.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mfree/core/error.hpp"
#include "plastic_update.hpp"

namespace mfree {

namespace {

/// The radial return of j2_plasticity.hpp in the scalar type S.
struct J2Return {
  const J2Plasticity& law;

  /// k(alpha) and dk/dalpha in S.
  template <class S>
  void flow(const S& alpha, S& k, S& dk) const {
    using std::exp;
    k = law.yield_stress + law.isotropic_modulus * alpha;
    dk = S(law.isotropic_modulus);
    if (law.saturation_stress > 0.0 && law.saturation_rate > 0.0) {
      const S e = exp(-law.saturation_rate * alpha);
      k += (law.saturation_stress - law.yield_stress) * (1.0 - e);
      dk += (law.saturation_stress - law.yield_stress) * law.saturation_rate * e;
    }
  }

  template <class S>
  plastic::Sym<S> return_map(const plastic::Sym<S>& trial, const MaterialState& n, S& dalpha) const {
    const double two_mu = 2.0 * law.lame.mu, c = std::sqrt(2.0 / 3.0);
    const double kin = 2.0 / 3.0 * law.kinematic_modulus;
    const plastic::Sym<S> back = S(kin) * plastic::sym_of<S>(n);  // B_n = 2/3 H_kin E_p,n (deviatoric)
    const plastic::Sym<S> xi = trial.deviator() - back;
    const S norm = plastic::safe_sqrt(plastic::dot(xi, xi));
    S k, dk;
    flow(S(n.alpha), k, dk);
    if (plastic::value(norm - c * k) <= 0.0) return trial;  // elastic
    // |xi^tr| - (2 mu + 2/3 H_kin) dgamma - sqrt(2/3) k(alpha_n + sqrt(2/3) dgamma) = 0 by
    // Newton (one step for linear hardening), one more step past convergence so that the
    // derivatives of dual numbers are those of the converged root.
    S dgamma(0.0);
    const double scale = plastic::value(norm);
    int extra = 0;
    for (int it = 0; it < 60 && extra < 2; ++it) {
      flow(S(n.alpha + c * dgamma), k, dk);
      const S r = norm - (two_mu + kin) * dgamma - c * k;
      dgamma += r / (two_mu + kin + 2.0 / 3.0 * dk);
      if (std::abs(plastic::value(r)) <= 1e-13 * scale) ++extra;
    }
    if (extra == 0)
      throw NumericalError(fmt::format("J2 plasticity: the return mapping did not converge (|xi^tr| = {:.6g})", scale));
    dalpha = c * dgamma;
    return trial - (two_mu * dgamma / norm) * xi;
  }
};

}  // namespace

double J2Plasticity::flow_stress(double alpha) const {
  double k, dk;
  J2Return{*this}.flow(alpha, k, dk);
  return k;
}

void J2Plasticity::validate() const {
  if (kinematics == Kinematics::multiplicative && kinematic_modulus != 0.0)
    throw InputError("J2 plasticity: kinematic hardening needs kinematics = \"logarithmic\" or \"small_strain\" (the "
                     "multiplicative state holds C_p^-1, not a plastic strain for the back stress)");
  if (!(yield_stress > 0.0) || !std::isfinite(yield_stress))
    throw InputError(fmt::format("J2 plasticity: the yield stress must be positive, got {}", yield_stress));
  if (!(isotropic_modulus >= 0.0) || !(kinematic_modulus >= 0.0) || !(saturation_rate >= 0.0))
    throw InputError(fmt::format("J2 plasticity: hardening moduli and the saturation rate must be >= 0, got {}, {}, {}",
                                 isotropic_modulus, kinematic_modulus, saturation_rate));
  if (saturation_stress != 0.0 && !(saturation_stress >= yield_stress))
    throw InputError(fmt::format("J2 plasticity: the saturation stress {} is below the yield stress {}",
                                 saturation_stress, yield_stress));
}

double J2Plasticity::energy(const Mat2& f, const MaterialState& state) const {
  return plastic::stored_energy(J2Return{*this}, lame, kinematics, f, state);
}

MaterialUpdate J2Plasticity::update(const Mat2& f, const MaterialState& state, bool with_tangent) const {
  (void)checked_jacobian(f, "J2 plasticity");
  return plastic::evaluate(J2Return{*this}, lame, kinematics, f, state, with_tangent);
}

}  // namespace mfree

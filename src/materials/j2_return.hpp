#pragma once
// The return map of J2 plasticity (its law in j2_plasticity.hpp) and the update that wraps it, for
// both dimensions. Private to src/materials: j2_plasticity.cpp instantiates the plane update,
// j2_plasticity_solid.cpp the 3D one. Two translation units, so that the 3D code does
// not take the compiler's inlining budget from the plane update (in one unit the plane
// tangent took 50 % longer).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/materials/j2_plasticity.hpp"
#include "plastic_update.hpp"

namespace mfree {

namespace plastic {
// Internal linkage in each unit that includes it: the compiler then sees every call of the
// update's templates and inlines as it did with the return map private to one file.
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

  /// T: a plane (plastic::Sym) or 3D (plastic::Sym3) symmetric tensor.
  template <class T, int dim>
  T return_map(const T& trial, const MaterialState<dim>& n, typename T::Scalar& dalpha) const {
    using S = typename T::Scalar;
    const double two_mu = 2.0 * law.lame.mu, c = std::sqrt(2.0 / 3.0);
    const double kin = 2.0 / 3.0 * law.kinematic_modulus;
    const T back = S(kin) * plastic::sym_of<S>(n);  // B_n = 2/3 H_kin E_p,n (deviatoric)
    const T xi = trial.deviator() - back;
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
      throw NumericalError(
          fmt::format("J2 plasticity: the return mapping did not converge (|xi^tr| = {:.6g})", scale));
    dalpha = c * dgamma;
    return trial - (two_mu * dgamma / norm) * xi;
  }
};

}  // namespace
}  // namespace plastic

template <int dim>
double J2Plasticity::energy(const Tensor2<dim>& f, const MaterialState<dim>& state) const {
  return plastic::stored_energy(plastic::J2Return{*this}, lame, kinematics, f, state);
}

template <int dim>
MaterialUpdate<dim> J2Plasticity::update(const Tensor2<dim>& f, const MaterialState<dim>& state,
                                         bool with_tangent) const {
  (void)checked_jacobian(f, "J2 plasticity");
  return plastic::evaluate(plastic::J2Return{*this}, lame, kinematics, f, state, with_tangent);
}

}  // namespace mfree

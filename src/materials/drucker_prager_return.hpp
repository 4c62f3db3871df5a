#pragma once
// The return map of Drucker–Prager (its law in drucker_prager.hpp) and the update that wraps it, for
// both dimensions. Private to src/materials: drucker_prager.cpp instantiates the plane update,
// drucker_prager_solid.cpp the 3D one. Two translation units, so that the 3D code does
// not take the compiler's inlining budget from the plane update (in one unit the plane
// tangent took 50 % longer).

#include <algorithm>
#include <cmath>

#include "mfree/materials/drucker_prager.hpp"
#include "plastic_update.hpp"

namespace mfree {

namespace plastic {
// Internal linkage in each unit that includes it: the compiler then sees every call of the
// update's templates and inlines as it did with the return map private to one file.
namespace {

/// The return of drucker_prager.hpp in the scalar type S.
struct DPReturn {
  const DruckerPrager& law;

  /// T: a plane (plastic::Sym) or 3D (plastic::Sym3) symmetric tensor.
  template <class T, int dim>
  T return_map(const T& trial, const MaterialState<dim>&, typename T::Scalar& dalpha) const {
    using S = typename T::Scalar;
    const double g = law.lame.mu, k = law.lame.lambda + 2.0 * law.lame.mu / 3.0;
    const double eta = law.eta(), eta_bar = law.eta_bar(), xi_c = law.xi() * law.cohesion;
    const double p_max = law.largest_mean_stress();
    const S p_tr = trial.trace() / 3.0;
    const T s_tr = trial.deviator();
    const S q_tr = plastic::safe_sqrt(S(0.5 * plastic::dot(s_tr, s_tr)));  // sqrt(J2^tr)
    const S f_tr = q_tr + eta * p_tr - xi_c;
    const T unit = T::identity();
    T out = trial;
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
      const T s = plastic::value(q_tr) <= q_max ? s_tr : S(q_max / q_tr) * s_tr;
      out = s + S(p_max) * unit;
    }
    const T dp = plastic::elastic_strain(law.lame, trial - out);
    dalpha = plastic::safe_sqrt(plastic::dot(dp, dp));
    return out;
  }
};

}  // namespace
}  // namespace plastic

template <int dim>
double DruckerPrager::energy(const Tensor2<dim>& f, const MaterialState<dim>& state) const {
  return plastic::stored_energy(plastic::DPReturn{*this}, lame, kinematics, f, state);
}

template <int dim>
MaterialUpdate<dim> DruckerPrager::update(const Tensor2<dim>& f, const MaterialState<dim>& state,
                                          bool with_tangent) const {
  (void)checked_jacobian(f, "Drucker–Prager");
  return plastic::evaluate(plastic::DPReturn{*this}, lame, kinematics, f, state, with_tangent);
}

}  // namespace mfree

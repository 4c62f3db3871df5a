#pragma once
// Drucker–Prager plasticity for granular and geomaterials (perfectly plastic), with a tension
// cutoff and associative or non-associative flow, in plane strain; the same strain spaces,
// stress mapping and consistent tangent as J2 (j2_plasticity.hpp).
//
// With p = tr T / 3 (tension positive), s = dev T and sqrt(J2) = |s| / sqrt(2)
// (de Souza Neto, Peric & Owen 2008, section 8.3):
//
//   cone     f = sqrt(J2) + eta p - xi c <= 0,    flow potential sqrt(J2) + eta_bar p
//   cutoff   p <= p_t  (p_t <= xi c / eta, the apex; by default the apex itself)
//
// matched to Mohr–Coulomb in plane strain: eta = 3 tan(phi) / sqrt(9 + 12 tan^2 phi),
// xi = 3 / sqrt(9 + 12 tan^2 phi), eta_bar the same of the dilatancy angle psi (psi = phi:
// associative). Return mapping (K the bulk, G the shear modulus):
//
//   1. elastic when f^tr <= 0 and p^tr <= p_t;
//   2. to the cone: dgamma = f^tr / (G + K eta eta_bar), s = (1 - G dgamma / sqrt(J2^tr)) s^tr,
//      p = p^tr - K eta_bar dgamma, when that leaves sqrt(J2) >= 0 and p <= p_t;
//   3. otherwise to the cutoff p = p_t, with sqrt(J2) limited to xi c - eta p_t: the plane of
//      the cutoff, its corner with the cone, or (p_t at the apex) the apex itself.
//
// The plastic strain is dE_p = D^-1 : (T^tr - T) on every branch; alpha sums |dE_p|.

#include "mfree/materials/material_state.hpp"

namespace mfree {

struct DruckerPrager {
  Lame lame;
  double friction_angle = 0.0;   ///< phi [rad], in [0, pi/2)
  double dilatancy_angle = 0.0;  ///< psi [rad], in [0, phi] (psi = phi: associative)
  double cohesion = 0.0;         ///< c >= 0 [Pa]
  double tension_cutoff = 1e300; ///< p_t [Pa]; above the apex xi c / eta it is the apex
  Kinematics kinematics = Kinematics::multiplicative;

  [[nodiscard]] double eta() const;      ///< of phi
  [[nodiscard]] double xi() const;       ///< of phi
  [[nodiscard]] double eta_bar() const;  ///< of psi
  /// The largest mean stress: min(p_t, xi c / eta) (the apex, for phi = 0: p_t).
  [[nodiscard]] double largest_mean_stress() const;
  /// InputError for angles out of range, a negative cohesion or psi > phi.
  void validate() const;
  template <int dim>
  [[nodiscard]] MaterialUpdate<dim> update(const Tensor2<dim>& f, const MaterialState<dim>& state,
                                           bool with_tangent) const;
  /// The stored (elastic) energy 1/2 T : E_e per unit reference volume after that update.
  template <int dim>
  [[nodiscard]] double energy(const Tensor2<dim>& f, const MaterialState<dim>& state) const;
};

}  // namespace mfree

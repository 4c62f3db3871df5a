#pragma once
// Von Mises (J2) plasticity by radial return (seed 004; Simo & Hughes 1998, Box 3.2), in plane
// strain, with isotropic and linear kinematic hardening.
//
// Finite strain, Kinematics::multiplicative (the default): F = F_e F_p, the same return on the
// Eulerian Hencky strain 1/2 ln b_e and the Kirchhoff stress (Simo 1992; isotropic hardening
// only: its state holds C_p^-1, not a plastic strain for a back stress).
// Kinematics::logarithmic, the Lagrangian logarithmic strain space (Miehe, Apel & Lambrecht 2002):
// E = 1/2 ln C, C = F^T F, an additive split E = E_e + E_p, the stress T = lambda tr(E_e) 1 +
// 2 mu E_e conjugate to E, and the second Piola–Kirchhoff stress S = T : 2 dE/dC (P = F S).
// The return in E-space is the textbook small-strain one, so the model is objective, exact
// for large rotations, and reduces to the textbook radial return at small strain (with
// Kinematics::small_strain it is that return, on eps = sym(F) - I, P = sigma):
//
//   xi^tr = dev T^tr - B_n,  B = 2/3 H_kin E_p (linear kinematic hardening, Prager)
//   f^tr  = |xi^tr| - sqrt(2/3) k(alpha_n),  k(alpha) = sigma_y + H_iso alpha
//                                                     + (sigma_inf - sigma_y)(1 - exp(-delta alpha))
//   plastic (f^tr > 0): n = xi^tr / |xi^tr|, dgamma from the scalar equation
//     |xi^tr| - (2 mu + 2/3 H_kin) dgamma - sqrt(2/3) k(alpha_n + sqrt(2/3) dgamma) = 0
//   (closed form for linear hardening, Newton otherwise), E_p += dgamma n,
//   alpha += sqrt(2/3) dgamma, T = T^tr - 2 mu dgamma n.
//
// The tangent is the consistent (algorithmic) one: the exact derivative of the update with
// respect to F, by forward-mode automatic differentiation of the same code. Units: stresses
// and moduli in Pa, strains dimensionless.

#include <Eigen/Core>

#include "mfree/materials/material_state.hpp"

namespace mfree {

struct J2Plasticity {
  Lame lame;
  double yield_stress = 0.0;       ///< sigma_y (uniaxial) > 0
  double isotropic_modulus = 0.0;  ///< H_iso >= 0 (linear isotropic hardening)
  double saturation_stress = 0.0;  ///< sigma_inf >= sigma_y of the saturation law; 0: none
  double saturation_rate = 0.0;    ///< delta >= 0 of the saturation law
  double kinematic_modulus = 0.0;  ///< H_kin >= 0 (linear kinematic hardening)
  Kinematics kinematics = Kinematics::multiplicative;

  /// The uniaxial flow stress k(alpha) (see above).
  [[nodiscard]] double flow_stress(double alpha) const;
  /// InputError for a non-positive yield stress, negative moduli or a saturation stress below
  /// the yield stress.
  void validate() const;
  /// P, sigma_zz and the state after F; with_tangent: the consistent tangent too.
  /// NumericalError for J <= 0.
  template <int dim>
  [[nodiscard]] MaterialUpdate<dim> update(const Tensor2<dim>& f, const MaterialState<dim>& state,
                                           bool with_tangent) const;
  /// The stored (elastic) energy 1/2 T : E_e per unit reference volume after that update.
  template <int dim>
  [[nodiscard]] double energy(const Tensor2<dim>& f, const MaterialState<dim>& state) const;
};

}  // namespace mfree

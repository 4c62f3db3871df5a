#pragma once
// The history of one material point, and what an update of a law with history returns.
//
// A law with history maps (F_{n+1}, state_n) -> (P_{n+1}, A = dP/dF, state_{n+1}). The state is
// a small fixed-size value (no heap), owned by the solver in its per-point arrays (the
// Galerkin solver's quadrature points, the MPM's particles): the solver keeps state_n while it
// iterates on F_{n+1} and commits state_{n+1} once the step is accepted (a Newton cut-back
// simply keeps state_n). The elastic laws have no history and leave it as it is.
//
// The plastic part is a symmetric 3 x 3 tensor: the plastic strain E_p (small strain,
// Lagrangian logarithmic strain), or C_p^-1 - I (multiplicative, the default;
// src/materials/plastic_update.hpp). In 3D it is the dim x dim block; in plane strain
// (dim = 2) the in-plane block and the out-of-plane component (xz, yz are zero).

#include "mfree/core/types.hpp"
#include "mfree/materials/finite_strain.hpp"

namespace mfree {

/// How a law with history measures strain: the small strain eps = sym(F) - I (P = sigma, not
/// objective); the Lagrangian logarithmic strain E = 1/2 ln C, C = F^T F, split additively
/// (objective; for moderate strains: under large shear the push-forward of its stress loses
/// the shear part the return bounds, sigma_xy / sigma_yy of a flowing soil falls from 0.48 at
/// shear 1 to 0.07 at shear 10); or multiplicative (the default): F = F_e F_p with the Eulerian Hencky strain 1/2 ln b_e and the Kirchhoff
/// stress (Simo 1992; the state's plastic_strain holds C_p^-1 - I): the yield condition
/// bounds the physical stress at any accumulated shear (MPM flows, granular runout).
enum class Kinematics { small_strain, logarithmic, multiplicative };

template <int dim>
struct MaterialState {
  Tensor2<dim> plastic_strain = Tensor2<dim>::Zero();  ///< E_p (symmetric); multiplicative: C_p^-1 - I
  double plastic_strain_zz = 0.0;      ///< E_p,zz: the out-of-plane plastic strain (dim = 2; 0 in 3D)
  double alpha = 0.0;                  ///< equivalent plastic strain sum sqrt(2/3) |dE_p| (J2), or sum |dE_p|
  double dissipation = 0.0;            ///< plastic work sum T : dE_p per unit reference volume [J/m^3]
};

/// One update of a law: the stress of F_{n+1}, the state after it and, when asked, the
/// consistent (algorithmic) tangent of that stress with respect to F_{n+1}.
template <int dim>
struct MaterialUpdate {
  Tensor2<dim> stress = Tensor2<dim>::Zero();  ///< first Piola–Kirchhoff P (small strain: sigma)
  double stress_zz = 0.0;    ///< out-of-plane Cauchy stress sigma_zz (plane strain; 0 in 3D)
  MaterialState<dim> state;  ///< the state after the update (commit it when the step is accepted)
  Tangent<dim> tangent = Tangent<dim>::Zero();  ///< dP/dF, A(dim i + J, dim k + L); only when asked for
};

}  // namespace mfree

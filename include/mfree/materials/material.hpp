#pragma once
// The materials both solvers take, as one value type: a variant of the laws, chosen by a
// scene's material model.
//
//   LinearElastic       small strain, plane stress or plane strain, 3D (not objective)
//   StVenantKirchhoff   plane strain, 3D
//   NeoHookean          compressible, plane strain, 3D (SPEC section 5)
//   J2Plasticity        von Mises plasticity, radial return (j2_plasticity.hpp)
//   DruckerPrager       pressure-dependent plasticity with a tension cutoff (drucker_prager.hpp)
//
// One interface for every law, in the plane (dim = 2) and in 3D: update(m, F_{n+1}, state_n)
// -> (P, sigma_zz, energy, state_{n+1}, and A = dP/dF when asked), material_state.hpp; the elastic laws leave
// the state as it is. The dispatch names every law (a law missing from it does not compile). stress(),
// tangent() and energy() are the response of a point without history: the elastic laws, and the reference
// state of any law (wave speeds, the reference tangent).

#include <functional>
#include <string_view>
#include <utility>
#include <variant>

#include "mfree/core/name_table.hpp"
#include "mfree/materials/drucker_prager.hpp"
#include "mfree/materials/j2_plasticity.hpp"
#include "mfree/materials/linear_elastic.hpp"
#include "mfree/materials/material_state.hpp"
#include "mfree/materials/neo_hookean.hpp"
#include "mfree/materials/st_venant_kirchhoff.hpp"

namespace mfree {

using Material = std::variant<LinearElastic, StVenantKirchhoff, NeoHookean, J2Plasticity, DruckerPrager>;
/// The law at a reference position X (a body of several materials: its region's).
template <int dim>
using MaterialAt = std::function<const Material&(const Point<dim>& x)>;

/// The update of any law (above), in dim = 2 (plane) or 3 dimensions. NumericalError for
/// J <= 0 (finite-strain laws); InputError for a plane-only law in 3D (plane stress, the
/// logarithmic kinematics).
template <int dim>
MaterialUpdate<dim> update(const Material& m, const Tensor2<dim>& f, const MaterialState<dim>& state,
                           bool with_tangent);
/// The stored (elastic) energy per unit reference volume at F after the state (W(F) of the
/// elastic laws, 1/2 T : E_e of the plastic ones); the plastic work is state.dissipation.
template <int dim>
double energy(const Material& m, const Tensor2<dim>& f, const MaterialState<dim>& state);
/// True for the laws whose response depends on their state (J2, Drucker–Prager).
bool has_history(const Material& m);
/// True when the tangent A = dP/dF has major symmetry, A_iJkL = A_kLiJ: the hyperelastic laws
/// and J2 (associative flow). False for Drucker–Prager (non-associative flow, the apex and
/// cutoff returns): a stiffness assembled from it is not symmetric.
bool has_symmetric_tangent(const Material& m);

template <int dim>
double energy(const Material& m, const Tensor2<dim>& f) {
  return energy(m, f, MaterialState<dim>{});
}
/// First Piola–Kirchhoff stress P (force per reference area) of a point without history.
template <int dim>
Tensor2<dim> stress(const Material& m, const Tensor2<dim>& f) {
  return update(m, f, MaterialState<dim>{}, false).stress;
}
template <int dim>
Tangent<dim> tangent(const Material& m, const Tensor2<dim>& f) {
  return update(m, f, MaterialState<dim>{}, true).tangent;
}
/// The plastic strain a state holds (2D: in-plane block and zz; 3D: the tensor and 0), as one
/// measure for every kinematics: E_p (small strain, logarithmic), or the Lagrangian plastic
/// log strain 1/2 ln C_p = -1/2 ln C_p^-1 (multiplicative, whose state holds C_p^-1 - I);
/// zero for the elastic laws.
template <int dim>
std::pair<Tensor2<dim>, double> plastic_strain(const Material& m, const MaterialState<dim>& state);
/// True for the laws of the small strain (LinearElastic, plastic laws with small-strain
/// kinematics), whose P is sigma.
bool is_small_strain(const Material& m);
/// Cauchy stress of the first Piola–Kirchhoff stress P at F: P F^T / J, or P (small strain).
template <int dim>
Tensor2<dim> cauchy_stress(const Material& m, const Tensor2<dim>& p, const Tensor2<dim>& f);
/// Cauchy stress of a point without history at F.
template <int dim>
Tensor2<dim> cauchy_stress(const Material& m, const Tensor2<dim>& f) {
  return cauchy_stress(m, stress(m, f), f);
}
/// The out-of-plane Cauchy stress sigma_zz of a plane point without history (plane strain:
/// F_zz = 1; plane stress: 0); update() gives it with history.
inline double out_of_plane_stress(const Material& m, const Mat2& f) {
  return update(m, f, MaterialState<2>{}, false).stress_zz;
}
/// True for the small-strain elastic law, whose tangent is the same at every F.
inline bool is_linear(const Material& m) { return std::holds_alternative<LinearElastic>(m); }
std::string_view name(const Material& m);

/// What a scene gives a material model: the elastic constants, and the plastic ones of the
/// models that take them (angles in radians).
struct MaterialParameters {
  double youngs_modulus = 0.0;
  double poisson_ratio = 0.0;
  Kinematics kinematics = Kinematics::multiplicative;
  double yield_stress = 0.0, isotropic_modulus = 0.0, saturation_stress = 0.0, saturation_rate = 0.0,
         kinematic_modulus = 0.0;  // J2
  double friction_angle = 0.0, dilatancy_angle = 0.0, cohesion = 0.0, tension_cutoff = 1e300;  // Drucker–Prager
};

/// The law of a model from its parameters.
using MaterialMaker = Material (*)(const MaterialParameters&);
/// plane_stress, plane_strain, neo_hookean, st_venant_kirchhoff, j2, drucker_prager: the
/// names scenes use.
const NameTable<MaterialMaker>& material_models();
/// multiplicative, logarithmic, small_strain: the strain measures of the plastic models.
const NameTable<Kinematics>& kinematics_names();

/// The law of a model name of material_models(); InputError for E <= 0, nu outside (-1, 1/2)
/// or plastic constants out of range (the message names the value).
Material make_material(std::string_view model, const MaterialParameters& parameters);
/// The same for the elastic constants alone (the elastic models).
Material make_material(std::string_view model, double youngs_modulus, double poisson_ratio);

/// P-wave modulus [Pa] of the reference state, the normal component A_xxxx of the tangent at
/// F = I: lambda + 2 mu in plane strain and in 3D, E / (1 - nu^2) in plane stress. The stiffness of the
/// stiffest traction: Nitsche penalties scale with it.
double p_wave_modulus(const Material& m);

/// Dilatational wave speed sqrt((lambda + 2 mu) / rho0) of the reference state: the speed
/// stability limits of explicit schemes and Courant numbers are measured with.
double wave_speed(const Material& m, double density);

}  // namespace mfree

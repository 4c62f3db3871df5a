#pragma once
// The materials both solvers take, as one value type: a variant of the laws of
// finite_strain.hpp (F -> W, P, A = dP/dF), chosen by a scene's [material] model.
//
//   LinearElastic       small strain, plane stress or plane strain (not objective)
//   StVenantKirchhoff   plane strain
//   NeoHookean          compressible, plane strain (SPEC section 5)
//
// The free functions dispatch once per call; per-point loops call them directly.

#include <string_view>
#include <variant>

#include "mfree/core/name_table.hpp"
#include "mfree/materials/linear_elastic.hpp"
#include "mfree/materials/neo_hookean.hpp"
#include "mfree/materials/st_venant_kirchhoff.hpp"

namespace mfree {

using Material = std::variant<LinearElastic, StVenantKirchhoff, NeoHookean>;

inline double energy(const Material& m, const Mat2& f) {
  return std::visit([&](const auto& law) { return law.energy(f); }, m);
}
/// First Piola–Kirchhoff stress P (force per reference area).
inline Mat2 stress(const Material& m, const Mat2& f) {
  return std::visit([&](const auto& law) { return law.stress(f); }, m);
}
inline Tangent tangent(const Material& m, const Mat2& f) {
  return std::visit([&](const auto& law) { return law.tangent(f); }, m);
}
/// Cauchy stress sigma = P F^T / J; for small strain, sigma = P.
Mat2 cauchy_stress(const Material& m, const Mat2& f);
/// The out-of-plane Cauchy stress sigma_zz (plane strain: F_zz = 1; plane stress: 0).
double out_of_plane_stress(const Material& m, const Mat2& f);
/// True for the small-strain law, whose tangent is the same at every F.
inline bool is_linear(const Material& m) { return std::holds_alternative<LinearElastic>(m); }
std::string_view name(const Material& m);

/// The law of a model from Young's modulus and Poisson's ratio.
using MaterialMaker = Material (*)(double youngs_modulus, double poisson_ratio);
/// plane_stress, plane_strain, neo_hookean, st_venant_kirchhoff: the names scenes use.
const NameTable<MaterialMaker>& material_models();

/// The law of a model name of material_models() with Young's modulus and Poisson's ratio; InputError for E <= 0 or nu outside
/// (-1, 1/2) (the message names the value).
Material make_material(std::string_view model, double youngs_modulus, double poisson_ratio);

/// P-wave modulus [Pa] of the reference state, the normal component A_xxxx of the tangent at
/// F = I: lambda + 2 mu in plane strain, E / (1 - nu^2) in plane stress. The stiffness of the
/// stiffest traction: Nitsche penalties scale with it.
double p_wave_modulus(const Material& m);

/// Dilatational wave speed sqrt((lambda + 2 mu) / rho0) of the reference state: the speed
/// stability limits of explicit schemes and Courant numbers are measured with.
double wave_speed(const Material& m, double density);

}  // namespace mfree

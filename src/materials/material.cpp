#include "mfree/materials/material.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mfree/core/error.hpp"

namespace mfree {

Mat2 cauchy_stress(const Material& m, const Mat2& f) {
  const Mat2 p = stress(m, f);
  if (is_linear(m)) return p;
  return p * f.transpose() / f.determinant();
}

double out_of_plane_stress(const Material& m, const Mat2& f) {
  if (const auto* l = std::get_if<LinearElastic>(&m)) {
    const Mat2 s = l->stress(f);
    return l->out_of_plane_stress({s(0, 0), s(1, 1), s(0, 1)});
  }
  const double j = f.determinant();
  if (const auto* n = std::get_if<NeoHookean>(&m)) return n->lame.lambda * std::log(j) / j;  // P_zz = lambda ln J
  const auto& s = std::get<StVenantKirchhoff>(m);
  const double tr_e = 0.5 * ((f.transpose() * f).trace() - 2.0);
  return s.lame.lambda * tr_e / j;  // S_zz = lambda tr E, sigma_zz = S_zz / J
}

std::string_view name(const Material& m) {
  if (const auto* l = std::get_if<LinearElastic>(&m)) return to_string(l->model);
  return std::holds_alternative<NeoHookean>(m) ? "neo_hookean" : "st_venant_kirchhoff";
}

namespace {

Material plane_stress(double e, double nu) { return LinearElastic{e, nu, PlaneModel::stress}; }
Material plane_strain(double e, double nu) { return LinearElastic{e, nu, PlaneModel::strain}; }
Material neo_hookean(double e, double nu) { return NeoHookean{lame_constants(e, nu)}; }
Material st_venant_kirchhoff(double e, double nu) { return StVenantKirchhoff{lame_constants(e, nu)}; }

}  // namespace

const NameTable<MaterialMaker>& material_models() {
  static const NameTable<MaterialMaker> table{{"plane_stress", plane_stress},
                                              {"plane_strain", plane_strain},
                                              {"neo_hookean", neo_hookean},
                                              {"st_venant_kirchhoff", st_venant_kirchhoff}};
  return table;
}

Material make_material(std::string_view model, double youngs_modulus, double poisson_ratio) {
  const std::vector<std::string> names = material_models().names();
  if (std::find(names.begin(), names.end(), model) == names.end())
    throw InputError(fmt::format("unknown material model '{}' (models: {})", model, fmt::join(names, ", ")));
  LinearElastic{youngs_modulus, poisson_ratio, PlaneModel::strain}.validate();
  return material_models().value(model)(youngs_modulus, poisson_ratio);
}

double p_wave_modulus(const Material& m) { return tangent(m, Mat2::Identity())(0, 0); }

double wave_speed(const Material& m, double density) {
  if (!(density > 0.0)) throw InputError(fmt::format("density must be positive, got {}", density));
  return std::sqrt(p_wave_modulus(m) / density);
}

}  // namespace mfree

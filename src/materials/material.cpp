#include "mfree/materials/material.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <optional>

#include <Eigen/Eigenvalues>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

/// Overloaded lambdas for std::visit: every law must have its case.
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

/// The update of an elastic law: no history.
template <class Law, int dim>
MaterialUpdate<dim> elastic_update(const Law& law, const Tensor2<dim>& f, const MaterialState<dim>& state,
                                   bool with_tangent, double stress_zz) {
  MaterialUpdate<dim> u;
  u.stress = law.stress(f);
  u.stress_zz = stress_zz;
  u.state = state;
  if (with_tangent) u.tangent = law.tangent(f);
  return u;
}

}  // namespace

template <int dim>
MaterialUpdate<dim> update(const Material& m, const Tensor2<dim>& f, const MaterialState<dim>& state,
                           bool with_tangent) {
  // sigma_zz of the plane laws (plane strain); a 3D law has none.
  const auto plane = [](auto zz) { return dim == 2 ? zz() : 0.0; };
  return std::visit(
      Overloaded{[&](const LinearElastic& l) {
                   return elastic_update(l, f, state, with_tangent, plane([&] {
                                           const Tensor2<dim> s = l.stress(f);
                                           return l.out_of_plane_stress({s(0, 0), s(1, 1), s(0, 1)});
                                         }));
                 },
                 [&](const NeoHookean& n) {
                   const double j = checked_jacobian(f, "Neo-Hookean");
                   return elastic_update(n, f, state, with_tangent, plane([&] {
                                           return n.lame.lambda * std::log(j) / j;
                                         }));  // P_zz = lambda ln J
                 },
                 [&](const StVenantKirchhoff& s) {
                   const double j = checked_jacobian(f, "St. Venant–Kirchhoff");
                   // S_zz = lambda tr E, sigma_zz = S_zz / J
                   return elastic_update(s, f, state, with_tangent, plane([&] {
                                           const double tr_e = 0.5 * ((f.transpose() * f).trace() - 2.0);
                                           return s.lame.lambda * tr_e / j;
                                         }));
                 },
                 [&](const J2Plasticity& j) { return j.update(f, state, with_tangent); },
                 [&](const DruckerPrager& d) { return d.update(f, state, with_tangent); }},
      m);
}

template <int dim>
double energy(const Material& m, const Tensor2<dim>& f, const MaterialState<dim>& state) {
  return std::visit(Overloaded{[&](const LinearElastic& l) { return l.energy(f); },
                               [&](const NeoHookean& n) { return n.energy(f); },
                               [&](const StVenantKirchhoff& s) { return s.energy(f); },
                               [&](const J2Plasticity& j) { return j.energy(f, state); },
                               [&](const DruckerPrager& d) { return d.energy(f, state); }},
                    m);
}

bool has_history(const Material& m) {
  return std::visit(Overloaded{[](const LinearElastic&) { return false; }, [](const NeoHookean&) { return false; },
                               [](const StVenantKirchhoff&) { return false; }, [](const J2Plasticity&) { return true; },
                               [](const DruckerPrager&) { return true; }},
                    m);
}

bool has_symmetric_tangent(const Material& m) {
  return std::visit(Overloaded{[](const LinearElastic&) { return true; }, [](const NeoHookean&) { return true; },
                               [](const StVenantKirchhoff&) { return true; }, [](const J2Plasticity&) { return true; },
                               [](const DruckerPrager&) { return false; }},
                    m);
}

template <int dim>
std::pair<Tensor2<dim>, double> plastic_strain(const Material& m, const MaterialState<dim>& state) {
  const auto kinematics = std::visit(
      Overloaded{[](const LinearElastic&) { return std::optional<Kinematics>(); },
                 [](const NeoHookean&) { return std::optional<Kinematics>(); },
                 [](const StVenantKirchhoff&) { return std::optional<Kinematics>(); },
                 [](const J2Plasticity& j) { return std::optional<Kinematics>(j.kinematics); },
                 [](const DruckerPrager& d) { return std::optional<Kinematics>(d.kinematics); }},
      m);
  if (!kinematics) return {Tensor2<dim>::Zero(), 0.0};
  if (*kinematics != Kinematics::multiplicative) return {state.plastic_strain, state.plastic_strain_zz};
  // -1/2 ln of the symmetric positive definite C_p^-1, by its eigen-decomposition.
  const Eigen::SelfAdjointEigenSolver<Tensor2<dim>> eigen(Tensor2<dim>::Identity() + state.plastic_strain);
  const Tensor2<dim> log = eigen.eigenvectors() * eigen.eigenvalues().array().log().matrix().asDiagonal() *
                           eigen.eigenvectors().transpose();
  return {-0.5 * log, dim == 2 ? -0.5 * std::log1p(state.plastic_strain_zz) : 0.0};
}

bool is_small_strain(const Material& m) {
  return std::visit(
      Overloaded{[](const LinearElastic&) { return true; }, [](const NeoHookean&) { return false; },
                 [](const StVenantKirchhoff&) { return false; },
                 [](const J2Plasticity& j) { return j.kinematics == Kinematics::small_strain; },
                 [](const DruckerPrager& d) { return d.kinematics == Kinematics::small_strain; }},
      m);
}

template <int dim>
Tensor2<dim> cauchy_stress(const Material& m, const Tensor2<dim>& p, const Tensor2<dim>& f) {
  return is_small_strain(m) ? p : Tensor2<dim>(p * f.transpose() / f.determinant());
}

template MaterialUpdate<2> update(const Material&, const Tensor2<2>&, const MaterialState<2>&, bool);
template MaterialUpdate<3> update(const Material&, const Tensor2<3>&, const MaterialState<3>&, bool);
template double energy(const Material&, const Tensor2<2>&, const MaterialState<2>&);
template double energy(const Material&, const Tensor2<3>&, const MaterialState<3>&);
template std::pair<Tensor2<2>, double> plastic_strain(const Material&, const MaterialState<2>&);
template std::pair<Tensor2<3>, double> plastic_strain(const Material&, const MaterialState<3>&);
template Tensor2<2> cauchy_stress(const Material&, const Tensor2<2>&, const Tensor2<2>&);
template Tensor2<3> cauchy_stress(const Material&, const Tensor2<3>&, const Tensor2<3>&);

std::string_view name(const Material& m) {
  return std::visit(
      Overloaded{[](const LinearElastic& l) { return to_string(l.model); },
                 [](const NeoHookean&) { return std::string_view("neo_hookean"); },
                 [](const StVenantKirchhoff&) { return std::string_view("st_venant_kirchhoff"); },
                 [](const J2Plasticity&) { return std::string_view("j2"); },
                 [](const DruckerPrager&) { return std::string_view("drucker_prager"); }},
      m);
}

namespace {

Material plane_stress(const MaterialParameters& p) { return LinearElastic{p.youngs_modulus, p.poisson_ratio, PlaneModel::stress}; }
Material plane_strain(const MaterialParameters& p) { return LinearElastic{p.youngs_modulus, p.poisson_ratio, PlaneModel::strain}; }
Material neo_hookean(const MaterialParameters& p) { return NeoHookean{lame_constants(p.youngs_modulus, p.poisson_ratio)}; }
Material st_venant_kirchhoff(const MaterialParameters& p) {
  return StVenantKirchhoff{lame_constants(p.youngs_modulus, p.poisson_ratio)};
}
Material j2(const MaterialParameters& p) {
  J2Plasticity m{lame_constants(p.youngs_modulus, p.poisson_ratio), p.yield_stress, p.isotropic_modulus,
                 p.saturation_stress, p.saturation_rate, p.kinematic_modulus, p.kinematics};
  m.validate();
  return m;
}
Material drucker_prager(const MaterialParameters& p) {
  DruckerPrager m{lame_constants(p.youngs_modulus, p.poisson_ratio), p.friction_angle, p.dilatancy_angle, p.cohesion,
                  p.tension_cutoff, p.kinematics};
  m.validate();
  return m;
}

}  // namespace

const NameTable<MaterialMaker>& material_models() {
  static const NameTable<MaterialMaker> table{{"plane_stress", plane_stress},
                                              {"plane_strain", plane_strain},
                                              {"neo_hookean", neo_hookean},
                                              {"st_venant_kirchhoff", st_venant_kirchhoff},
                                              {"j2", j2},
                                              {"drucker_prager", drucker_prager}};
  return table;
}

const NameTable<Kinematics>& kinematics_names() {
  static const NameTable<Kinematics> table{{"logarithmic", Kinematics::logarithmic},
                                           {"small_strain", Kinematics::small_strain},
                                           {"multiplicative", Kinematics::multiplicative}};
  return table;
}

Material make_material(std::string_view model, const MaterialParameters& parameters) {
  const std::vector<std::string> names = material_models().names();
  if (std::find(names.begin(), names.end(), model) == names.end())
    throw InputError(fmt::format("unknown material model '{}' (models: {})", model, fmt::join(names, ", ")));
  LinearElastic{parameters.youngs_modulus, parameters.poisson_ratio, PlaneModel::strain}.validate();
  return material_models().value(model)(parameters);
}

Material make_material(std::string_view model, double youngs_modulus, double poisson_ratio) {
  MaterialParameters p;
  p.youngs_modulus = youngs_modulus;
  p.poisson_ratio = poisson_ratio;
  return make_material(model, p);
}

double p_wave_modulus(const Material& m) { return tangent(m, Mat2(Mat2::Identity()))(0, 0); }

double wave_speed(const Material& m, double density) {
  if (!(density > 0.0)) throw InputError(fmt::format("density must be positive, got {}", density));
  return std::sqrt(p_wave_modulus(m) / density);
}

}  // namespace mfree

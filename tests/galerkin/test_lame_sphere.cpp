// Lamé's thick sphere under internal pressure p (a = 1 <= r <= b = 2, E = 1, nu = 0.3), one
// eighth of it by symmetry (meshes/thick_sphere_octant.geo read through gmsh: a solid of
// tetrahedra whose curved faces are flat triangles), slip walls (Nitsche) on x = 0, y = 0,
// z = 0, the pressure on the bore, the outside free. Exact (small strain):
//   u_r = C [(1 - 2 nu) r + (1 + nu) b^3 / (2 r^2)],  C = p a^3 / (E (b^3 - a^3)),
//   grad u = (u_r / r) I + (u_r' - u_r / r) e_r e_r^T.
// The L2 and energy errors over the meshed solid by an independent rule (the tetrahedra
// clipped to cells of h, 27 collapsed Gauss points on each piece), against the exact field.
#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "../test_support.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/newton_solver.hpp"
#include "mfree/geometry/gmsh_solid.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"
#include "mfree/quadrature/gauss_cells.hpp"

using namespace mfree;

namespace {

using P3 = Point<3>;
using M3 = Tensor2<3>;

struct LameSphere {
  double a = 1.0, b = 2.0, p = 0.01, young = 1.0, nu = 0.3;
  [[nodiscard]] double c() const { return p * a * a * a / (young * (b * b * b - a * a * a)); }
  [[nodiscard]] P3 displacement(const P3& x) const {
    const double r = x.norm();
    return c() * ((1.0 - 2.0 * nu) * r + (1.0 + nu) * b * b * b / (2.0 * r * r)) * x / r;
  }
  [[nodiscard]] M3 gradient(const P3& x) const {
    const double r = x.norm();
    const double ur = c() * ((1.0 - 2.0 * nu) * r + (1.0 + nu) * b * b * b / (2.0 * r * r));
    const double dur = c() * ((1.0 - 2.0 * nu) - (1.0 + nu) * b * b * b / (r * r * r));
    const P3 e = x / r;
    return ur / r * M3::Identity() + (dur - ur / r) * e * e.transpose();
  }
};

struct Errors {
  double l2 = 0.0, energy = 0.0;
};

Errors solve_and_measure(double h, double size, RKOrder order) {
  const LameSphere lame;
  const Solid solid = testing::thick_sphere_octant(size);
  const LinearElastic law{lame.young, lame.nu, PlaneModel::strain};
  SolidProblem<3> problem;
  problem.material = law;
  problem.spacing = h;
  const auto zero = [](const P3&, const P3&, double) { return P3::Zero(); };
  for (const char* face : {"x_sym", "y_sym", "z_sym"})
    problem.conditions.push_back({BoundaryCondition<3>::Type::slip, select_part(solid, face), zero, face});
  BoundaryCondition<3> bore{BoundaryCondition<3>::Type::pressure, select_part(solid, "bore"), {}, "bore"};
  bore.pressure = [lame](const P3&, double) { return lame.p; };
  problem.conditions.push_back(bore);
  ElasticitySettings s;
  s.nodes.spacing = h;
  s.order = order;
  s.support_factor = order == RKOrder::linear ? 2.0 : 3.0;
  s.scheme = QuadratureScheme::projected;
  s.quadrature_ratio = 8.0;
  s.quadrature_order = order;
  StageTimer timer;
  const Discretisation<3> disc = discretise(solid, s, condition_parts(problem.conditions), timer);
  TotalLagrangian<3> model(problem, solid, disc.node_count(), disc.quadrature, disc.test(), disc.boundary,
                           disc.at_boundary);
  NewtonSettings ns;
  ns.load_steps = 1;
  const StaticSolution sol = solve_static(model, disc.nodes, ns, timer);

  const Lame constants = lame_constants(lame.young, lame.nu);
  const auto stress = [&](const M3& g) {
    const M3 eps = 0.5 * (g + g.transpose());
    return M3(constants.lambda * eps.trace() * M3::Identity() + 2.0 * constants.mu * eps);
  };
  const QuadratureRule<3> rule = gauss_cell_rule(solid, h, 3);
  double l2 = 0.0, l2_norm = 0.0, energy = 0.0, energy_norm = 0.0;
  // In blocks of points: the functions at all of them at once would take gigabytes.
  constexpr std::size_t block = 100000;
  for (std::size_t begin = 0; begin < rule.size(); begin += block) {
    const std::size_t end = std::min(rule.size(), begin + block);
    const std::vector<P3> points(rule.points.begin() + begin, rule.points.begin() + end);
    const GalerkinQuadrature<3> at = sample_shape_functions(*disc.trial, points, true);
    for (Index k = 0; k < at.size(); ++k) {
      const P3& x = points[k];
      const double w = rule.weights[begin + k];
      M3 g = M3::Zero();
      for (Index j = at.row_begin(k); j < at.row_end(k); ++j)
        g += sol.coefficients.segment<3>(3 * at.nodes[j]) * at.grad[j].transpose();
      const P3 u = lame.displacement(x);
      const M3 exact = lame.gradient(x), e = g - exact;
      l2 += w * (displacement_at(at, k, sol.coefficients) - u).squaredNorm();
      l2_norm += w * u.squaredNorm();
      energy += w * (stress(e).array() * e.array()).sum();
      energy_norm += w * (stress(exact).array() * exact.array()).sum();
    }
  }
  std::string stages;
  for (const auto& [name, seconds] : timer.stages()) stages += fmt::format(" {} {:.2f} s,", name, seconds);
  WARN(fmt::format(
      "{} RK, h = {:.4g}, mesh size {:.4g}: {} nodes, {} tetrahedra, {} quadrature points; L2 {:.3e}, "
      "energy {:.3e};{}",
      to_string(order), h, size, disc.node_count(), solid.mesh()->size(), disc.quadrature.size(),
      std::sqrt(l2 / l2_norm), std::sqrt(energy / energy_norm), stages));
  return {std::sqrt(l2 / l2_norm), std::sqrt(energy / energy_norm)};
}

void check_rates(RKOrder order, const std::vector<double>& spacings, double l2_rate, double energy_rate) {
  std::vector<Errors> e;
  for (const double h : spacings) e.push_back(solve_and_measure(h, h / 2, order));
  const std::size_t n = spacings.size() - 1;
  const double ratio = std::log(spacings[n - 1] / spacings[n]);
  const double l2 = std::log(e[n - 1].l2 / e[n].l2) / ratio,
               energy = std::log(e[n - 1].energy / e[n].energy) / ratio;
  WARN(fmt::format("{} RK rates: L2 {:.2f}, energy {:.2f}", to_string(order), l2, energy));
  CHECK(l2 >= l2_rate);
  CHECK(energy >= energy_rate);
}

}  // namespace

// Measured (mesh size h / 2): linear RK L2 7.81e-2, 1.15e-2, 5.52e-3 at h = 0.4, 0.2, 0.133
// (rates 2.76, 1.80), energy 3.06e-1, 8.07e-2, 5.39e-2 (1.92, 0.99).
TEST_CASE("Lame sphere, linear RK: L2 rate 2, energy rate 1", "[galerkin][3d][study]") {
  check_rates(RKOrder::linear, {0.4, 0.2, 0.133}, 1.7, 0.9);
}

// Quadratic RK falls short of the cube's rates (3 and 2) here: L2 6.40e-2, 1.35e-2, 5.40e-3 at
// h = 0.4, 0.3, 0.2 (rates 5.4, 2.25), energy 2.20e-1, 6.47e-2, 3.72e-2 (4.3, 1.37); a surface
// mesh of h / 5 changes them little (3.81e-3, 3.39e-2 at h = 0.2), so the flat facets are not
// the cause; h = 0.15 gives L2 2.36e-3, energy 2.09e-2 (mesh h / 3). Guarded at what it does.
TEST_CASE("Lame sphere, quadratic RK: L2 rate 2, energy rate 1.3 (short of 3 and 2)",
          "[galerkin][3d][study]") {
  check_rates(RKOrder::quadratic, {0.4, 0.3, 0.2}, 2.0, 1.3);
}

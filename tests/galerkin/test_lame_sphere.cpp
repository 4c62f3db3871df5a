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
#include "elastic_errors_3d.hpp"
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

using testing::ElasticErrors;

ElasticErrors solve_and_measure(double h, double size, RKOrder order) {
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
  s.support_rule = SupportRule::plain;  // a solid's default (geodesic supports are plane only)
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

  const ElasticErrors e = small_strain_errors(
      *disc.trial, sol.coefficients, gauss_cell_rule(solid, h, 3),
      [&](const P3&) { return lame_constants(lame.young, lame.nu); },
      [&](const P3& x) { return lame.displacement(x); }, [&](const P3& x) { return lame.gradient(x); });
  std::string stages;
  for (const auto& [name, seconds] : timer.stages()) stages += fmt::format(" {} {:.2f} s,", name, seconds);
  WARN(fmt::format(
      "{} RK, h = {:.4g}, mesh size {:.4g}: {} nodes, {} tetrahedra, {} quadrature points; L2 {:.3e}, "
      "energy {:.3e};{}",
      to_string(order), h, size, disc.node_count(), solid.mesh()->size(), disc.quadrature.size(), e.l2,
      e.energy, stages));
  return e;
}

void check_rates(RKOrder order, const std::vector<double>& spacings, double l2_rate, double energy_rate) {
  std::vector<ElasticErrors> e;
  for (const double h : spacings) e.push_back(solve_and_measure(h, h / 2, order));
  const ElasticErrors rates = testing::last_rates(spacings, e);
  WARN(fmt::format("{} RK rates: L2 {:.2f}, energy {:.2f}", to_string(order), rates.l2, rates.energy));
  CHECK(rates.l2 >= l2_rate);
  CHECK(rates.energy >= energy_rate);
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

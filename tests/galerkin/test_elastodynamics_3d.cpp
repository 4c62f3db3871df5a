// Elastodynamics in three dimensions: the vibration problem of SPEC section 6 on the unit cube
// (a Neo-Hookean body, slip walls on the six faces by Nitsche's method, the manufactured body
// force), linear RK on lattices with VCI. The L2 error of u^h against the exact motion, by an
// independent Gauss rule (4 x 4 x 4 points per cell of h: 64 a node, as the plane 4 x 4 per
// cell of h / 2), falls at rate 2 with central differences (h = 1/8 to 1/16, at T/4 and 3T/4)
// and with Newmark (h = 1/8 to 1/12 at 3T/4: from 1/8 to 1/16, 1.84 at T/4, but 125 s, mostly
// three factorisations of the 14739-unknown effective tangent) (studies: Release only, their
// value is the rates; about 60 s each on 2 cores).
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/problems/axis_aligned_vibration.hpp"
#include "mfree/quadrature/gauss_cells.hpp"

using namespace mfree;

namespace {

using P3 = Point<3>;

const Solid& cube() {
  static const Solid solid = Solid::box(P3(0.0, 0.0, 0.0), P3(1.0, 1.0, 1.0));
  return solid;
}

/// ||u^h - u|| / ||u|| (L2) at the times given as fractions of the period, for lattice
/// spacing h and the scheme of `settings`.
std::vector<double> vibration_errors(double h, const std::vector<double>& fractions,
                                     DynamicsSettings settings) {
  const AxisAlignedVibration exact{0.05};
  SolidProblem<3> p;
  p.material = exact.material();
  p.density = exact.density;
  p.spacing = h;
  p.body_force = [exact](const P3& x, double t) { return P3(exact.density * exact.body_force(x, t)); };
  const auto zero = [](const P3&, const P3&, double) { return P3::Zero(); };
  for (const std::string& face : cube().parts())
    p.conditions.push_back({BoundaryCondition<3>::Type::slip, select_part(cube(), face), zero, face});
  ElasticitySettings s;
  s.nodes.spacing = h;
  s.scheme = QuadratureScheme::projected;
  s.quadrature_ratio = 8.0;
  StageTimer timer;
  const Discretisation<3> disc = discretise(cube(), s, condition_parts(p.conditions), timer);
  TotalLagrangian<3> model(p, cube(), disc.node_count(), disc.quadrature, disc.test(), disc.boundary,
                           disc.at_boundary);
  const Eigen::VectorXd v0 =
      project_velocity(model, disc.nodes, [&](const P3& x) { return exact.velocity(x, 0.0); }, {});

  const QuadratureRule<3> rule = gauss_cell_rule(cube(), h, 4);
  const GalerkinQuadrature<3> at = sample_shape_functions(*disc.trial, rule.points, false);
  std::vector<double> errors;
  std::size_t next = 0;
  settings.end_time = fractions.back() * exact.period();
  (void)integrate_dynamics(
      model, disc.nodes, Eigen::VectorXd::Zero(model.dofs()), v0, settings, timer,
      [&](const DynamicState& st) {
        if (next >= fractions.size() || st.time < fractions[next] * exact.period() * (1 - 1e-12)) return;
        double error = 0.0, norm = 0.0;
        for (Index k = 0; k < at.size(); ++k) {
          const P3 u = exact.displacement(rule.points[k], st.time);
          error += rule.weights[k] * (displacement_at(at, k, st.d) - u).squaredNorm();
          norm += rule.weights[k] * u.squaredNorm();
        }
        errors.push_back(std::sqrt(error / norm));
        ++next;
      });
  return errors;
}

void check_rates(const DynamicsSettings& s, const std::vector<double>& spacings,
                 const std::vector<double>& fractions) {
  std::vector<std::vector<double>> levels;
  for (const double h : spacings) levels.push_back(vibration_errors(h, fractions, s));
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    const double rate = std::log(levels[0][k] / levels[1][k]) / std::log(spacings[0] / spacings[1]);
    INFO(fmt::format("{} at t = {} T: L2 errors {:.3e} (h = {}), {:.3e} (h = {}): rate {:.2f}",
                     to_string(s.scheme), fractions[k], levels[0][k], spacings[0], levels[1][k], spacings[1],
                     rate));
    CHECK(rate >= 1.8);
  }
}

}  // namespace

TEST_CASE("3D vibration, central differences: displacement converges at rate 2",
          "[galerkin][dynamics][3d][study]") {
  DynamicsSettings s;
  s.scheme = TimeScheme::central_difference;
  s.time_step = 2.5e-5;  // below the stability limits of both levels
  s.energy_every = 0;
  check_rates(s, {1.0 / 8, 1.0 / 16}, {0.25, 0.75});
}

TEST_CASE("3D vibration, Newmark: displacement converges at rate 2", "[galerkin][dynamics][3d][study]") {
  DynamicsSettings s;
  s.scheme = TimeScheme::newmark;
  s.time_step = 2.5e-4;  // 80 steps a period
  s.energy_every = 0;
  s.newton.tolerance = 1e-10;
  check_rates(s, {1.0 / 8, 1.0 / 12}, {0.75});
}

// The perfectly plastic thick sphere under growing internal pressure (Hill 1950): a = 1,
// b = 2, J2 with sigma_y = 1 and no hardening, small strain, E = 1000, nu = 0.3; the octant
// of meshes/thick_sphere_octant.geo with slip walls on x = 0, y = 0, z = 0 and the pressure on
// the bore. Classical solution (independent of the elastic constants): first yield at r = a
// when p = 2/3 sigma_y (1 - a^3/b^3); a plastic shell a <= r <= c with
//   p = 2 sigma_y ln(c / a) + 2/3 sigma_y (1 - c^3 / b^3),
// and the collapse (limit) pressure when c = b, p_L = 2 sigma_y ln(b / a). The plastic zone's
// volume V_p (quadrature weights of the points that yielded) gives the radius of the octant's
// shell, c = (a^3 + 6 V_p / pi)^(1/3).
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/newton_solver.hpp"
#include "mfree/geometry/solid.hpp"
#include "mfree/materials/j2_plasticity.hpp"

using namespace mfree;

namespace {

using P3 = Point<3>;
const double pi = std::acos(-1.0);
constexpr double a = 1.0, b = 2.0, sy = 1.0;

double hill(double c) { return 2 * sy * std::log(c / a) + 2.0 / 3.0 * sy * (1 - c * c * c / (b * b * b)); }

/// c(p) by bisection.
double plastic_radius(double p) {
  double lo = a, hi = b;
  for (int i = 0; i < 100; ++i) (hill(0.5 * (lo + hi)) < p ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

struct Sphere {
  Solid solid;
  Discretisation<3> disc;
  SolidProblem<3> problem;
};

/// The octant at node spacing h (linear RK), the pressure p_max at load factor 1.
Sphere plastic_sphere(double h, double p_max) {
  Sphere s{testing::thick_sphere_octant(h / 2), {}, {}};
  J2Plasticity law;
  law.lame = lame_constants(1000.0, 0.3);
  law.yield_stress = sy;
  law.kinematics = Kinematics::small_strain;
  s.problem.material = law;
  s.problem.spacing = h;
  const auto zero = [](const P3&, const P3&, double) { return P3::Zero(); };
  for (const char* face : {"x_sym", "y_sym", "z_sym"})
    s.problem.conditions.push_back(
        {BoundaryCondition<3>::Type::slip, select_part(s.solid, face), zero, face});
  BoundaryCondition<3> bore{BoundaryCondition<3>::Type::pressure, select_part(s.solid, "bore"), {}, "bore"};
  bore.pressure = [p_max](const P3&, double) { return p_max; };  // scaled by the load factor
  s.problem.conditions.push_back(bore);
  ElasticitySettings settings;
  settings.support_rule = SupportRule::plain;  // a solid's default (geodesic supports are plane only)
  settings.nodes.spacing = h;
  settings.order = RKOrder::linear;
  settings.support_factor = 2.0;
  settings.scheme = QuadratureScheme::projected;
  settings.quadrature_ratio = 8.0;
  StageTimer timer;
  s.disc = discretise(s.solid, settings, condition_parts(s.problem.conditions), timer);
  return s;
}

}  // namespace

TEST_CASE(
    "plastic thick sphere: elastic-plastic radius against Hill's, Newton to 95 % of p_L and not past it",
    "[galerkin][3d][plasticity][study]") {
  // One loading to 1.1 p_L: Hill's radius on the way to 0.95 p_L, each step without a cut-back;
  // past the limit load there is no equilibrium and Newton must give up (the discrete collapse
  // load lies above p_L by the discretisation's stiffness, a few per cent at this h).
  const double h = 0.2, p_limit = 2 * sy * std::log(b / a), p_max = 1.1 * p_limit;
  Sphere s = plastic_sphere(h, p_max);
  TotalLagrangian<3> model(s.problem, s.solid, s.disc.node_count(), s.disc.quadrature, s.disc.test(),
                           s.disc.boundary, s.disc.at_boundary);
  NewtonSettings ns;
  for (double p : {0.285, 0.4275, 0.57, 0.665, 0.76, 0.836, 0.893, 0.931, 0.95, 1.0, 1.04, 1.1})
    ns.load_factors.push_back(p * p_limit / p_max);
  ns.load_factors.back() = 1.0;
  ns.max_iterations = 12;  // the converged steps take at most 9
  ns.max_cutbacks = 4;
  StageTimer timer;
  double worst = 0.0, last = 0.0;
  int steps_to_095 = 0;
  CHECK_THROWS_AS(solve_static(model, s.disc.nodes, ns, timer,
                               [&](const LoadStepRecord& step, const Eigen::VectorXd&) {
                                 const double p = p_max * step.factor;
                                 last = p / p_limit;
                                 if (p > 0.95 * p_limit * (1 + 1e-12)) return;
                                 ++steps_to_095;
                                 CHECK(step.history.size() <= 10);
                                 if (p <= hill(a) * 0.999) {
                                   CHECK(model.plastic_area() == 0.0);  // below first yield
                                 } else if (p >= hill(a) * 1.2) {
                                   const double c = std::cbrt(a * a * a + 6 * model.plastic_area() / pi),
                                                exact = plastic_radius(p);
                                   WARN(fmt::format("p / p_L = {:.3f}: c = {:.4f}, Hill {:.4f} ({:+.2f} %)",
                                                    p / p_limit, c, exact, 100 * (c - exact) / exact));
                                   worst = std::max(worst, std::abs(c - exact) / exact);
                                 }
                               }),
                  NumericalError);
  CHECK(steps_to_095 == 9);  // no cut-back needed below 0.95 p_L
  CHECK(worst <= 0.015);     // measured: 0.31 % to 0.66 % from p = 0.57 p_L to 0.95 p_L
  WARN(fmt::format("Newton's last converged pressure {:.4f} p_L", last));
  CHECK(last >= 0.95);
  CHECK(last < 1.08);  // measured: 1.059 p_L
}

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>

#include "mfree/core/error.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/newton_solver.hpp"
#include "../test_support.hpp"

using namespace mfree;

namespace {

/// A 4 x 1 block of Neo-Hookean material on a coarse cloud, clamped at x = 0 by Nitsche's
/// method, with a slip wall at y = 0 for x < 1 (clipped from the bottom edge) and a downward
/// traction on x = 4.
struct Block {
  Domain domain = Domain::rectangle(Vec2(0.0, 0.0), Vec2(4.0, 1.0));
  Discretisation<2> disc;
  SolidProblem<2> problem;

  explicit Block(double load, Material material = NeoHookean{lame_constants(1000.0, 0.3)}) {
    ElasticitySettings s;
    s.scheme = QuadratureScheme::projected;  // symmetric correction: the trial gradients are the test ones
    s.nodes.spacing = 0.25;
    StageTimer timer;
    disc = discretise(domain, s, timer);
    problem.material = material;
    problem.spacing = s.nodes.spacing;
    problem.conditions = {
        {BoundaryCondition<2>::Type::displacement, select_part(domain, "left"),
         [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); }, "clamp"},
        {BoundaryCondition<2>::Type::slip, select_box(domain, Box{Vec2(0.0, -0.1), Vec2(1.0, 0.1)}),
         [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); }, "wall"},
        {BoundaryCondition<2>::Type::traction, select_part(domain, "right"),
         [load](const Vec2&, const Vec2&, double) { return Vec2(-0.3 * load, -load); }, "load"}};
  }
  [[nodiscard]] TotalLagrangian<2> model() const {
    return TotalLagrangian<2>(problem, domain, disc.node_count(), disc.quadrature, nullptr, disc.boundary,
                              disc.at_boundary);
  }
};

/// A displacement field of size `amplitude` on the nodes (coefficients), smooth so that F
/// stays invertible.
Eigen::VectorXd smooth_field(const std::vector<Vec2>& nodes, double amplitude) {
  Eigen::VectorXd d(2 * nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Vec2& x = nodes[i];
    d.segment<2>(2 * i) = amplitude * Vec2(std::sin(x.y() + 0.3 * x.x()), 0.5 * x.x() * std::cos(x.y()));
  }
  return d;
}

/// solve_static keeping the iteration log in `log` (shown by INFO when a check fails).
StaticSolution solve_logged(TotalLagrangian<2>& model, NewtonSettings s, std::ostringstream& log) {
  s.log = &log;
  StageTimer timer;
  return solve_static(model, {}, s, timer);
}

/// K dir and the central difference of `residual` at d along dir, for a random dir.
template <class Residual>
std::pair<Eigen::VectorXd, Eigen::VectorXd> directional_derivatives(const Residual& residual, const Eigen::MatrixXd& k,
                                                                    const Eigen::VectorXd& d, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd dir(d.size());
  for (Eigen::Index i = 0; i < d.size(); ++i) dir[i] = u(rng);
  const double h = 1e-6;
  return {k * dir, (residual(d + h * dir) - residual(d - h * dir)) / (2 * h)};
}

}  // namespace

TEST_CASE("TL tangent equals finite differences of the residual (Neo-Hookean, Nitsche, slip)", "[galerkin][tl]") {
  const Block block(0.0);
  TotalLagrangian<2> model = block.model();
  REQUIRE_FALSE(model.symmetric());
  const Eigen::VectorXd d = smooth_field(block.disc.nodes, 0.05);
  const LoadState load{0.7, 0.0};
  const auto residual = [&](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(model.internal_force(x) + model.boundary_force(x, load));
  };
  SparseMatrix k = model.zero_matrix();
  model.tangent(d, load, k);
  const Eigen::MatrixXd dense(k);
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 3; ++trial) {
    const auto [kd, fd] = directional_derivatives(residual, dense, d, rng);
    INFO("relative difference " << (fd - kd).norm() / kd.norm());
    CHECK((fd - kd).norm() <= 1e-6 * kd.norm());
  }
}

TEST_CASE("small-strain law: one Newton step solves the linear problem; the system is symmetric", "[galerkin][tl]") {
  const Block block(1.0, LinearElastic{1000.0, 0.3, PlaneModel::strain});
  TotalLagrangian<2> model = block.model();
  REQUIRE(model.symmetric());
  NewtonSettings s;
  s.load_steps = 1;
  std::ostringstream log;
  const StaticSolution sol = solve_logged(model, s, log);
  INFO(log.str());
  REQUIRE(sol.steps.size() == 1);
  // The residual after one iteration is round-off.
  CHECK(sol.steps[0].history.size() == 2);
  CHECK(sol.steps[0].history[1].residual <= 1e-12 * sol.steps[0].history[0].residual);
}

TEST_CASE("Newton converges quadratically on a Neo-Hookean bending case", "[galerkin][tl]") {
  Block block(4.0);  // tip deflection about a quarter of the length
  // Without the slip wall: with it the iterates reach round-off before the ratio estimate of
  // the order settles (4e-5 -> 1.9e-8 -> 3.9e-13: quadratic with constant 12, "order" 0.9).
  block.problem.conditions.erase(block.problem.conditions.begin() + 1);
  TotalLagrangian<2> model = block.model();
  NewtonSettings s;
  s.load_steps = 2;
  s.tolerance = 1e-12;
  std::ostringstream log;
  const StaticSolution sol = solve_logged(model, s, log);
  INFO(log.str());
  REQUIRE(sol.steps.size() == 2);
  const Vec2 tip = block.disc.displacement({Vec2(4.0, 0.5)}, sol.coefficients)[0];
  INFO("tip displacement " << tip.transpose());
  CHECK(tip.y() < -0.7);  // large deflection: nonlinear regime
  for (const LoadStepRecord& step : sol.steps) {
    CHECK(step.history.size() <= 9);
    // The best observed order among the iterations where |R| / |R0| is in (1e-12, 1e-3).
    double best = 0.0;
    for (const NewtonIterate& it : step.history)
      if (it.residual < 1e-3 * step.history[0].residual && it.residual > 1e-12 * step.history[0].residual)
        best = std::max(best, it.order);
    CHECK(best >= 1.8);
  }
}

TEST_CASE("an inverting load gives up with a clear message naming J <= 0 and the load factor", "[galerkin][tl]") {
  Block block(0.0);
  // Push the free end 12 units left (3 lengths): the block must turn inside out. Without a
  // line search Newton steps straight into the inverted state.
  block.problem.conditions.push_back(
      {BoundaryCondition<2>::Type::displacement, select_part(block.domain, "right"),
       [](const Vec2&, const Vec2&, double) { return Vec2(-12.0, 0.0); }, "push"});
  block.problem.conditions.erase(block.problem.conditions.begin() + 1, block.problem.conditions.begin() + 3);
  TotalLagrangian<2> model = block.model();
  NewtonSettings s;
  s.load_steps = 1;
  s.max_cutbacks = 1;
  s.line_search = false;
  StageTimer timer;
  const std::string m = testing::message_of<NumericalError>([&] { (void)solve_static(model, block.disc.nodes, s, timer); });
  CHECK_THAT(m, Catch::Contains("Newton gave up at load factor"));
  CHECK_THAT(m, Catch::Contains("J = det F"));
  CHECK_THAT(m, Catch::Contains("<= 0"));
  CHECK_THAT(m, Catch::Contains("load steps"));
}

namespace {
/// The block with a pressure p(X, t) = p0 (1 + X / 4)(1 + t) on its top instead of the end
/// traction: a follower load with the Neo-Hookean law.
Block pressed_block(double p0, Material material = NeoHookean{lame_constants(1000.0, 0.3)}) {
  Block block(0.0, material);
  block.problem.conditions.pop_back();
  block.problem.conditions.push_back(
      {BoundaryCondition<2>::Type::pressure,
       select_part(block.domain, "top"),
       {},
       "top",
       [p0](const Vec2& x, double t) { return p0 * (1.0 + x.x() / 4.0) * (1.0 + t); }});
  return block;
}
}  // namespace

TEST_CASE("follower pressure: the load stiffness equals finite differences of the pressure force", "[galerkin][tl]") {
  const Block block = pressed_block(20.0);
  TotalLagrangian<2> model = block.model();
  REQUIRE_FALSE(model.symmetric());
  const Eigen::VectorXd d = smooth_field(block.disc.nodes, 0.05);
  const LoadState load{0.7, 0.3};
  const auto residual = [&](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(model.internal_force(x) + model.boundary_force(x, load));
  };
  SparseMatrix k = model.zero_matrix();
  model.tangent(d, load, k);
  const Eigen::MatrixXd dense(k);
  // The pressure part alone: the same model without the pressure condition.
  SolidProblem<2> bare = block.problem;
  bare.conditions.pop_back();
  const TotalLagrangian<2> without(bare, block.domain, block.disc.node_count(), block.disc.quadrature,
                                   nullptr, block.disc.boundary, block.disc.at_boundary);
  SparseMatrix k0 = without.zero_matrix();
  without.tangent(d, load, k0);
  // The pressure part: the tangent with the pressure less the one without, along the same
  // direction (the same seed draws the same direction).
  std::mt19937_64 rng(5), again(5);
  for (int trial = 0; trial < 3; ++trial) {
    const auto [kd, fd] = directional_derivatives(residual, dense, d, rng);
    const Eigen::VectorXd pressure_part = kd - directional_derivatives(residual, Eigen::MatrixXd(k0), d, again).first;
    INFO("relative difference " << (fd - kd).norm() / pressure_part.norm());
    REQUIRE(pressure_part.norm() > 1e-5 * kd.norm());  // the load stiffness is there to be checked
    CHECK((fd - kd).norm() <= 1e-6 * pressure_part.norm());
  }
  // The force is -p int phi R x,S: at d = 0 the dead load -p N, i.e. (0, -p) on the top.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.dofs());
  const Eigen::VectorXd f = -(model.boundary_force(zero, load) - without.boundary_force(zero, load));
  double fy = 0.0, fx = 0.0;
  for (Index i = 0; i < model.nodes(); ++i) {
    fx += f[2 * i];
    fy += f[2 * i + 1];
  }
  // sum_I phi_I = 1: the resultant is -0.7 * 20 * 1.3 * int_0^4 (1 + X / 4) dX = -0.7 * 20 * 1.3 * 6.
  CHECK(std::abs(fx) <= 1e-12);
  CHECK(fy == Approx(-0.7 * 20.0 * 1.3 * 6.0).epsilon(1e-12));
}

TEST_CASE("pressure with the small-strain law is the dead traction -p N", "[galerkin][tl]") {
  const Block pressed = pressed_block(20.0, LinearElastic{1000.0, 0.3, PlaneModel::strain});
  Block traction = pressed_block(20.0, LinearElastic{1000.0, 0.3, PlaneModel::strain});
  traction.problem.conditions.back() = {BoundaryCondition<2>::Type::traction,
                                        select_part(traction.domain, "top"),
                                        [](const Vec2& x, const Vec2& n, double t) {
                                          return Vec2(-20.0 * (1.0 + x.x() / 4.0) * (1.0 + t) * n);
                                        },
                                        "top"};
  const LoadState load{0.7, 0.3};
  const TotalLagrangian<2> a = pressed.model(), b = traction.model();
  REQUIRE(a.symmetric());
  const Eigen::VectorXd fa = a.external_force(load), fb = b.external_force(load);
  CHECK((fa - fb).norm() <= 1e-14 * fb.norm());
}

TEST_CASE("Nitsche slip and clamp terms: their tangent equals finite differences at a deformed state", "[galerkin][tl]") {
  const Block block(0.0);
  const Eigen::VectorXd d = smooth_field(block.disc.nodes, 0.05);
  const LoadState load{0.7, 0.0};
  const auto model_of = [&](std::vector<BoundaryCondition<2>> conditions) {
    SolidProblem<2> p = block.problem;
    p.conditions = std::move(conditions);
    return TotalLagrangian<2>(p, block.domain, block.disc.node_count(), block.disc.quadrature, nullptr,
                              block.disc.boundary, block.disc.at_boundary);
  };
  const TotalLagrangian<2> none = model_of({});
  for (std::size_t c = 0; c < 2; ++c) {  // the clamp, then the slip wall
    const TotalLagrangian<2> with = model_of({block.problem.conditions[c]});
    SparseMatrix k = with.zero_matrix(), k0 = none.zero_matrix();
    with.tangent(d, load, k);
    none.tangent(d, load, k0);
    const auto boundary_part = [&](const Eigen::VectorXd& x) {
      return Eigen::VectorXd(with.internal_force(x) + with.boundary_force(x, load) - none.internal_force(x));
    };
    std::mt19937_64 rng(11);
    const auto [kd, fd] = directional_derivatives(boundary_part, Eigen::MatrixXd(k) - Eigen::MatrixXd(k0), d, rng);
    INFO("condition " << block.problem.conditions[c].name << ": relative difference " << (fd - kd).norm() / kd.norm());
    CHECK((fd - kd).norm() <= 1e-6 * kd.norm());
  }
}

namespace {

/// J2 plasticity (multiplicative, the default) with linear and saturating isotropic hardening, E = 1000, nu = 0.3.
J2Plasticity j2_law(double yield_stress) {
  J2Plasticity j2;
  j2.lame = lame_constants(1000.0, 0.3);
  j2.yield_stress = yield_stress;
  j2.isotropic_modulus = 100.0;
  j2.saturation_stress = 1.5 * yield_stress;
  j2.saturation_rate = 20.0;
  return j2;
}

}  // namespace

TEST_CASE("TL with J2 and Drucker–Prager: the tangent at a plastic state with history equals finite differences",
          "[galerkin][tl][plasticity]") {
  DruckerPrager soil;  // non-associative: psi = 0 < phi
  soil.lame = lame_constants(1000.0, 0.3);
  soil.friction_angle = 20.0 * M_PI / 180.0;
  soil.cohesion = 2.0;
  for (const Material& law : {Material(j2_law(8.0)), Material(soil)}) {
  CAPTURE(name(law));
  const Block block(0.0, law);
  TotalLagrangian<2> model = block.model();
  REQUIRE(model.has_history());
  REQUIRE_FALSE(model.symmetric());
  // A history first (committed at d1), then the tangent at d2 beyond it: both plastic.
  const Eigen::VectorXd d1 = smooth_field(block.disc.nodes, 0.04), d2 = 1.3 * d1;
  model.commit(d1);
  const double alpha_max = [&] {
    double a = 0.0;
    for (const MaterialState<2>& s : model.history().domain) a = std::max(a, s.alpha);
    for (const MaterialState<2>& s : model.history().boundary) a = std::max(a, s.alpha);
    return a;
  }();
  INFO("largest equivalent plastic strain " << alpha_max);
  REQUIRE(alpha_max > 0.01);
  REQUIRE(model.dissipated() > 0.0);
  const LoadState load{0.7, 0.0};
  const auto residual = [&](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(model.internal_force(x) + model.boundary_force(x, load));
  };
  SparseMatrix k = model.zero_matrix();
  model.tangent(d2, load, k);
  const Eigen::MatrixXd dense(k);
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 3; ++trial) {
    const auto [kd, fd] = directional_derivatives(residual, dense, d2, rng);
    INFO("relative difference " << (fd - kd).norm() / kd.norm());
    CHECK((fd - kd).norm() <= 1e-6 * kd.norm());
  }
  }
}

TEST_CASE("TL with J2: a uniaxial-strain block reproduces the material point's path at every point", "[galerkin][tl][plasticity]") {
  // Plane-strain uniaxial compression of the unit square: slip on the left, right and bottom,
  // the top pressed down by delta. The exact motion u = (0, -delta y) is linear, hence in the
  // trial space; with integration-consistent gradients and a consistent Nitsche form it solves
  // the discrete equations, so every quadrature point (and Nitsche point) must follow the
  // material-point update of F = diag(1, 1 - lambda delta) through the same load factors.
  const Domain domain = Domain::rectangle(Vec2(0.0, 0.0), Vec2(1.0, 1.0));
  ElasticitySettings es;
  es.scheme = QuadratureScheme::projected;
  es.nodes.spacing = 0.25;
  StageTimer timer;
  const Discretisation<2> disc = discretise(domain, es, timer);
  const J2Plasticity law = j2_law(5.0);
  const double delta = 0.05;  // eight times the yield strain sigma_y / (2 mu)
  SolidProblem<2> p;
  p.material = law;
  p.spacing = es.nodes.spacing;
  const auto zero = [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); };
  p.conditions = {{BoundaryCondition<2>::Type::displacement, select_part(domain, "top"),
                   [delta](const Vec2&, const Vec2&, double) { return Vec2(0.0, -delta); }, "top"},
                  {BoundaryCondition<2>::Type::slip, select_part(domain, "bottom"), zero, "bottom"},
                  {BoundaryCondition<2>::Type::slip, select_part(domain, "left"), zero, "left"},
                  {BoundaryCondition<2>::Type::slip, select_part(domain, "right"), zero, "right"}};
  TotalLagrangian<2> model(p, domain, disc.node_count(), disc.quadrature, nullptr, disc.boundary,
                           disc.at_boundary);
  NewtonSettings s;
  s.load_factors = {0.1, 0.25, 0.5, 0.75, 1.0};
  s.tolerance = 1e-12;
  std::ostringstream log;
  const StaticSolution sol = solve_logged(model, s, log);
  INFO(log.str());
  // The material point along the same path.
  MaterialState<2> point;
  MaterialUpdate<2> last;
  for (const double f : s.load_factors) {
    last = update(Material(law), Mat2(Eigen::Vector2d(1.0, 1.0 - f * delta).asDiagonal()), point, false);
    point = last.state;
  }
  REQUIRE(point.alpha > 0.02);
  const double scale = std::abs(last.stress(1, 1));
  double worst_stress = 0.0, worst_alpha = 0.0;
  for (Index k = 0; k < disc.quadrature.size(); ++k) {
    const TotalLagrangian<2>::PointResponse r = model.response(k, sol.coefficients);
    const Mat2 f = model.deformation_gradient(k, sol.coefficients);
    worst_stress = std::max(worst_stress, (cauchy_stress(law, last.stress, f) - r.cauchy).norm() / scale);
    worst_alpha = std::max(worst_alpha, std::abs(r.state.alpha - point.alpha) / point.alpha);
  }
  for (const MaterialState<2>& b : model.history().boundary)
    worst_alpha = std::max(worst_alpha, std::abs(b.alpha - point.alpha) / point.alpha);
  INFO("worst relative stress difference " << worst_stress << ", plastic strain " << worst_alpha);
  CHECK(worst_stress <= 1e-8);
  CHECK(worst_alpha <= 1e-8);
  // The plastic work: sum w_K D_K = the material point's D times the area.
  CHECK(std::abs(model.dissipated() - point.dissipation) <= 1e-8 * point.dissipation);
}

TEST_CASE("TL with J2: Newton keeps quadratic convergence through yield, and history is committed per step",
          "[galerkin][tl][plasticity]") {
  Block block(2.0, j2_law(20.0));  // yields at the clamp from a load factor of about 0.4
  block.problem.conditions.erase(block.problem.conditions.begin() + 1);
  TotalLagrangian<2> model = block.model();
  NewtonSettings s;
  s.load_steps = 3;
  s.tolerance = 1e-12;
  std::vector<double> dissipated;
  std::ostringstream log;
  s.log = &log;
  StageTimer timer;
  const StaticSolution sol = solve_static(model, block.disc.nodes, s, timer, [&](const LoadStepRecord&, const Eigen::VectorXd&) {
    dissipated.push_back(model.dissipated());
  });
  INFO(log.str());
  REQUIRE(sol.steps.size() == 3);
  // Yield is reached and spreads: the plastic work grows from step to step.
  CHECK(dissipated[1] > 0.0);
  CHECK(dissipated[2] > dissipated[1]);
  // Quadratic convergence: once |R| / |R0| = e_k < 1e-2, the next iterate has e_{k+1} <= e_k^1.8
  // (or round-off, 1e-11: the consistent tangent takes 1e-5 there in one iteration). A tangent
  // that is not the derivative of the update (the elastic one, the continuum one) converges
  // linearly, e_{k+1} ~ c e_k.
  for (const LoadStepRecord& step : sol.steps) {
    CAPTURE(step.factor);
    CHECK(step.history.size() <= 10);
    const double r0 = step.history[0].residual;
    for (std::size_t k = 1; k + 1 < step.history.size(); ++k) {
      const double e = step.history[k].residual / r0, next = step.history[k + 1].residual / r0;
      CAPTURE(k, e, next);
      if (e < 1e-2) CHECK(next <= std::max(std::pow(e, 1.8), 1e-11));
    }
  }
}

TEST_CASE("TL with J2: a cut-back leaves the history of the last converged step", "[galerkin][tl][plasticity]") {
  // A: one load step and few Newton iterations, so that the step is cut back; B: the load
  // factors A converged at, given outright. A failed attempt that touched the history would
  // make A's plastic state differ from B's.
  Block block(1.8, j2_law(20.0));
  block.problem.conditions.erase(block.problem.conditions.begin() + 1);
  TotalLagrangian<2> a = block.model(), b = block.model();
  NewtonSettings s;
  s.load_steps = 1;
  s.max_iterations = 4;
  std::ostringstream log;
  const StaticSolution sa = solve_logged(a, s, log);
  INFO(log.str());
  int cutbacks = 0;
  NewtonSettings sb;
  for (const LoadStepRecord& step : sa.steps) {
    cutbacks += step.cutbacks;
    sb.load_factors.push_back(step.factor);
  }
  REQUIRE(cutbacks > 0);
  sb.max_iterations = 4;
  const StaticSolution solution_b = solve_logged(b, sb, log);
  CHECK((sa.coefficients - solution_b.coefficients).norm() <= 1e-10 * solution_b.coefficients.norm());
  CHECK(std::abs(a.dissipated() - b.dissipated()) <= 1e-9 * b.dissipated());
  CHECK(b.dissipated() > 0.0);
}

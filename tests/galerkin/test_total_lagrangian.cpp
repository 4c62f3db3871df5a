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
  Discretisation disc;
  SolidProblem problem;

  explicit Block(double load, Material material = NeoHookean{lame_constants(1000.0, 0.3)}) {
    ElasticitySettings s;
    s.nodes.spacing = 0.25;
    StageTimer timer;
    disc = discretise(domain, s, timer);
    problem.material = material;
    problem.penalty_modulus = 1000.0;
    problem.spacing = s.nodes.spacing;
    problem.conditions = {
        {BoundaryCondition::Type::displacement, select_part(domain, "left"),
         [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); }, "clamp"},
        {BoundaryCondition::Type::slip, select_box(domain, Box{Vec2(0.0, -0.1), Vec2(1.0, 0.1)}),
         [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); }, "wall"},
        {BoundaryCondition::Type::traction, select_part(domain, "right"),
         [load](const Vec2&, const Vec2&, double) { return Vec2(-0.3 * load, -load); }, "load"}};
  }
  [[nodiscard]] TotalLagrangian model() const {
    return TotalLagrangian(problem, domain, disc.node_count(), disc.quadrature, nullptr, disc.boundary, disc.at_boundary);
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
StaticSolution solve_logged(const TotalLagrangian& model, NewtonSettings s, std::ostringstream& log) {
  s.log = &log;
  StageTimer timer;
  return solve_static(model, s, timer);
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
  const TotalLagrangian model = block.model();
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
  const TotalLagrangian model = block.model();
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
  const TotalLagrangian model = block.model();
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
  block.problem.conditions.push_back({BoundaryCondition::Type::displacement, select_part(block.domain, "right"),
                                      [](const Vec2&, const Vec2&, double) { return Vec2(-12.0, 0.0); }, "push"});
  block.problem.conditions.erase(block.problem.conditions.begin() + 1, block.problem.conditions.begin() + 3);
  const TotalLagrangian model = block.model();
  NewtonSettings s;
  s.load_steps = 1;
  s.max_cutbacks = 1;
  s.line_search = false;
  StageTimer timer;
  const std::string m = testing::message_of<NumericalError>([&] { (void)solve_static(model, s, timer); });
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
  block.problem.conditions.push_back({BoundaryCondition::Type::pressure, select_part(block.domain, "top"), {}, "top",
                                      [p0](const Vec2& x, double t) { return p0 * (1.0 + x.x() / 4.0) * (1.0 + t); }});
  return block;
}
}  // namespace

TEST_CASE("follower pressure: the load stiffness equals finite differences of the pressure force", "[galerkin][tl]") {
  const Block block = pressed_block(20.0);
  const TotalLagrangian model = block.model();
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
  SolidProblem bare = block.problem;
  bare.conditions.pop_back();
  const TotalLagrangian without(bare, block.domain, block.disc.node_count(), block.disc.quadrature, nullptr,
                                block.disc.boundary, block.disc.at_boundary);
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
  traction.problem.conditions.back() = {BoundaryCondition::Type::traction, select_part(traction.domain, "top"),
                                        [](const Vec2& x, const Vec2& n, double t) {
                                          return Vec2(-20.0 * (1.0 + x.x() / 4.0) * (1.0 + t) * n);
                                        },
                                        "top"};
  const LoadState load{0.7, 0.3};
  const TotalLagrangian a = pressed.model(), b = traction.model();
  REQUIRE(a.symmetric());
  const Eigen::VectorXd fa = a.external_force(load), fb = b.external_force(load);
  CHECK((fa - fb).norm() <= 1e-14 * fb.norm());
}

TEST_CASE("Nitsche slip and clamp terms: their tangent equals finite differences at a deformed state", "[galerkin][tl]") {
  const Block block(0.0);
  const Eigen::VectorXd d = smooth_field(block.disc.nodes, 0.05);
  const LoadState load{0.7, 0.0};
  const auto model_of = [&](std::vector<BoundaryCondition> conditions) {
    SolidProblem p = block.problem;
    p.conditions = std::move(conditions);
    return TotalLagrangian(p, block.domain, block.disc.node_count(), block.disc.quadrature, nullptr, block.disc.boundary,
                           block.disc.at_boundary);
  };
  const TotalLagrangian none = model_of({});
  for (std::size_t c = 0; c < 2; ++c) {  // the clamp, then the slip wall
    const TotalLagrangian with = model_of({block.problem.conditions[c]});
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

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
/// method, with a slip wall at y = 0 for x > 3 and a downward traction on x = 4.
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
        {BoundaryCondition::Type::displacement, Box{Vec2(-0.1, -0.1), Vec2(0.1, 1.1)},
         [](const Vec2&, const Vec2&) { return Vec2(0.0, 0.0); }, "clamp"},
        {BoundaryCondition::Type::slip, Box{Vec2(3.0, -0.1), Vec2(4.0, 0.1)},
         [](const Vec2&, const Vec2&) { return Vec2(0.0, 0.0); }, "wall"},
        {BoundaryCondition::Type::traction, Box{Vec2(3.9, -0.1), Vec2(4.1, 1.1)},
         [load](const Vec2&, const Vec2&) { return Vec2(-0.3 * load, -load); }, "load"}};
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

}  // namespace

TEST_CASE("TL tangent equals finite differences of the residual (Neo-Hookean, Nitsche, slip)", "[galerkin][tl]") {
  const Block block(0.0);
  const TotalLagrangian model = block.model();
  REQUIRE_FALSE(model.symmetric());
  const Eigen::VectorXd d = smooth_field(block.disc.nodes, 0.05);
  const LoadState load{0.7, 0.0};
  const auto residual = [&](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(model.internal_force(x) + model.constraint_force(x, load));
  };
  SparseMatrix k = model.zero_matrix();
  model.tangent(d, k);
  const Eigen::MatrixXd dense(k);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd dir(d.size());
    for (Eigen::Index i = 0; i < d.size(); ++i) dir[i] = u(rng);
    const double h = 1e-6;
    const Eigen::VectorXd fd = (residual(d + h * dir) - residual(d - h * dir)) / (2 * h);
    const Eigen::VectorXd kd = dense * dir;
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
  const Block block(4.0);  // tip deflection about a quarter of the length
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
  block.problem.conditions.push_back({BoundaryCondition::Type::displacement, Box{Vec2(3.9, -0.1), Vec2(4.1, 1.1)},
                                      [](const Vec2&, const Vec2&) { return Vec2(-12.0, 0.0); }, "push"});
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

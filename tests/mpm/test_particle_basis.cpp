// Partition of unity and linear completeness of every MPM basis, and gradients against
// finite differences, at random particle positions including next to the walls.

#include <catch2/catch.hpp>
#include <Eigen/LU>
#include <random>

#include "mfree/mpm/grid_transfer.hpp"
#include "mfree/mpm/particle_basis.hpp"

using namespace mfree;

namespace {

struct Case {
  MPMMethod method;
  int degree;
};
const Case cases[] = {{MPMMethod::classic, 1}, {MPMMethod::ugimp, 1}, {MPMMethod::cpdi, 1},
                      {MPMMethod::bspline, 2}, {MPMMethod::bspline, 3}};

const Box domain{Vec2(0.0, 0.0), Vec2(1.0, 0.75)};

struct Weights {
  std::vector<Index> node;
  std::vector<double> S;
  std::vector<Vec2> G;
};
Weights weights_at(const ParticleBasis& b, const Vec2& x, const Mat2& F, const Vec2& half) {
  WeightTable table;
  b.resize(table, 1);
  b.evaluate(x, F, half, table, 0);
  Weights w;
  table.for_each(0, [&](Index node, double S, const Vec2& G) {
    w.node.push_back(node);
    w.S.push_back(S);
    w.G.push_back(G);
  });
  REQUIRE(static_cast<int>(w.node.size()) == b.stride());
  return w;
}

}  // namespace

TEST_CASE("B-spline axis: Greville nodes reproduce x, the end functions interpolate", "[mpm]") {
  for (int p = 1; p <= 3; ++p) {
    const BSplineAxis a(0.5, 0.25, 6, p);
    CHECK(a.size() == 6 + p);
    CHECK(a.node(0) == 0.5);
    CHECK(a.node(a.size() - 1) == Approx(2.0).epsilon(1e-15));
    for (double x : {0.5, 0.51, 0.75, 1.3, 1.999, 2.0}) {
      const auto v = a.evaluate(x);
      double one = 0.0, lin = 0.0, d_one = 0.0, d_lin = 0.0;
      for (int k = 0; k <= p; ++k) {
        one += v.value[k];
        lin += a.node(v.first + k) * v.value[k];
        d_one += v.derivative[k];
        d_lin += a.node(v.first + k) * v.derivative[k];
        CHECK(v.value[k] >= 0.0);
      }
      CHECK(std::abs(one - 1.0) <= 1e-14);
      CHECK(std::abs(lin - x) <= 1e-14);
      CHECK(std::abs(d_one) <= 1e-12);
      CHECK(std::abs(d_lin - 1.0) <= 1e-12);
    }
    // Only N_0 is non-zero at the left end and only N_{n-1} at the right one.
    const auto left = a.evaluate(0.5), right = a.evaluate(2.0);
    CHECK(left.first == 0);
    CHECK(left.value[0] == 1.0);
    CHECK(right.first + p == a.size() - 1);
    CHECK(std::abs(right.value[p] - 1.0) <= 1e-15);
  }
}

TEST_CASE("B-spline axis: the closed form on uniform cells is the Cox-de Boor recursion", "[mpm]") {
  // evaluate() uses the uniform B-spline's pieces on cells p - 1 .. cells - p and the recursion
  // elsewhere: on every cell, the knots included, both must give the same functions to a few
  // ulps (values, and derivatives times h, are O(1)).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int p = 1; p <= 3; ++p) {
    const BSplineAxis a(-0.3, 0.07, 9, p);
    std::vector<double> xs;
    for (int j = 0; j <= a.cells() + 2 * p; ++j) xs.push_back(a.knot(j));
    for (int trial = 0; trial < 2000; ++trial) xs.push_back(a.lo() + (a.hi() - a.lo()) * u(rng));
    double worst_value = 0.0, worst_derivative = 0.0;
    for (double x : xs) {
      const auto closed = a.evaluate(x), recursive = a.cox_de_boor(x);
      REQUIRE(closed.first == recursive.first);
      for (int k = 0; k <= p; ++k) {
        worst_value = std::max(worst_value, std::abs(closed.value[k] - recursive.value[k]));
        worst_derivative = std::max(worst_derivative, std::abs(closed.derivative[k] - recursive.derivative[k]) * a.spacing());
      }
    }
    INFO("degree " << p << ": values " << worst_value << ", derivatives " << worst_derivative);
    CHECK(worst_value <= 1e-15);
    CHECK(worst_derivative <= 1e-15);
  }
}

TEST_CASE("quadratic B-spline: the interior function is the uniform quadratic spline", "[mpm]") {
  // Away from the ends the open knot vector is uniform: N(x) = (1/2) s^2, 3/4 - (s - 3/2)^2, ...
  const BSplineAxis a(0.0, 1.0, 8, 2);
  for (double x : {3.1, 3.5, 3.99}) {
    const auto v = a.evaluate(x);  // cell [3, 4]: functions N_3 .. N_5, N_3 centred at 3.5 - 1
    const double s = x - 3.0;
    CHECK(v.value[0] == Approx(0.5 * (1 - s) * (1 - s)).epsilon(1e-14));
    CHECK(v.value[1] == Approx(0.75 - (s - 0.5) * (s - 0.5)).epsilon(1e-14));
    CHECK(v.value[2] == Approx(0.5 * s * s).epsilon(1e-14));
    CHECK(v.derivative[1] == Approx(-2.0 * (s - 0.5)).margin(1e-14));
  }
}

TEST_CASE("every MPM basis is a partition of unity and linearly complete, walls included", "[mpm]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Case& c : cases) {
    const Grid grid(domain, 8, c.degree, grid_padding(c.method));
    const ParticleBasis basis(c.method, grid);
    const double h = grid.spacing();
    const Vec2 half(h / 6.0, h / 6.0);  // 9 particles per cell
    double worst = 0.0;
    for (int trial = 0; trial < 400; ++trial) {
      // A quarter of the points within a particle half size of a wall.
      Vec2 x(u(rng), 0.75 * u(rng));
      if (trial % 4 == 0) x.x() = half.x() * u(rng);
      if (trial % 4 == 1) x.y() = 0.75 - half.y() * u(rng);
      Mat2 F = Mat2::Identity();
      if (c.method == MPMMethod::cpdi) F += 0.4 * (Mat2::Random());
      if (F.determinant() < 0.3) F = Mat2::Identity();
      const Weights w = weights_at(basis, x, F, half);
      double one = 0.0;
      Vec2 lin = Vec2::Zero(), d_one = Vec2::Zero();
      Mat2 d_lin = Mat2::Zero();
      for (int k = 0; k < basis.stride(); ++k) {
        const Vec2 xi = grid.node(w.node[k]);
        one += w.S[k];
        lin += w.S[k] * xi;
        d_one += w.G[k];
        d_lin += xi * w.G[k].transpose();
      }
      worst = std::max({worst, std::abs(one - 1.0), (lin - x).norm(), h * d_one.norm(),
                        (d_lin - Mat2::Identity()).norm()});
    }
    INFO(to_string(c.method) << " degree " << c.degree);
    CHECK(worst <= 1e-12);
  }
}

TEST_CASE("MPM basis gradients are the derivatives of the weights (classic, uGIMP, B-splines)", "[mpm]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.02, 0.98);
  for (const Case& c : cases) {
    if (c.method == MPMMethod::cpdi) continue;  // CPDI's G is the average of grad N, not grad S
    const Grid grid(domain, 8, c.degree, grid_padding(c.method));
    const ParticleBasis basis(c.method, grid);
    const Vec2 half = Vec2::Constant(grid.spacing() / 6.0);
    const double eps = 1e-6;
    double worst = 0.0;
    for (int trial = 0; trial < 100; ++trial) {
      const Vec2 x(u(rng), 0.75 * u(rng));
      const Weights w = weights_at(basis, x, Mat2::Identity(), half);
      for (int d = 0; d < 2; ++d) {
        const Vec2 e = eps * Vec2::Unit(d);
        const Weights wp = weights_at(basis, x + e, Mat2::Identity(), half);
        const Weights wm = weights_at(basis, x - e, Mat2::Identity(), half);
        // Same cell on both sides (a kink of the hats between them spoils the difference).
        if (wp.node != w.node || wm.node != w.node) continue;
        for (int k = 0; k < basis.stride(); ++k)
          worst = std::max(worst, std::abs((wp.S[k] - wm.S[k]) / (2 * eps) - w.G[k][d]) * grid.spacing());
      }
    }
    INFO(to_string(c.method) << " degree " << c.degree);
    CHECK(worst <= 1e-7);
  }
}

TEST_CASE("particle to grid conserves mass and momentum to round-off", "[mpm]") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Case& c : cases) {
    const Grid grid(domain, 8, c.degree, grid_padding(c.method));
    const ParticleBasis basis(c.method, grid);
    const Vec2 half = Vec2::Constant(grid.spacing() / 6.0);
    const Index n = 2000;
    WeightTable table;
    basis.resize(table, n);
    std::vector<double> mass(n);
    std::vector<Vec2> momentum(n);
    double total_mass = 0.0;
    Vec2 total_momentum = Vec2::Zero();
    for (Index p = 0; p < n; ++p) {
      const Vec2 x(u(rng), 0.75 * u(rng));
      basis.evaluate(x, Mat2::Identity(), half, table, p);
      mass[p] = 0.5 + u(rng);
      momentum[p] = mass[p] * Vec2(u(rng) - 0.5, u(rng) - 0.5);
      total_mass += mass[p];
      total_momentum += momentum[p];
    }
    std::vector<Eigen::Vector3d> g;
    ScatterBuffers<Eigen::Vector3d> partial;
    scatter<Eigen::Vector3d>(table, grid.size(), g, partial, [&](Index q) {
      return [&, q](double S, const Vec2&) { return Eigen::Vector3d(S * mass[q], S * momentum[q].x(), S * momentum[q].y()); };
    });
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& v : g) sum += v;
    INFO(to_string(c.method) << " degree " << c.degree);
    CHECK(std::abs(sum[0] - total_mass) <= 1e-13 * total_mass);
    CHECK((sum.tail<2>() - total_momentum).norm() <= 1e-13 * total_mass);
  }
}

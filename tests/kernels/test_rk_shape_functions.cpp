#include <algorithm>
#include <catch2/catch.hpp>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"

using namespace mfree;

namespace {

/// Random cloud of n x n points in [0, 1]^2 (one per lattice cell, fully randomised).
std::vector<Vec2> random_unit_cloud(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> p;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) p.emplace_back((i + u(rng)) / n, (j + u(rng)) / n);
  return p;
}

}  // namespace

TEST_CASE("RK shape functions reproduce their basis, values and gradients, on random clouds",
          "[kernels]") {
  const int n = 20;
  const double h = 1.0 / n;
  const auto nodes = random_unit_cloud(n, 7);
  for (RKOrder order : {RKOrder::linear, RKOrder::quadratic})
    for (Window window : {Window::cubic_bspline, Window::quadratic_spline})
      for (SupportShape shape : {SupportShape::circular, SupportShape::tensor}) {
        CAPTURE(to_string(order), to_string(window), to_string(shape));
        RKSettings s;
        s.order = order;
        s.window = window;
        s.support = shape;
        s.radius = (order == RKOrder::linear ? 2.5 : 3.5) * h;
        const RKShapeFunctions<2> rk(nodes, s);
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> u(0.2, 0.8);
        ShapeValues<2> v;
        double worst_value = 0.0, worst_grad = 0.0;
        for (int trial = 0; trial < 200; ++trial) {
          const Vec2 x(u(rng), u(rng));
          rk.evaluate(x, v);
          // sum phi_I p(x_I) = p(x) for p in {1, x, y (, x^2, xy, y^2)}, and the gradients.
          double s0 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
          Vec2 g0 = Vec2::Zero();
          Mat2 gx = Mat2::Zero();  // sum x_I (x) grad phi_I
          Vec2 gxx = Vec2::Zero(), gxy = Vec2::Zero(), gyy = Vec2::Zero();
          for (std::size_t k = 0; k < v.size(); ++k) {
            const Vec2& p = nodes[v.nodes[k]];
            const double f = v.phi[k];
            s0 += f;
            sx += f * p.x();
            sy += f * p.y();
            sxx += f * p.x() * p.x();
            sxy += f * p.x() * p.y();
            syy += f * p.y() * p.y();
            g0 += v.grad[k];
            gx += p * v.grad[k].transpose();
            gxx += p.x() * p.x() * v.grad[k];
            gxy += p.x() * p.y() * v.grad[k];
            gyy += p.y() * p.y() * v.grad[k];
          }
          worst_value = std::max({worst_value, std::abs(s0 - 1), std::abs(sx - x.x()), std::abs(sy - x.y())});
          // Gradients scale like 1/h: compare relative to that scale.
          worst_grad = std::max({worst_grad, g0.norm() * h, (gx - Mat2::Identity()).norm() * h});
          if (order == RKOrder::quadratic) {
            worst_value = std::max({worst_value, std::abs(sxx - x.x() * x.x()),
                                    std::abs(sxy - x.x() * x.y()), std::abs(syy - x.y() * x.y())});
            worst_grad = std::max({worst_grad, (gxx - Vec2(2 * x.x(), 0)).norm() * h,
                                   (gxy - Vec2(x.y(), x.x())).norm() * h,
                                   (gyy - Vec2(0, 2 * x.y())).norm() * h});
          }
        }
        CHECK(worst_value <= 1e-12);
        CHECK(worst_grad <= 1e-12);
      }
}

TEST_CASE("RK gradients are the derivatives of the values (central differences)", "[kernels]") {
  const auto nodes = random_unit_cloud(12, 3);
  for (RKOrder order : {RKOrder::linear, RKOrder::quadratic}) {
    RKSettings s;
    s.order = order;
    s.radius = (order == RKOrder::linear ? 2.2 : 3.2) / 12.0;
    const RKShapeFunctions<2> rk(nodes, s);
    const Vec2 x(0.43, 0.57);
    ShapeValues<2> v, vp, vm;
    rk.evaluate(x, v);
    const double e = 1e-6;
    for (int dir = 0; dir < 2; ++dir) {
      const Vec2 dx = e * Vec2::Unit(dir);
      rk.evaluate(x + dx, vp, false);
      rk.evaluate(x - dx, vm, false);
      REQUIRE(vp.nodes == v.nodes);
      REQUIRE(vm.nodes == v.nodes);
      for (std::size_t k = 0; k < v.size(); ++k)
        CHECK(v.grad[k][dir] == Approx((vp.phi[k] - vm.phi[k]) / (2 * e)).margin(1e-6));
    }
  }
}

TEST_CASE("a point whose neighbours cannot span the basis gets a clear error", "[kernels]") {
  // Nodes on one line: M is singular for a linear basis everywhere.
  std::vector<Vec2> line;
  for (int i = 0; i < 10; ++i) line.emplace_back(0.1 * i, 0.0);
  RKSettings s;
  s.radius = 0.35;
  const RKShapeFunctions<2> rk(line, s);
  ShapeValues<2> v;
  REQUIRE_THROWS_AS(rk.evaluate(Vec2(0.45, 0.01), v), NumericalError);
  REQUIRE_THROWS_WITH(rk.evaluate(Vec2(0.45, 0.01), v),
                      Catch::Contains("(0.45, 0.01)") && Catch::Contains("neighbour") &&
                          Catch::Contains("Increase the support radius"));
  // Too few neighbours: a lattice with a support too small for a quadratic basis.
  std::vector<Vec2> grid;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) grid.emplace_back(0.1 * i, 0.1 * j);
  s.order = RKOrder::quadratic;
  s.radius = 0.11;
  const RKShapeFunctions<2> small(grid, s);
  REQUIRE_THROWS_WITH(small.evaluate(Vec2(0.45, 0.45), v),
                      Catch::Contains("4 neighbour(s)") && Catch::Contains("at least 6"));
  // The same grid with an adequate support works.
  s.radius = 0.3;
  const RKShapeFunctions<2> ok(grid, s);
  REQUIRE_NOTHROW(ok.evaluate(Vec2(0.45, 0.45), v));
  CHECK_THROWS_AS(RKShapeFunctions<2>(grid, RKSettings{}), InputError);  // radius 0
}

TEST_CASE(
    "RK shape functions in 3D reproduce their basis and its gradients on random clouds, and are "
    "differentiable",
    "[kernels][3d]") {
  using P3 = Point<3>;
  const int n = 8;
  const double h = 1.0 / n;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<P3> nodes;  // one point per lattice cell, anywhere in it
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) nodes.emplace_back((i + u(rng)) * h, (j + u(rng)) * h, (k + u(rng)) * h);
  // The monomials of the quadratic basis in x, and their gradients.
  const auto monomials = [](const P3& x) {
    return std::array<double, 10>{1.0,         x[0],        x[1],        x[2],        x[0] * x[0],
                                  x[0] * x[1], x[0] * x[2], x[1] * x[1], x[1] * x[2], x[2] * x[2]};
  };
  const auto monomial_gradients = [](const P3& x) {
    std::array<P3, 10> g;
    g[0] = P3::Zero();
    g[1] = P3(1, 0, 0), g[2] = P3(0, 1, 0), g[3] = P3(0, 0, 1);
    g[4] = P3(2 * x[0], 0, 0), g[5] = P3(x[1], x[0], 0), g[6] = P3(x[2], 0, x[0]);
    g[7] = P3(0, 2 * x[1], 0), g[8] = P3(0, x[2], x[1]), g[9] = P3(0, 0, 2 * x[2]);
    return g;
  };
  for (RKOrder order : {RKOrder::linear, RKOrder::quadratic})
    for (SupportShape shape : {SupportShape::circular, SupportShape::tensor}) {
      CAPTURE(to_string(order), to_string(shape));
      RKSettings s;
      s.order = order;
      s.support = shape;
      s.radius = (order == RKOrder::linear ? 2.5 : 3.5) * h;
      const RKShapeFunctions<3> rk(nodes, s);
      CHECK(rk.basis_size() == (order == RKOrder::linear ? 4 : 10));
      const int terms = rk.basis_size();
      std::uniform_real_distribution<double> inner(0.3, 0.7);
      ShapeValues<3> v, plus, minus;
      double worst_value = 0.0, worst_grad = 0.0, worst_fd = 0.0;
      for (int trial = 0; trial < 50; ++trial) {
        const P3 x(inner(rng), inner(rng), inner(rng));
        rk.evaluate(x, v);
        std::array<double, 10> sum{};
        std::array<P3, 10> grad_sum;
        grad_sum.fill(P3::Zero());
        for (std::size_t k = 0; k < v.size(); ++k) {
          const auto m = monomials(nodes[v.nodes[k]]);
          for (int t = 0; t < terms; ++t) {
            sum[t] += v.phi[k] * m[t];
            grad_sum[t] += m[t] * v.grad[k];
          }
        }
        const auto m = monomials(x);
        const auto g = monomial_gradients(x);
        for (int t = 0; t < terms; ++t) {
          worst_value = std::max(worst_value, std::abs(sum[t] - m[t]));
          worst_grad = std::max(worst_grad, (grad_sum[t] - g[t]).norm());
        }
        // grad phi_I against central differences of phi_I, node by node.
        const double d = 1e-6;
        for (int c = 0; c < 3; ++c) {
          P3 e = P3::Zero();
          e[c] = d;
          rk.evaluate(x + e, plus, false);
          rk.evaluate(x - e, minus, false);
          // A node whose support edge lies within d of x is in one list only; its window and
          // the window's slope vanish there, so it counts with phi = 0 where it is missing.
          const auto phi_of = [](const ShapeValues<3>& w, Index node) {
            const auto at = std::find(w.nodes.begin(), w.nodes.end(), node);
            return at == w.nodes.end() ? 0.0 : w.phi[at - w.nodes.begin()];
          };
          for (std::size_t k = 0; k < v.size(); ++k)
            worst_fd = std::max(
                worst_fd,
                std::abs((phi_of(plus, v.nodes[k]) - phi_of(minus, v.nodes[k])) / (2 * d) - v.grad[k][c]));
        }
      }
      CHECK(worst_value < 1e-12);
      CHECK(worst_grad < 1e-10);
      CHECK(worst_fd < 1e-6);
    }
}

TEST_CASE("a 3D point whose neighbours lie in one plane cannot take a linear basis", "[kernels][3d]") {
  std::vector<Point<3>> nodes;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) nodes.emplace_back(0.25 * i, 0.25 * j, 0.0);
  RKSettings s;
  s.radius = 0.6;
  const RKShapeFunctions<3> rk(nodes, s);
  ShapeValues<3> v;
  CHECK_THROWS_WITH(
      rk.evaluate(Point<3>(0.5, 0.5, 0.1), v),
      Catch::Contains("point (0.5, 0.5, 0.1) is singular") && Catch::Contains("not all on one plane"));
  // The same nodes lifted off the plane, one by one in a checkerboard, span it.
  for (std::size_t i = 0; i < nodes.size(); i += 2) nodes[i][2] = 0.2;
  const RKShapeFunctions<3> lifted(nodes, s);
  lifted.evaluate(Point<3>(0.5, 0.5, 0.1), v);
  double sum = 0.0;
  for (double p : v.phi) sum += p;
  CHECK(std::abs(sum - 1.0) < 1e-13);
}

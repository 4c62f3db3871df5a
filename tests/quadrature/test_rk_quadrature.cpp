#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "../test_support.hpp"
#include "mfree/clouds/point_cloud.hpp"
#include "mfree/quadrature/background_lattice.hpp"
#include "mfree/quadrature/rk_quadrature.hpp"

using namespace mfree;

namespace {

Domain mesh(const std::string& name) {
  return Domain::from_file(mfree::testing::source_dir() + "/meshes/" + name);
}

/// RK quadrature weights on a quadrature cloud of the given kind and spacing.
std::pair<std::vector<Vec2>, std::vector<double>> rk_rule(const Domain& d, CloudKind kind, double h,
                                                          RKOrder order, std::uint64_t seed = 3) {
  CloudSettings cs;
  cs.kind = kind;
  cs.spacing = h;
  cs.perturbation = 0.5;
  cs.cell_centred = true;
  cs.seed = seed;
  std::vector<Vec2> x = make_cloud(d, cs);
  const double factor = order == RKOrder::linear ? 2.0 : 3.0;
  RKSettings rs;
  rs.order = order;
  rs.radius = factor * h;
  if (kind != CloudKind::lattice) rs.node_radii = nodal_support_radii(x, h, factor * 1.25);
  const RKShapeFunctions<2> rk(x, rs);
  const BackgroundLattice<2> lattice(d, h / 2, order == RKOrder::linear ? 1 : 2);
  return {x, rk_quadrature_weights(rk, lattice)};
}

}  // namespace

TEST_CASE("lattice rule: Lagrange cell integrals are exact for clipped polygons", "[quadrature]") {
  // Triangle (0,0)-(1,0)-(0,1) in the unit cell: integral of (1-s)(1-t) is 5/24 and of s t 1/24.
  double out[9];
  lagrange_cell_integrals({{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}}, Vec2(0, 0), 1.0, 1, out);
  CHECK(out[0] == Approx(5.0 / 24.0).epsilon(1e-14));
  CHECK(out[3] == Approx(1.0 / 24.0).epsilon(1e-14));
  CHECK(out[1] == Approx(1.0 / 8.0).epsilon(1e-14));  // s (1 - t) over the triangle
  // Simpson weights on the full cell of side 2: (1/6, 2/3, 1/6)^2 * 4.
  lagrange_cell_integrals({{Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)}}, Vec2(0, 0), 2.0, 2, out);
  CHECK(out[4] == Approx(4.0 * 4.0 / 9.0).epsilon(1e-14));
  CHECK(out[0] == Approx(4.0 / 36.0).epsilon(1e-14));
  CHECK(out[1] == Approx(4.0 / 9.0).epsilon(1e-14));
}

TEST_CASE("background lattice weights integrate 1 and x exactly on every mesh", "[quadrature]") {
  for (const std::string name : {"rectangle.wkt", "l_shape.wkt", "plate_with_hole.wkt"}) {
    const Domain d = mesh(name);
    for (int order : {1, 2}) {
      CAPTURE(name, order);
      const BackgroundLattice<2> lattice(d, 0.037, order);
      double s = 0.0;
      Vec2 m = Vec2::Zero();
      for (std::size_t v = 0; v < lattice.points().size(); ++v) {
        s += lattice.weights()[v];
        m += lattice.weights()[v] * lattice.points()[v];
      }
      CHECK(lattice.cut_cells() > 0);
      CHECK(std::abs(s - d.area()) <= 1e-12 * d.area());
      CHECK((m - d.first_moment()).norm() <= 1e-12 * d.area());
    }
  }
}

TEST_CASE("RK quadrature weights: sum = |Omega| and first moments = integral of x to round-off",
          "[quadrature]") {
  // Guaranteed to round-off: every local grid is a window of one background lattice, so
  // partition of unity and linear reproduction of the quadrature-cloud functions carry the
  // lattice rule's exactness (previous test) over to the weights.
  for (const std::string name : {"rectangle.wkt", "l_shape.wkt", "plate_with_hole.wkt"})
    for (CloudKind kind : {CloudKind::lattice, CloudKind::perturbed, CloudKind::random})
      for (RKOrder order : {RKOrder::linear, RKOrder::quadratic}) {
        CAPTURE(name, to_string(kind), to_string(order));
        const Domain d = mesh(name);
        const auto [x, w] = rk_rule(d, kind, 0.08, order);
        double s = 0.0;
        Vec2 m = Vec2::Zero();
        Eigen::Vector3d second = Eigen::Vector3d::Zero();  // x^2, xy, y^2
        for (std::size_t k = 0; k < x.size(); ++k) {
          s += w[k];
          m += w[k] * x[k];
          second += w[k] * Eigen::Vector3d(x[k].x() * x[k].x(), x[k].x() * x[k].y(), x[k].y() * x[k].y());
        }
        CHECK(std::abs(s - d.area()) <= 1e-12 * d.area());
        CHECK((m - d.first_moment()).norm() <= 1e-12 * d.area());
        if (order == RKOrder::quadratic && name == "rectangle.wkt") {
          // Quadratic RK with Simpson's rule: second moments exact too ([-1,1] x [-1/2,1/2]).
          CHECK(second[0] == Approx(2.0 / 3.0).epsilon(1e-12));
          CHECK(std::abs(second[1]) <= 1e-12);
          CHECK(second[2] == Approx(1.0 / 6.0).epsilon(1e-12));
        }
      }
}

TEST_CASE("RK quadrature converges at rate >= 1.8 for linear RK, lattice and random clouds",
          "[quadrature]") {
  // f1 of seed 003 on the 2 x 1 rectangle in corner coordinates (see integration_study.hpp).
  const Domain d = mesh("rectangle.wkt");
  const double pi = std::numbers::pi, exact = 8.0 / (pi * pi);
  const auto f1 = [&](const Vec2& x) { return std::sin(pi * (x.x() + 1.0) / 2.0) * std::sin(pi * (x.y() + 0.5)); };
  for (CloudKind kind : {CloudKind::lattice, CloudKind::random}) {
    CAPTURE(to_string(kind));
    std::vector<double> err, h;
    for (double spacing : {0.05, 0.025, 0.0125}) {
      const auto [x, w] = rk_rule(d, kind, spacing, RKOrder::linear, 7);
      double q = 0.0;
      for (std::size_t k = 0; k < x.size(); ++k) q += w[k] * f1(x[k]);
      err.push_back(std::abs(q - exact));
      h.push_back(std::sqrt(d.area() / static_cast<double>(x.size())));
    }
    for (std::size_t k = 1; k < err.size(); ++k) {
      const double rate = std::log(err[k - 1] / err[k]) / std::log(h[k - 1] / h[k]);
      CAPTURE(k, err[k - 1], err[k]);
      CHECK(rate >= 1.8);
    }
  }
}

TEST_CASE("quadratic RK weights: negative weights are counted", "[quadrature]") {
  const NegativeWeights none = negative_weights({0.1, 0.2});
  CHECK(none.count == 0);
  const NegativeWeights some = negative_weights({0.1, -0.2, 0.3, -0.05});
  CHECK(some.count == 2);
  CHECK(some.most_negative == -0.2);
}

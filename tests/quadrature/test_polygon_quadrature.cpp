#include <catch2/catch.hpp>
#include <cmath>

#include "../test_support.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/polygon_integrals.hpp"
#include "mfree/quadrature/gauss_cells.hpp"
#include "mfree/quadrature/polygon_quadrature.hpp"

using namespace mfree;

TEST_CASE("polygon rule: exact for polynomials of degree 2 m - 2 on a nonconvex polygon, points inside",
          "[quadrature]") {
  // An L with a notch: CGAL cuts it into convex pieces, each fanned.
  const Ring l{{0, 0}, {2, 0}, {2, 1}, {1.2, 1}, {1.2, 0.4}, {0.7, 0.4}, {0.7, 2}, {0, 2}};
  const Domain d = Domain::from_rings({l}, {{-1, -1, -1, -1, -1, -1, -1, -1}}, {}, "L");
  for (int m : {2, 3, 4}) {
    QuadratureRule<2> rule;
    REQUIRE(add_polygon_rule({l}, m, 2.0, rule));
    // x^a y^b against the exact integral over the L as the sum over unit-free rectangles.
    const auto rect = [](double x0, double x1, double y0, double y1, int a, int b) {
      return (std::pow(x1, a + 1) - std::pow(x0, a + 1)) / (a + 1) *
             (std::pow(y1, b + 1) - std::pow(y0, b + 1)) / (b + 1);
    };
    for (int a = 0; a <= 2 * m - 2; ++a)
      for (int b = 0; a + b <= 2 * m - 2; ++b) {
        const double exact =
            rect(0, 2, 0, 0.4, a, b) + rect(0, 0.7, 0.4, 2, a, b) + rect(1.2, 2, 0.4, 1, a, b);
        double sum = 0.0;
        for (std::size_t k = 0; k < rule.size(); ++k)
          sum += rule.weights[k] * std::pow(rule.points[k].x(), a) * std::pow(rule.points[k].y(), b);
        CAPTURE(m, a, b);
        CHECK(sum == Approx(exact).epsilon(1e-13));
      }
    for (std::size_t k = 0; k < rule.size(); ++k) {
      CHECK(d.contains(rule.points[k]));
      CHECK(rule.weights[k] > 0.0);
    }
  }
}

TEST_CASE(
    "Gauss cells on a curved domain: cut cells integrate area and first moment of the polygon to round-off",
    "[quadrature]") {
  const Domain d =
      Domain::from_file(mfree::testing::source_dir() + "/verification/lame/quarter_annulus_1024.geo");
  for (double h : {0.4, 0.2}) {
    const QuadratureRule<2> rule = gauss_cell_rule(d, h, 3);
    double area = 0.0;
    Vec2 moment = Vec2::Zero();
    for (std::size_t k = 0; k < rule.size(); ++k) {
      area += rule.weights[k];
      moment += rule.weights[k] * rule.points[k];
      REQUIRE(d.contains(rule.points[k]));
    }
    CAPTURE(h);
    CHECK(area == Approx(d.area()).epsilon(1e-13));
    CHECK((moment - d.first_moment()).norm() <= 1e-13 * d.first_moment().norm());
  }
}

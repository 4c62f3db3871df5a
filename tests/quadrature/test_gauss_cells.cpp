// Gauss cells of a solid (a box): tensor Gauss–Legendre points on cells fitted to it.
#include <catch2/catch.hpp>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/quadrature/gauss_cells.hpp"

using namespace mfree;

TEST_CASE("Gauss cells of a box solid integrate x^(2n-1) y^(2n-1) z^(2n-1) exactly, and no further",
          "[quadrature][3d]") {
  const Point<3> lo(-0.5, 0.0, 0.2), hi(1.0, 0.8, 0.6);
  const Solid box = Solid::box(lo, hi);
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    const QuadratureRule<3> rule = gauss_cell_rule(box, 0.3, n);
    // Cells: round(size / 0.3) per axis = 5 x 3 x 1, n^3 points each.
    CHECK(rule.size() == static_cast<std::size_t>(15 * n * n * n));
    for (const int d : {2 * n - 1, 2 * n}) {
      double sum = 0.0;
      for (std::size_t k = 0; k < rule.size(); ++k)
        sum += rule.weights[k] * std::pow(rule.points[k][0], d) * std::pow(rule.points[k][1], d) *
               std::pow(rule.points[k][2], d);
      double exact = 1.0;
      for (int a = 0; a < 3; ++a) exact *= (std::pow(hi[a], d + 1) - std::pow(lo[a], d + 1)) / (d + 1);
      const double error = std::abs(sum - exact) / std::abs(exact);
      if (d == 2 * n - 1)
        CHECK(error < 1e-13);
      else
        CHECK(error > 1e-8);
    }
  }
  CHECK_THROWS_AS(gauss_cell_rule(box, 0.0, 2), InputError);
}

#include <catch2/catch.hpp>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

using namespace mfree;

TEST_CASE("Gauss–Legendre with n points integrates x^d on [0, 1] exactly for d <= 2n - 1, and no further",
          "[quadrature]") {
  for (int n = 1; n <= 64; ++n) {
    const GaussLegendre1D g = gauss_legendre(n);
    REQUIRE(g.points.size() == static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      CHECK(g.weights[k] > 0.0);
      CHECK(g.points[k] > 0.0);
      CHECK(g.points[k] < 1.0);
      if (k > 0) CHECK(g.points[k] > g.points[k - 1]);
      CHECK(std::abs(g.points[k] + g.points[n - 1 - k] - 1.0) < 1e-15);  // symmetric about 1/2
      CHECK(g.weights[k] == g.weights[n - 1 - k]);
    }
    // The monomials centred at 1/2 keep the sums well conditioned at high degree:
    // integral of (x - 1/2)^d over [0, 1] = (1/2)^d / (d + 1) for even d, 0 for odd d.
    for (int d = 0; d <= 2 * n; ++d) {
      double sum = 0.0;
      for (int k = 0; k < n; ++k) sum += g.weights[k] * std::pow(g.points[k] - 0.5, d);
      const double exact = d % 2 ? 0.0 : std::pow(0.5, d) / (d + 1);
      const double error = std::abs(sum - exact) / std::pow(0.5, d);
      INFO("n = " << n << ", degree " << d << ": error " << error);
      if (d <= 2 * n - 1)
        CHECK(error < 1e-13);
      else if (n <= 8)        // the error at degree 2n, n!^4 / ((2n + 1) (2n)!^2) 4^n, is above 1e-5
        CHECK(error > 1e-6);  // there: the rule's order is sharp
    }
  }
  CHECK_THROWS_AS(gauss_legendre(0), InputError);
  CHECK_THROWS_AS(gauss_legendre(65), InputError);
}

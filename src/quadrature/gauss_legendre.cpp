#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "mfree/core/error.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

namespace {

/// P_n(z) and P_n'(z) by the three-term recurrence (k + 1) P_{k+1} = (2k + 1) z P_k - k P_{k-1}
/// and P_n' = n (z P_n - P_{n-1}) / (z^2 - 1) (|z| < 1).
std::pair<double, double> legendre_and_derivative(int n, double z) {
  double previous = 1.0, current = z;
  for (int k = 1; k < n; ++k) {
    const double next = ((2 * k + 1) * z * current - k * previous) / (k + 1);
    previous = current;
    current = next;
  }
  return {current, n * (z * current - previous) / (z * z - 1.0)};
}

}  // namespace

GaussLegendre1D gauss_legendre(int n) {
  if (n < 1 || n > 64) throw InputError(fmt::format("Gauss–Legendre: need 1..64 points, got {}", n));
  // The nodes on [-1, 1] are the roots of P_n, symmetric about 0: Newton's method from Tricomi's
  // estimate cos(pi (k + 3/4) / (n + 1/2)) of the k-th largest root, which lies in its basin for
  // every n; the weights are 2 / ((1 - z^2) P_n'(z)^2) (Abramowitz & Stegun 25.4.29).
  GaussLegendre1D rule;
  rule.points.resize(n);
  rule.weights.resize(n);
  for (int k = 0; k < (n + 1) / 2; ++k) {
    double z = std::cos(std::numbers::pi * (k + 0.75) / (n + 0.5));
    for (int iteration = 0; iteration < 100; ++iteration) {
      const auto [p, dp] = legendre_and_derivative(n, z);
      const double step = p / dp;
      z -= step;
      if (std::abs(step) <= 1e-15) break;
    }
    if (2 * k + 1 == n) z = 0.0;  // the middle node of an odd rule
    const double dp = legendre_and_derivative(n, z).second;
    const double weight = 1.0 / ((1.0 - z * z) * dp * dp);  // 2 / (...) mapped to [0, 1]
    rule.points[k] = 0.5 * (1.0 - z);
    rule.points[n - 1 - k] = 0.5 * (1.0 + z);
    rule.weights[k] = rule.weights[n - 1 - k] = weight;
  }
  return rule;
}

}  // namespace mfree

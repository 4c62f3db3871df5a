// The CPDIs' element nodes against Gauss quadrature of the elements' own shape functions:
// the closed-form weights w_k = (1 / V) int M_k and gradient integrals int grad M_k of the
// bilinear quadrilateral (random convex ones) and of the serendipity parallelogram.

#include <catch2/catch.hpp>
#include <Eigen/LU>
#include <cmath>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/mpm/domain_nodes.hpp"
#include "random_domains.hpp"

using namespace mfree;

namespace {

/// Reference coordinates of the element nodes: corners counter-clockwise from (-1, -1), then
/// the midsides of edges 0-1, 1-2, 2-3, 3-0.
const Vec2 reference[8] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}};

/// Bilinear M_k(xi, eta) and its derivatives in (xi, eta).
double bilinear(int k, const Vec2& s) { return 0.25 * (1 + reference[k].x() * s.x()) * (1 + reference[k].y() * s.y()); }
Vec2 bilinear_gradient(int k, const Vec2& s) {
  const Vec2& r = reference[k];
  return {0.25 * r.x() * (1 + r.y() * s.y()), 0.25 * r.y() * (1 + r.x() * s.x())};
}

/// The 8-node serendipity functions (Zienkiewicz's standard forms) and their derivatives.
double serendipity(int k, const Vec2& s) {
  const Vec2& r = reference[k];
  if (k < 4) return 0.25 * (1 + r.x() * s.x()) * (1 + r.y() * s.y()) * (r.x() * s.x() + r.y() * s.y() - 1);
  if (r.x() == 0) return 0.5 * (1 - s.x() * s.x()) * (1 + r.y() * s.y());
  return 0.5 * (1 + r.x() * s.x()) * (1 - s.y() * s.y());
}
Vec2 serendipity_gradient(int k, const Vec2& s) {
  const Vec2& r = reference[k];
  if (k < 4) {
    const double a = 1 + r.x() * s.x(), b = 1 + r.y() * s.y(), c = r.x() * s.x() + r.y() * s.y() - 1;
    return {0.25 * r.x() * b * (c + a), 0.25 * r.y() * a * (c + b)};
  }
  if (r.x() == 0) return {-s.x() * (1 + r.y() * s.y()), 0.5 * (1 - s.x() * s.x()) * r.y()};
  return {0.5 * r.x() * (1 - s.y() * s.y()), -s.y() * (1 + r.x() * s.x())};
}

/// 3 x 3 Gauss points on [-1, 1]^2: exact for degree 5 in each variable, more than any
/// integrand here has.
template <class F>
void gauss(F&& f) {
  const double a = std::sqrt(0.6), p[3] = {-a, 0.0, a}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f(Vec2(p[i], p[j]), w[i] * w[j]);
}

}  // namespace

TEST_CASE("bilinear quadrilateral: closed-form weights and gradient integrals are the integrals of M_k", "[mpm]") {
  std::mt19937_64 rng(17);
  double worst_w = 0.0, worst_g = 0.0, worst_V = 0.0;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const DomainCorners c = testing::random_quadrilateral(rng, Vec2(u(rng), u(rng)), testing::random_deformation(rng, 0.5),
                                                          Vec2(0.3, 0.2));
    const DomainNodes<4> nodes = bilinear_nodes(c, c[0], "test");
    double V = 0.0;
    std::array<double, 4> w{};
    std::array<Vec2, 4> g;
    g.fill(Vec2::Zero());  // Eigen's vectors start uninitialised
    gauss([&](const Vec2& s, double weight) {
      Mat2 dx = Mat2::Zero();  // d x / d (xi, eta)
      for (int k = 0; k < 4; ++k) dx += c[k] * bilinear_gradient(k, s).transpose();
      const double J = dx.determinant();
      V += weight * J;
      const Mat2 inverse_t = dx.inverse().transpose();
      for (int k = 0; k < 4; ++k) {
        w[k] += weight * J * bilinear(k, s);
        g[k] += weight * J * inverse_t * bilinear_gradient(k, s);
      }
    });
    worst_V = std::max(worst_V, std::abs(nodes.volume - V) / V);
    for (int k = 0; k < 4; ++k) {
      worst_w = std::max(worst_w, std::abs(nodes.weight[k] - w[k] / V));
      worst_g = std::max(worst_g, (nodes.gradient[k] - g[k]).norm() / std::sqrt(V));
      CHECK(nodes.point[k] == c[k]);
    }
  }
  INFO("volume " << worst_V << ", weights " << worst_w << ", gradient integrals " << worst_g);
  CHECK(worst_V <= 1e-14);
  CHECK(worst_w <= 1e-14);
  CHECK(worst_g <= 1e-14);
}

TEST_CASE("bilinear quadrilateral: a parallelogram has weights 1/4, a non-convex or inverted domain is refused", "[mpm]") {
  Mat2 F;
  F << 1.3, 0.4, -0.2, 0.8;
  const DomainNodes<4> nodes = bilinear_nodes(parallelogram_corners(Vec2(0.1, 0.2), F, Vec2(0.05, 0.03)), Vec2(0.1, 0.2), "CPDI");
  for (double w : nodes.weight) CHECK(std::abs(w - 0.25) <= 1e-15);
  CHECK(std::abs(nodes.volume - 4 * 0.05 * 0.03 * F.determinant()) <= 1e-16);
  // Corner 2 pulled inside the triangle of the others: the angle at corner 3 passes 180 degrees.
  DomainCorners dart = {Vec2(0, 0), Vec2(1, 0), Vec2(0.2, 0.2), Vec2(0, 1)};
  CHECK_THROWS_WITH(bilinear_nodes(dart, Vec2(0.3, 0.3), "CPDI2"),
                    Catch::Contains("CPDI2: the domain of the particle at (0.3, 0.3) is not a convex quadrilateral"));
  DomainCorners clockwise = {Vec2(0, 0), Vec2(0, 1), Vec2(1, 1), Vec2(1, 0)};
  CHECK_THROWS_AS(bilinear_nodes(clockwise, Vec2(0.5, 0.5), "CPDI2"), NumericalError);
}

TEST_CASE("serendipity parallelogram: weights -1/12 at corners and 1/3 at midsides, gradient integrals", "[mpm]") {
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst_w = 0.0, worst_g = 0.0;
  for (int trial = 0; trial < 100; ++trial) {
    const Mat2 F = testing::random_deformation(rng, 0.5);
    const Vec2 x(u(rng), u(rng)), half(0.04, 0.07);
    const DomainNodes<8> nodes = serendipity_nodes(x, F, half);
    const Mat2 dx = F * half.asDiagonal();  // the affine map's d x / d (xi, eta)
    const double J = dx.determinant();
    std::array<double, 8> w{};
    std::array<Vec2, 8> g;
    g.fill(Vec2::Zero());
    gauss([&](const Vec2& s, double weight) {
      for (int k = 0; k < 8; ++k) {
        w[k] += weight * J * serendipity(k, s);
        g[k] += weight * J * dx.inverse().transpose() * serendipity_gradient(k, s);
      }
    });
    const double V = 4 * J;
    CHECK(std::abs(nodes.volume - V) <= 1e-15 * V);
    for (int k = 0; k < 8; ++k) {
      CHECK((nodes.point[k] - (x + dx * reference[k])).norm() <= 1e-15);
      worst_w = std::max({worst_w, std::abs(nodes.weight[k] - w[k] / V), std::abs(w[k] / V - (k < 4 ? -1.0 / 12 : 1.0 / 3))});
      worst_g = std::max(worst_g, (nodes.gradient[k] - g[k]).norm() / std::sqrt(V));
    }
  }
  INFO("weights " << worst_w << ", gradient integrals " << worst_g);
  CHECK(worst_w <= 1e-14);
  CHECK(worst_g <= 1e-14);
  Mat2 inverted;
  inverted << 0.5, 1.0, 1.0, 0.5;
  CHECK_THROWS_WITH(serendipity_nodes(Vec2(0.25, 0.5), inverted, Vec2(0.1, 0.1)),
                    Catch::Contains("qCPDI: the particle domain at (0.25, 0.5) has area"));
}

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/problems/crack_references.hpp"

using namespace mfree;

namespace {

constexpr double pi = std::numbers::pi;

Mat2 tensor_of(const Eigen::Vector3d& v) {
  Mat2 m;
  m << v[0], v[2], v[2], v[1];
  return m;
}

}  // namespace

// K_I, K_II are the normal and shear stress on the crack plane (rotated uniaxial stress)
// times sqrt(pi a).
TEST_CASE("crack references: Griffith inclined crack", "[problems][crack]") {
  const double sigma = 80.0, a = 0.02;
  for (const double beta : {pi / 2, pi / 4, 0.3, 1.1}) {
    const StressIntensityPair k = griffith_inclined_crack(sigma, a, beta);
    // Crack along x; remote stress sigma along (cos beta, sin beta): traction on the plane
    // y = 0 (normal e2) is sigma (d . e2) d.
    const Vec2 d(std::cos(beta), std::sin(beta));
    const Vec2 traction = sigma * d.y() * d;
    CHECK(k.k1 == Approx(traction.y() * std::sqrt(pi * a)).epsilon(1e-14));
    CHECK(k.k2 == Approx(traction.x() * std::sqrt(pi * a)).epsilon(1e-14).margin(1e-14));
  }
  CHECK(griffith_inclined_crack(1.0, 1.0, pi / 2).k1 == Approx(std::sqrt(pi)).epsilon(1e-15));
  CHECK(std::abs(griffith_inclined_crack(1.0, 1.0, pi / 2).k2) <= 1e-15);
  CHECK_THAT(testing::message_of<InputError>([] { griffith_inclined_crack(1.0, 0.0, 1.0); }),
             Catch::Contains("half-length must be positive and finite, got 0"));
}

// Centre crack: F(0) = 1; F(0.5) = 0.9975 sqrt(sqrt 2) = 1.186234 by the formula, within its
// 0.1 % of Tada's tabulated 1.1867. Edge crack: F(0) = 1.12, F(0.5) = 1.12 - 0.1155 + 2.6375
// - 2.715 + 1.899375 = 2.826375, F(0.6) = 4.026424. Outside the fits' ranges: InputError.
TEST_CASE("crack references: strip geometry factors", "[problems][crack]") {
  CHECK(centre_crack_strip_factor(0.0) == 1.0);
  CHECK(centre_crack_strip_factor(0.5) == Approx(0.9975 * std::pow(2.0, 0.25)).epsilon(1e-14));
  CHECK(centre_crack_strip_factor(0.5) == Approx(1.186234).epsilon(1e-6));
  CHECK(std::abs(centre_crack_strip_factor(0.5) - 1.1867) <= 1e-3 * 1.1867);
  CHECK(centre_crack_strip_factor(0.9) > centre_crack_strip_factor(0.8));  // grows without bound
  CHECK(edge_crack_strip_factor(0.0) == 1.12);
  CHECK(edge_crack_strip_factor(0.5) == Approx(1.12 - 0.1155 + 2.6375 - 2.715 + 1.899375).epsilon(1e-14));
  CHECK(edge_crack_strip_factor(0.5) == Approx(2.826375).epsilon(1e-14));
  CHECK(edge_crack_strip_factor(0.6) == Approx(4.026424).epsilon(1e-14));
  using testing::message_of;
  CHECK_THAT(message_of<InputError>([] { centre_crack_strip_factor(1.0); }),
             Catch::Contains("a/w must lie in [0, 1)") && Catch::Contains("got 1"));
  CHECK_THAT(message_of<InputError>([] { edge_crack_strip_factor(0.7); }),
             Catch::Contains("a/w must lie in [0, 0.6], the range of the handbook fit") &&
                 Catch::Contains("got 0.7"));
  CHECK_THAT(message_of<InputError>([] { edge_crack_strip_factor(-0.1); }), Catch::Contains("got -0.1"));
}

// delta(s) = 4 sigma sqrt(a^2 - s^2) / E'; near the tip it is the opening of Williams' field
// with K_I = sigma sqrt(pi a): (kappa + 1) K_I sqrt(r / 2 pi) / mu at r = a - s, which
// checks E' against mu and kappa in both plane models.
TEST_CASE("crack references: Griffith crack opening", "[problems][crack]") {
  const double sigma = 50.0, a = 0.4;
  for (const PlaneModel model : {PlaneModel::strain, PlaneModel::stress}) {
    const LinearElastic m{2.0e4, 0.3, model};
    const double e_prime = model == PlaneModel::strain ? 2.0e4 / 0.91 : 2.0e4;
    CHECK(griffith_crack_opening(sigma, a, 0.0, m) == Approx(4 * sigma * a / e_prime).epsilon(1e-14));
    CHECK(griffith_crack_opening(sigma, a, -0.3, m) ==
          Approx(4 * sigma * std::sqrt(a * a - 0.09) / e_prime).epsilon(1e-14));
    CHECK(griffith_crack_opening(sigma, a, a, m) == 0.0);
    CHECK(griffith_crack_opening(sigma, a, 1.5 * a, m) == 0.0);
    const NearTipConstants c = near_tip_constants(m);
    const double r = 1e-8 * a;
    const double williams =
        (c.kolosov + 1) * sigma * std::sqrt(pi * a) * std::sqrt(r / (2 * pi)) / c.shear_modulus;
    INFO(to_string(model));
    CHECK(griffith_crack_opening(sigma, a, a - r, m) / williams == Approx(1.0).epsilon(1e-8));
  }
}

// The K-field about a rotated tip as an exact solution: grad u = the central difference of
// u, sigma = D sym(grad u), div sigma = 0 = b, and no traction on the crack faces behind the
// tip (points 1e-12 above and below the line).
TEST_CASE("crack references: Williams near-tip solution", "[problems][crack]") {
  const CrackTipFrame tip{Vec2(0.5, -0.25), Vec2(-0.6, -0.8)};
  const Mat2 q = tip.rotation();
  for (const PlaneModel model : {PlaneModel::strain, PlaneModel::stress}) {
    const LinearElastic m{3.0e3, 0.2, model};
    const ExactElasticity e = williams_near_tip_solution(tip, 1.3, -0.4, m);
    const auto gradient = williams_near_tip_gradient(tip, 1.3, -0.4, m);
    const Eigen::Matrix3d d = m.voigt_tangent();
    const double h = 1e-6;
    for (const Vec2 local : {Vec2(0.3, 0.1), Vec2(-0.2, 0.15), Vec2(-0.4, -0.05), Vec2(0.05, -0.6)}) {
      const Vec2 x = tip.position + q * local;
      Mat2 fd;
      Vec2 div = Vec2::Zero();
      for (int j = 0; j < 2; ++j) {
        const Vec2 step = Vec2::Unit(j) * h;
        fd.col(j) = (e.displacement(x + step) - e.displacement(x - step)) / (2 * h);
        div += (tensor_of(e.stress(x + step)) - tensor_of(e.stress(x - step))).col(j) / (2 * h);
      }
      const Mat2 g = gradient(x);
      const Eigen::Vector3d s = e.stress(x);
      INFO(to_string(model) << ", local point " << local.transpose());
      CHECK((fd - g).norm() <= 1e-7 * g.norm());
      CHECK((d * Eigen::Vector3d(g(0, 0), g(1, 1), g(0, 1) + g(1, 0)) - s).norm() <= 1e-12 * s.norm());
      CHECK(div.norm() <= 1e-7 * s.norm() / local.norm());
      CHECK(e.body_force(x).norm() == 0.0);
    }
    for (const double behind : {0.01, 0.3}) {
      const Vec2 face = tip.position - behind * q.col(0);
      const double size = e.stress(tip.position + behind * q.col(1)).norm();
      CHECK(e.traction(face + 1e-12 * q.col(1), -q.col(1)).norm() <= 1e-9 * size);
      CHECK(e.traction(face - 1e-12 * q.col(1), q.col(1)).norm() <= 1e-9 * size);
    }
    CHECK(e.displacement(tip.position).norm() == 0.0);
    CHECK_THROWS_AS(e.stress(tip.position), NumericalError);
  }
}

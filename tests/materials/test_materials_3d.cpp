// Every law in three dimensions: the tangent against central differences of the stress (at
// elastic and plastic states), P = dW/dF for the hyperelastic laws, objectivity under
// superposed rotations, the reference tangent lambda d d + mu (d d + d d) of every law, the
// return onto the yield surface in 3D, and plane strain as the reduction of the 3D law: the
// 3D update at F = diag(F_2, 1) along a loading path reproduces the plane update (P, sigma_zz,
// plastic strain, alpha, plastic work). The plane-only laws are refused in 3D.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "mfree/core/error.hpp"
#include "mfree/materials/material.hpp"

using namespace mfree;

namespace {

using Mat3 = Tensor2<3>;

Material plastic(std::string_view model, Kinematics k) {
  MaterialParameters p;
  p.kinematics = k;
  if (model == "j2") {
    p.youngs_modulus = 200e9, p.poisson_ratio = 0.3, p.yield_stress = 250e6, p.isotropic_modulus = 2e9;
    p.saturation_stress = 400e6, p.saturation_rate = 30.0;
  } else {
    p.youngs_modulus = 50e6, p.poisson_ratio = 0.3, p.friction_angle = 30.0 * std::numbers::pi / 180.0;
    p.dilatancy_angle = 5.0 * std::numbers::pi / 180.0, p.cohesion = 20e3;
  }
  return make_material(model, p);
}

/// The laws of the test, each with a deformation scale that takes the plastic ones through
/// yield (strain ~ 10 yield strains).
struct Case {
  std::string name;
  Material law;
  double scale;
};
std::vector<Case> laws() {
  return {{"plane_strain (3D linear)", make_material("plane_strain", 1e7, 0.3), 0.05},
          {"neo_hookean", make_material("neo_hookean", 1e7, 0.3), 0.3},
          {"st_venant_kirchhoff", make_material("st_venant_kirchhoff", 1e7, 0.3), 0.2},
          {"j2 multiplicative", plastic("j2", Kinematics::multiplicative), 0.01},
          {"j2 small strain", plastic("j2", Kinematics::small_strain), 0.01},
          {"drucker_prager multiplicative", plastic("drucker_prager", Kinematics::multiplicative), 0.01},
          {"drucker_prager small strain", plastic("drucker_prager", Kinematics::small_strain), 0.01}};
}

/// A general F = I + s G (no symmetry, all nine components) and its path from I.
Mat3 deformation(double s, double t) {
  Mat3 g;
  g << 0.9, 0.35, -0.2, -0.15, -0.5, 0.3, 0.25, 0.1, -0.6;
  return Mat3::Identity() + t * s * g;
}

Mat3 rotation(double a, double b) {
  const Eigen::AngleAxisd r1(a, Eigen::Vector3d(1, 2, 3).normalized()), r2(b, Eigen::Vector3d::UnitZ());
  return (r1 * r2).toRotationMatrix();
}

/// |A - A_fd| / |A| with A_fd by central differences of P, step 1e-7.
double tangent_error(const Material& m, const Mat3& f, const MaterialState<3>& state) {
  const MaterialUpdate<3> u = update(m, f, state, true);
  Tangent<3> fd;
  const double h = 1e-7;
  for (int k = 0; k < 9; ++k) {
    Mat3 plus = f, minus = f;
    plus(k / 3, k % 3) += h;
    minus(k / 3, k % 3) -= h;
    const Mat3 dp = (update(m, plus, state, false).stress - update(m, minus, state, false).stress) / (2 * h);
    for (int r = 0; r < 9; ++r) fd(r, k) = dp(r / 3, r % 3);
  }
  return (u.tangent - fd).norm() / u.tangent.norm();
}

}  // namespace

TEST_CASE("3D laws: consistent tangents against central differences at elastic and plastic states",
          "[materials][3d]") {
  for (const Case& c : laws()) {
    CAPTURE(c.name);
    MaterialState<3> state;
    // Five increments along the path, the tangent checked at each (elastic first, then
    // plastic for the plastic laws), each state committed as a solver would.
    int plastic_steps = 0;
    for (int n = 1; n <= 5; ++n) {
      const Mat3 f = deformation(c.scale, n / 5.0);
      CHECK(tangent_error(c.law, f, state) < 1e-6);
      const MaterialUpdate<3> u = update(c.law, f, state, false);
      if (u.state.alpha > state.alpha) ++plastic_steps;
      state = u.state;
    }
    if (has_history(c.law)) CHECK(plastic_steps >= 3);
  }
}

TEST_CASE("3D hyperelastic laws: P = dW/dF (central differences)", "[materials][3d]") {
  for (const Case& c : laws()) {
    if (has_history(c.law)) continue;
    CAPTURE(c.name);
    const Mat3 f = deformation(c.scale, 1.0);
    const Mat3 p = stress(c.law, f);
    const double h = 1e-6;
    Mat3 dw;
    for (int k = 0; k < 9; ++k) {
      Mat3 plus = f, minus = f;
      plus(k / 3, k % 3) += h;
      minus(k / 3, k % 3) -= h;
      dw(k / 3, k % 3) = (energy(c.law, plus) - energy(c.law, minus)) / (2 * h);
    }
    CHECK((dw - p).norm() <= 1e-7 * p.norm());
  }
}

TEST_CASE("3D laws: objective under superposed rotations, P(QF) = Q P(F), the same state",
          "[materials][3d]") {
  for (const Case& c : laws()) {
    if (is_small_strain(c.law)) continue;  // the small strain is not objective (by design)
    CAPTURE(c.name);
    for (double angle : {0.4, 2.1, -2.8}) {
      const Mat3 q = rotation(angle, 0.7 * angle);
      MaterialState<3> a, b;
      for (int n = 1; n <= 4; ++n) {
        const Mat3 f = deformation(c.scale, n / 4.0);
        const MaterialUpdate<3> ua = update(c.law, f, a, false), ub = update(c.law, Mat3(q * f), b, false);
        CHECK((ub.stress - q * ua.stress).norm() <= 1e-11 * ua.stress.norm());
        CHECK((ub.state.plastic_strain - ua.state.plastic_strain).norm() <=
              1e-11 * (1.0 + ua.state.plastic_strain.norm()));
        CHECK(ub.state.alpha == Approx(ua.state.alpha).epsilon(1e-10).margin(1e-300));
        a = ua.state, b = ub.state;
      }
    }
  }
}

TEST_CASE(
    "3D laws: the reference tangent is isotropic linear elasticity, and J2 returns onto its yield surface",
    "[materials][3d]") {
  for (const Case& c : laws()) {
    CAPTURE(c.name);
    const Tangent<3> a = tangent(c.law, Mat3(Mat3::Identity()));
    // lambda and mu from A_xxyy and A_xyxy; then every component.
    const double lambda = a(tensor_index<3>(0, 0), tensor_index<3>(1, 1)),
                 mu = a(tensor_index<3>(0, 1), tensor_index<3>(0, 1));
    Tangent<3> iso;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l)
            iso(tensor_index<3>(i, j), tensor_index<3>(k, l)) =
                lambda * (i == j) * (k == l) + mu * ((i == k) * (j == l) + (i == l) * (j == k));
    CHECK((a - iso).norm() <= 1e-10 * a.norm());
    CHECK(a(0, 0) == Approx(p_wave_modulus(c.law)).epsilon(1e-12));
  }
  // J2: after a plastic step the Kirchhoff stress tau = P F^T lies on the yield surface,
  // sqrt(3/2) |dev tau| = k(alpha).
  J2Plasticity j2;
  j2.lame = lame_constants(200e9, 0.3);
  j2.yield_stress = 250e6, j2.isotropic_modulus = 2e9, j2.saturation_stress = 400e6,
  j2.saturation_rate = 30.0;
  const Mat3 f = deformation(0.01, 1.0);
  const MaterialUpdate<3> u = j2.update(f, MaterialState<3>{}, false);
  const Mat3 tau = u.stress * f.transpose();
  const Mat3 dev = tau - tau.trace() / 3.0 * Mat3::Identity();
  REQUIRE(u.state.alpha > 0.0);
  CHECK(std::sqrt(1.5) * dev.norm() == Approx(j2.flow_stress(u.state.alpha)).epsilon(1e-12));
  CHECK(von_mises(Mat3(tau / f.determinant())) * f.determinant() ==
        Approx(j2.flow_stress(u.state.alpha)).epsilon(1e-12));
}

TEST_CASE(
    "plane strain is the reduction of the 3D law: F = diag(F_2, 1) along a path through yield gives the "
    "plane "
    "update",
    "[materials][3d]") {
  for (const Case& c : laws()) {
    CAPTURE(c.name);
    MaterialState<2> s2;
    MaterialState<3> s3;
    Mat2 g;
    g << 0.9, 0.35, -0.15, -0.5;
    for (int n = 1; n <= 6; ++n) {
      // out and back: loading to n = 4, then partly unloading
      const double t = n <= 4 ? n / 4.0 : 1.0 - 0.3 * (n - 4);
      const Mat2 f2 = Mat2::Identity() + t * c.scale * g;
      Mat3 f3 = Mat3::Identity();
      f3.topLeftCorner<2, 2>() = f2;
      const MaterialUpdate<2> u2 = update(c.law, f2, s2, true);
      const MaterialUpdate<3> u3 = update(c.law, f3, s3, true);
      const double scale = u2.stress.norm();
      CHECK((u3.stress.topLeftCorner<2, 2>() - u2.stress).norm() <= 1e-11 * scale);
      CHECK(u3.stress.col(2).head<2>().norm() + u3.stress.row(2).head<2>().norm() <= 1e-11 * scale);
      CHECK(cauchy_stress(c.law, u3.stress, f3)(2, 2) ==
            Approx(u2.stress_zz).epsilon(1e-10).margin(1e-11 * scale));
      CHECK((u3.state.plastic_strain.topLeftCorner<2, 2>() - u2.state.plastic_strain).norm() <= 1e-11);
      CHECK(u3.state.plastic_strain(2, 2) == Approx(u2.state.plastic_strain_zz).margin(1e-11));
      CHECK(u3.state.alpha == Approx(u2.state.alpha).epsilon(1e-10).margin(1e-14));
      CHECK(u3.state.dissipation == Approx(u2.state.dissipation).epsilon(1e-9).margin(1e-9 * scale * 1e-3));
      CHECK(energy(c.law, f3, s3) == Approx(energy(c.law, f2, s2)).epsilon(1e-10));
      // The in-plane block of the 3D tangent is the plane tangent.
      double worst = 0.0;
      for (int r = 0; r < 4; ++r)
        for (int k = 0; k < 4; ++k)
          worst = std::max(worst,
                           std::abs(u3.tangent(tensor_index<3>(r / 2, r % 2), tensor_index<3>(k / 2, k % 2)) -
                                    u2.tangent(r, k)));
      CHECK(worst <= 1e-9 * u2.tangent.norm());
      s2 = u2.state, s3 = u3.state;
    }
    if (has_history(c.law)) CHECK(s3.alpha > 0.0);
  }
}

TEST_CASE("plane-only laws are refused in 3D", "[materials][3d]") {
  const Mat3 f = deformation(0.01, 1.0);
  CHECK_THROWS_WITH(stress(make_material("plane_stress", 1e7, 0.3), f),
                    Catch::Contains("plane-stress law has no 3D form"));
  CHECK_THROWS_WITH(stress(plastic("j2", Kinematics::logarithmic), f),
                    Catch::Contains("logarithmic") && Catch::Contains("plane only"));
  Mat3 inverted = Mat3::Identity();
  inverted(2, 2) = -1.0;
  CHECK_THROWS_WITH(stress(make_material("neo_hookean", 1e7, 0.3), inverted),
                    Catch::Contains("J = det F = -1 <= 0") && Catch::Contains("[0, 0, -1]"));
}

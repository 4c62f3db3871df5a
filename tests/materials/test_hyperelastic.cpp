#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/materials/material.hpp"
#include "mfree/materials/neo_hookean.hpp"
#include "mfree/materials/st_venant_kirchhoff.hpp"

using namespace mfree;

namespace {

/// Random deformation gradients with det F in about [0.5, 1.6].
std::vector<Mat2> samples() {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::vector<Mat2> out;
  for (int k = 0; k < 20; ++k) {
    Mat2 f = Mat2::Identity();
    f << 1.0 + u(rng), u(rng), u(rng), 1.0 + u(rng);
    out.push_back(f);
  }
  return out;
}

/// Checks P against central differences of W, and A against central differences of P.
template <class Material>
void check_derivatives(const Material& m) {
  for (const Mat2& f : samples()) {
    const Mat2 p = m.stress(f);
    const Tangent<2> a = m.tangent(f);
    const double h = 1e-6;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        Mat2 fp = f, fm = f;
        fp(i, j) += h;
        fm(i, j) -= h;
        const double dw = (m.energy(fp) - m.energy(fm)) / (2 * h);
        CHECK(std::abs(dw - p(i, j)) <= 1e-6 * p.norm());
        const Mat2 dp = (m.stress(fp) - m.stress(fm)) / (2 * h);
        for (int k = 0; k < 2; ++k)
          for (int l = 0; l < 2; ++l)
            CHECK(std::abs(dp(k, l) - a(tensor_index<2>(k, l), tensor_index<2>(i, j))) <= 1e-6 * a.norm());
      }
  }
}

/// W(QF) = W(F) and P(QF) = Q P(F) for rotations Q.
template <class Material>
void check_objectivity(const Material& m) {
  for (const Mat2& f : samples())
    for (double angle : {0.3, 1.7, -2.5}) {
      Mat2 q;
      q << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
      CHECK(m.energy(Mat2(q * f)) == Approx(m.energy(f)).epsilon(1e-12));
      CHECK((m.stress(Mat2(q * f)) - q * m.stress(f)).norm() <= 1e-12 * m.stress(f).norm() + 1e-9);
    }
}

}  // namespace

TEST_CASE("Neo-Hookean: P = dW/dF, A = dP/dF (finite differences), objectivity", "[materials]") {
  const NeoHookean m{lame_constants(1e7, 0.3)};
  check_derivatives(m);
  check_objectivity(m);
  // Stress free at F = I.
  CHECK(m.stress(Mat2(Mat2::Identity())).norm() == 0.0);
}

TEST_CASE("St. Venant-Kirchhoff: P = dW/dF, A = dP/dF (finite differences), objectivity", "[materials]") {
  const StVenantKirchhoff m{lame_constants(3e7, 0.25)};
  check_derivatives(m);
  check_objectivity(m);
}

TEST_CASE("an inverted deformation (J <= 0) is a clear error", "[materials]") {
  const NeoHookean m{lame_constants(1e7, 0.3)};
  Mat2 f;
  f << 1.0, 0.0, 0.0, -0.1;
  CHECK_THROWS_AS(m.stress(f), NumericalError);
  CHECK_THROWS_WITH(m.stress(f), Catch::Contains("J = det F = -0.1 <= 0"));
  CHECK_THROWS_AS(StVenantKirchhoff{m.lame}.tangent(f), NumericalError);
}

TEST_CASE("small-strain law in F form: P = dW/dF, A = dP/dF, and the Voigt law it wraps", "[materials]") {
  for (PlaneModel model : {PlaneModel::stress, PlaneModel::strain}) {
    const LinearElastic m{2e5, 0.3, model};
    check_derivatives(m);
    Mat2 f;
    f << 1.01, 0.003, -0.002, 0.995;
    const Eigen::Vector3d s = m.voigt_tangent() * Eigen::Vector3d(0.01, -0.005, 0.001);
    const Mat2 p = m.stress(f);
    CHECK((Eigen::Vector3d(p(0, 0), p(1, 1), p(0, 1)) - s).norm() <= 1e-12 * s.norm());
    CHECK(p(0, 1) == p(1, 0));
  }
}

TEST_CASE("the variant Material dispatches, and its reference tangent is the linear law's", "[materials]") {
  const Material nh = make_material("neo_hookean", 1e7, 0.3);
  const Material lin = make_material("plane_strain", 1e7, 0.3);
  // Neo-Hookean linearised at F = I is plane-strain linear elasticity.
  CHECK((tangent(nh, Mat2(Mat2::Identity())) - tangent(lin, Mat2(Mat2::Identity()))).norm() <=
        1e-9 * tangent(lin, Mat2(Mat2::Identity())).norm());
  CHECK(wave_speed(nh, 1000.0) == Approx(std::sqrt(1e7 * 0.7 / (1.3 * 0.4) / 1000.0)).epsilon(1e-14));
  Mat2 f;
  f << 1.2, 0.1, -0.05, 0.9;
  // sigma = P F^T / J is symmetric for an objective material.
  const Mat2 sigma = cauchy_stress(nh, f);
  CHECK(std::abs(sigma(0, 1) - sigma(1, 0)) <= 1e-12 * sigma.norm());
  CHECK_THROWS_WITH(make_material("neo_hookean", -1.0, 0.3), Catch::Contains("Young's modulus must be positive"));
}

TEST_CASE("the P-wave modulus is lambda + 2 mu in plane strain and E / (1 - nu^2) in plane stress", "[materials]") {
  const double e = 3e7, nu = 0.4999;
  const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu)), mu = e / (2 * (1 + nu));
  for (const char* model : {"plane_strain", "neo_hookean", "st_venant_kirchhoff"})
    CHECK(p_wave_modulus(make_material(model, e, nu)) == Approx(lambda + 2 * mu).epsilon(1e-12));
  CHECK(p_wave_modulus(make_material("plane_stress", e, nu)) == Approx(e / (1 - nu * nu)).epsilon(1e-12));
}

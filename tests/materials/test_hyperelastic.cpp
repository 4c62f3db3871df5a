#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "mfree/core/error.hpp"
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
    const Tangent a = m.tangent(f);
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
            CHECK(std::abs(dp(k, l) - a(tensor_index(k, l), tensor_index(i, j))) <= 1e-6 * a.norm());
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
      CHECK(m.energy(q * f) == Approx(m.energy(f)).epsilon(1e-12));
      CHECK((m.stress(q * f) - q * m.stress(f)).norm() <= 1e-12 * m.stress(f).norm() + 1e-9);
    }
}

}  // namespace

TEST_CASE("Neo-Hookean: P = dW/dF, A = dP/dF (finite differences), objectivity", "[materials]") {
  const NeoHookean m{lame_constants(1e7, 0.3)};
  check_derivatives(m);
  check_objectivity(m);
  // Stress free at F = I.
  CHECK(m.stress(Mat2::Identity()).norm() == 0.0);
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

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/galerkin/near_tip_field.hpp"

using namespace mfree;

namespace {

constexpr double pi = std::numbers::pi;

Mat2 tensor_of(const Eigen::Vector3d& v) {
  Mat2 m;
  m << v[0], v[2], v[2], v[1];
  return m;
}

/// The field at local Cartesian coordinates x.
NearTipState field_at(const Vec2& x, double k1, double k2, const NearTipConstants& c) {
  return williams_field(k1, k2, x.norm(), std::atan2(x.y(), x.x()), c);
}

}  // namespace

// The gradient is the derivative of the displacement (central differences), and the stress
// is D sym(grad u) of the material (which fixes kappa for each plane model).
TEST_CASE("Williams field: gradient and stress agree with the displacement", "[near_tip]") {
  for (const PlaneModel model : {PlaneModel::strain, PlaneModel::stress}) {
    const LinearElastic m{210.0, 0.3, model};
    const NearTipConstants c = near_tip_constants(m);
    const Eigen::Matrix3d d = m.voigt_tangent();
    const double h = 1e-6;
    for (const double theta : {-2.9, -1.7, -0.4, 0.0, 0.9, 2.2, 3.0})
      for (const double r : {0.05, 0.7}) {
        const Vec2 x = r * Vec2(std::cos(theta), std::sin(theta));
        const NearTipState s = field_at(x, 1.3, -0.4, c);
        Mat2 fd;
        for (int j = 0; j < 2; ++j) {
          const Vec2 e = Vec2::Unit(j) * h;
          fd.col(j) =
              (field_at(x + e, 1.3, -0.4, c).displacement - field_at(x - e, 1.3, -0.4, c).displacement) /
              (2 * h);
        }
        INFO(to_string(model) << ", r = " << r << ", theta = " << theta);
        CHECK((fd - s.gradient).norm() <= 1e-7 * s.gradient.norm());
        const Mat2 g = s.gradient;
        const Mat2 sigma = tensor_of(d * Eigen::Vector3d(g(0, 0), g(1, 1), g(0, 1) + g(1, 0)));
        CHECK((sigma - s.stress).norm() <= 1e-12 * s.stress.norm());
      }
  }
}

// div sigma = 0 off the crack (central differences of the stress in x1, x2).
TEST_CASE("Williams field: equilibrium", "[near_tip]") {
  const NearTipConstants c = near_tip_constants(LinearElastic{1.0, 0.25, PlaneModel::strain});
  const double h = 1e-6;
  for (const double theta : {-3.0, -2.0, -0.5, 0.3, 1.5, 2.8})
    for (const double r : {0.1, 1.0}) {
      const Vec2 x = r * Vec2(std::cos(theta), std::sin(theta));
      Vec2 div = Vec2::Zero();
      for (int j = 0; j < 2; ++j) {
        const Vec2 e = Vec2::Unit(j) * h;
        div += (field_at(x + e, 1.3, -0.4, c).stress - field_at(x - e, 1.3, -0.4, c).stress).col(j) / (2 * h);
      }
      const double scale = field_at(x, 1.3, -0.4, c).stress.norm() / r;  // size of one derivative
      INFO("r = " << r << ", theta = " << theta);
      CHECK(div.norm() <= 1e-7 * scale);
    }
}

// The crack faces theta = +-pi are traction free (sigma n = 0 with n = -+e2), the faces open
// (u_2(pi) - u_2(-pi) = (kappa + 1) K_I sqrt(r / 2 pi) / mu) and slide, and the two sides of
// the line ahead of the tip meet.
TEST_CASE("Williams field: traction-free faces, opening and continuity ahead", "[near_tip]") {
  const NearTipConstants c = near_tip_constants(LinearElastic{1.0, 0.3, PlaneModel::stress});
  for (const double r : {0.01, 0.5, 2.0}) {
    const NearTipState upper = williams_field(1.3, -0.4, r, pi, c);
    const NearTipState lower = williams_field(1.3, -0.4, r, -pi, c);
    const double size = williams_field(1.3, -0.4, r, pi / 2, c).stress.norm();
    CHECK(upper.stress.col(1).norm() <= 1e-15 * size);
    CHECK(lower.stress.col(1).norm() <= 1e-15 * size);
    const double opening = (c.kolosov + 1.0) * std::sqrt(r / (2 * pi)) / c.shear_modulus;
    CHECK((upper.displacement - lower.displacement - opening * Vec2(-0.4, 1.3)).norm() <= 1e-14 * opening);
    // Ahead of the tip the field is smooth: theta = +-1e-12 agree.
    const NearTipState a = williams_field(1.3, -0.4, r, 1e-12, c),
                       b = williams_field(1.3, -0.4, r, -1e-12, c);
    CHECK((a.stress - b.stress).norm() <= 1e-10 * size);
    CHECK((a.displacement - b.displacement).norm() <= 1e-10 * opening);
  }
  // Mode I alone: the stress ahead is sigma_22 = K / sqrt(2 pi r), no shear.
  const NearTipState s = williams_field(2.0, 0.0, 0.25, 0.0, c);
  CHECK(s.stress(1, 1) == Approx(2.0 / std::sqrt(2 * pi * 0.25)).epsilon(1e-15));
  CHECK(s.stress(0, 1) == 0.0);
}

TEST_CASE("Williams field: the frame and its errors", "[near_tip]") {
  const CrackTipFrame tip{Vec2(1.0, 2.0), Vec2(0.0, 3.0)};
  const Vec2 local = tip.to_local(Vec2(1.0, 2.5));
  CHECK((local - Vec2(0.5, 0.0)).norm() <= 1e-15);
  CHECK((tip.to_local(Vec2(0.5, 2.0)) - Vec2(0.0, 0.5)).norm() <= 1e-15);  // e2 = e1 turned +90 degrees
  CHECK_NOTHROW(tip.validate());
  CHECK_THAT(testing::message_of<InputError>([] {
               CrackTipFrame{Vec2(0, 0), Vec2(0, 0)}.validate();
             }),
             Catch::Contains("direction (0, 0) must be finite and nonzero"));
  CHECK_THAT(testing::message_of<NumericalError>([] {
               williams_field(1, 0, 0.0, 0.0, NearTipConstants{1, 2, 1});
             }),
             Catch::Contains("singular at the crack tip"));
  const NearTipConstants strain = near_tip_constants(LinearElastic{100.0, 0.25, PlaneModel::strain});
  CHECK(strain.kolosov == Approx(2.0));
  CHECK(strain.shear_modulus == Approx(40.0));
  CHECK(strain.effective_modulus == Approx(100.0 / 0.9375));
  const NearTipConstants stress = near_tip_constants(LinearElastic{100.0, 0.25, PlaneModel::stress});
  CHECK(stress.kolosov == Approx(2.2));
  CHECK(stress.effective_modulus == Approx(100.0));
}

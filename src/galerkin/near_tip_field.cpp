#include "mfree/galerkin/near_tip_field.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "mfree/core/error.hpp"

namespace mfree {

void CrackTipFrame::validate() const {
  if (!position.allFinite())
    throw InputError(fmt::format("crack tip: the position ({}, {}) is not finite; give a finite tip position",
                                 position.x(), position.y()));
  if (!direction.allFinite() || !(direction.norm() > 0.0))
    throw InputError(
        fmt::format("crack tip at ({}, {}): the direction ({}, {}) must be finite and nonzero "
                    "(the direction of crack extension)",
                    position.x(), position.y(), direction.x(), direction.y()));
}

Mat2 CrackTipFrame::rotation() const {
  const Vec2 e1 = direction.normalized();
  Mat2 q;
  q << e1.x(), -e1.y(), e1.y(), e1.x();
  return q;
}

NearTipConstants near_tip_constants(const LinearElastic& material) {
  const double e = material.youngs_modulus, nu = material.poisson_ratio;
  NearTipConstants c;
  c.shear_modulus = e / (2.0 * (1.0 + nu));
  if (material.model == PlaneModel::strain) {
    c.kolosov = 3.0 - 4.0 * nu;
    c.effective_modulus = e / (1.0 - nu * nu);
  } else {
    c.kolosov = (3.0 - nu) / (1.0 + nu);
    c.effective_modulus = e;
  }
  return c;
}

namespace {

/// The angular functions of one mode: u_i = K sqrt(r) / (2 mu sqrt(2 pi)) f_i(theta) and
/// sigma_ij = K / sqrt(2 pi r) g_ij(theta), with f_i' = df_i / dtheta.
struct AngularFunctions {
  Vec2 f;
  Vec2 df;
  Mat2 g;
};

/// Mode I (Anderson Tables 2.1, 2.2), with c = cos(theta/2), s = sin(theta/2):
/// f = (c (kappa - 1 + 2 s^2), s (kappa + 1 - 2 c^2)),
/// g_xx = c (1 - s sin(3 theta/2)), g_yy = c (1 + s sin(3 theta/2)), g_xy = c s cos(3 theta/2).
AngularFunctions mode_one(double theta, double kappa) {
  const double c = std::cos(theta / 2), s = std::sin(theta / 2);
  const double c3 = std::cos(1.5 * theta), s3 = std::sin(1.5 * theta);
  AngularFunctions a;
  a.f = {c * (kappa - 1.0 + 2.0 * s * s), s * (kappa + 1.0 - 2.0 * c * c)};
  a.df = {s * (-(kappa - 1.0) / 2.0 - s * s + 2.0 * c * c), c * ((kappa + 1.0) / 2.0 - c * c + 2.0 * s * s)};
  a.g << c * (1.0 - s * s3), c * s * c3, c * s * c3, c * (1.0 + s * s3);
  return a;
}

/// Mode II (Anderson Tables 2.1, 2.2):
/// f = (s (kappa + 1 + 2 c^2), -c (kappa - 1 - 2 s^2)),
/// g_xx = -s (2 + c cos(3 theta/2)), g_yy = s c cos(3 theta/2), g_xy = c (1 - s sin(3 theta/2)).
AngularFunctions mode_two(double theta, double kappa) {
  const double c = std::cos(theta / 2), s = std::sin(theta / 2);
  const double c3 = std::cos(1.5 * theta), s3 = std::sin(1.5 * theta);
  AngularFunctions a;
  a.f = {s * (kappa + 1.0 + 2.0 * c * c), -c * (kappa - 1.0 - 2.0 * s * s)};
  a.df = {c * ((kappa + 1.0) / 2.0 + c * c - 2.0 * s * s), s * ((kappa - 1.0) / 2.0 - s * s + 2.0 * c * c)};
  a.g << -s * (2.0 + c * c3), c * (1.0 - s * s3), c * (1.0 - s * s3), s * c * c3;
  return a;
}

}  // namespace

NearTipState williams_field(double k1, double k2, double r, double theta, const NearTipConstants& c) {
  if (!(r > 0.0) || !std::isfinite(r) || !std::isfinite(theta))
    throw NumericalError(
        fmt::format("Williams near-tip field: evaluated at r = {}, theta = {}; it is "
                    "singular at the crack tip and needs r > 0 (keep points off the tip)",
                    r, theta));
  const AngularFunctions one = mode_one(theta, c.kolosov), two = mode_two(theta, c.kolosov);
  const Vec2 f = k1 * one.f + k2 * two.f, df = k1 * one.df + k2 * two.df;
  const double root_two_pi = std::sqrt(2.0 * std::numbers::pi);
  const double scale = 1.0 / (2.0 * c.shear_modulus * root_two_pi);
  const double sqrt_r = std::sqrt(r), ct = std::cos(theta), st = std::sin(theta);
  NearTipState state;
  state.displacement = scale * sqrt_r * f;
  // Chain rule with u_i = scale sqrt(r) f_i(theta): d/dx1 = cos d/dr - sin / r d/dtheta,
  // d/dx2 = sin d/dr + cos / r d/dtheta.
  state.gradient.col(0) = scale / sqrt_r * (0.5 * ct * f - st * df);
  state.gradient.col(1) = scale / sqrt_r * (0.5 * st * f + ct * df);
  state.stress = (k1 * one.g + k2 * two.g) / (root_two_pi * sqrt_r);
  return state;
}

}  // namespace mfree

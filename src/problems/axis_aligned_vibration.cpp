#include "mfree/problems/axis_aligned_vibration.hpp"

#include <cmath>
#include <numbers>

namespace mfree {

namespace {
constexpr double pi = std::numbers::pi;
}

double AxisAlignedVibration::wave_speed() const { return std::sqrt(youngs_modulus / density); }

Vec2 AxisAlignedVibration::displacement(const Vec2& x, double t) const {
  const double s = std::sin(wave_speed() * pi * t / length);
  return amplitude * s * Vec2(std::sin(2 * pi * x.x() / length), -std::sin(2 * pi * x.y() / length));
}

Vec2 AxisAlignedVibration::velocity(const Vec2& x, double t) const {
  const double w = wave_speed() * pi / length;
  return amplitude * w * std::cos(w * t) * Vec2(std::sin(2 * pi * x.x() / length), -std::sin(2 * pi * x.y() / length));
}

Vec2 AxisAlignedVibration::acceleration(const Vec2& x, double t) const {
  const double w = wave_speed() * pi / length;
  return -w * w * displacement(x, t);
}

Mat2 AxisAlignedVibration::deformation_gradient(const Vec2& x, double t) const {
  const double s = amplitude * (2 * pi / length) * std::sin(wave_speed() * pi * t / length);
  Mat2 f = Mat2::Zero();
  f(0, 0) = 1.0 + s * std::cos(2 * pi * x.x() / length);
  f(1, 1) = 1.0 - s * std::cos(2 * pi * x.y() / length);
  return f;
}

Mat2 AxisAlignedVibration::cauchy_stress(const Vec2& x, double t) const {
  const Mat2 f = deformation_gradient(x, t);
  return material().stress(f) * f.transpose() / f.determinant();
}

Vec2 AxisAlignedVibration::body_force(const Vec2& x, double t) const {
  // SPEC section 6: b_i = (pi^2 u_i / L^2) [4 mu / rho0 - c^2 - 4 (lambda (ln(Fxx Fyy) - 1) - mu) / (rho0 F_ii^2)],
  // with u and F written out so that each sine, cosine and logarithm is evaluated once (the
  // MPM evaluates this at every particle and step).
  const Lame m = lame_constants(youngs_modulus, poisson_ratio);
  const double c2 = youngs_modulus / density, kx = 2 * pi / length;
  const double s = amplitude * std::sin(std::sqrt(c2) * pi * t / length);
  const double sx = std::sin(kx * x.x()), cx = std::cos(kx * x.x());
  const double sy = std::sin(kx * x.y()), cy = std::cos(kx * x.y());
  const double fxx = 1.0 + s * kx * cx, fyy = 1.0 - s * kx * cy;
  const double common = 4.0 * m.mu / density - c2;
  const double k = 4.0 * (m.lambda * (std::log(fxx * fyy) - 1.0) - m.mu) / density;
  const double scale = pi * pi / (length * length);
  return scale * s * Vec2(sx * (common - k / (fxx * fxx)), -sy * (common - k / (fyy * fyy)));
}

ExactMotion AxisAlignedVibration::motion() const {
  return {[v = *this](const Vec2& x, double t) { return v.displacement(x, t); },
          [v = *this](const Vec2& x, double t) { return v.velocity(x, t); },
          [v = *this](const Vec2& x, double t) { return v.cauchy_stress(x, t); },
          [v = *this](const Vec2& x, double t) { return v.body_force(x, t); }};
}

}  // namespace mfree

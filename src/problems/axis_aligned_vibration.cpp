#include "mfree/problems/axis_aligned_vibration.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {
constexpr double pi = std::numbers::pi;

/// (sin(2 pi x / L), -sin(2 pi y / L), sin(2 pi z / L)).
template <int dim>
Point<dim> mode_shape_of(const Point<dim>& x, double length) {
  Point<dim> m;
  for (int a = 0; a < dim; ++a)
    m[a] = a % 2 == 0 ? std::sin(2 * pi * x[a] / length) : -std::sin(2 * pi * x[a] / length);
  return m;
}
}

double AxisAlignedVibration::wave_speed() const { return std::sqrt(youngs_modulus / density); }

void AxisAlignedVibration::check_amplitude() const {
  const double limit = length / (2.0 * pi);
  if (!(std::abs(amplitude) < limit))
    throw InputError(
        fmt::format("the vibration solution inverts the material for an amplitude of L / (2 pi) = {:.6g} m "
                    "or more (F_xx = 1 - 2 pi A / L at its extreme); amplitude {:.6g} m is not below it",
                    limit, amplitude));
}

template <int dim>
Point<dim> AxisAlignedVibration::displacement(const Point<dim>& x, double t) const {
  const double s = std::sin(wave_speed() * pi * t / length);
  return amplitude * s * mode_shape_of(x, length);
}

template <int dim>
Point<dim> AxisAlignedVibration::velocity(const Point<dim>& x, double t) const {
  const double w = wave_speed() * pi / length;
  return amplitude * w * std::cos(w * t) * mode_shape_of(x, length);
}

template <int dim>
Point<dim> AxisAlignedVibration::acceleration(const Point<dim>& x, double t) const {
  const double w = wave_speed() * pi / length;
  return -w * w * displacement(x, t);
}

template <int dim>
Tensor2<dim> AxisAlignedVibration::deformation_gradient(const Point<dim>& x, double t) const {
  const double s = amplitude * (2 * pi / length) * std::sin(wave_speed() * pi * t / length);
  Tensor2<dim> f = Tensor2<dim>::Zero();
  for (int a = 0; a < dim; ++a)
    f(a, a) =
        a % 2 == 0 ? 1.0 + s * std::cos(2 * pi * x[a] / length) : 1.0 - s * std::cos(2 * pi * x[a] / length);
  return f;
}

template <int dim>
Tensor2<dim> AxisAlignedVibration::cauchy_stress(const Point<dim>& x, double t) const {
  const Tensor2<dim> f = deformation_gradient(x, t);
  return material().stress(f) * f.transpose() / f.determinant();
}

template <int dim>
Point<dim> AxisAlignedVibration::body_force(const Point<dim>& x, double t) const {
  // SPEC section 6: b_i = (pi^2 u_i / L^2) [4 mu / rho0 - c^2 - 4 (lambda (ln J - 1) - mu) / (rho0 F_ii^2)],
  // J = prod F_ii, with u and F written out so that each sine, cosine and logarithm is
  // evaluated once (the MPM evaluates this at every particle and step).
  const Lame m = lame_constants(youngs_modulus, poisson_ratio);
  const double c2 = youngs_modulus / density, kx = 2 * pi / length;
  const double s = amplitude * std::sin(std::sqrt(c2) * pi * t / length);
  Point<dim> sines, f;
  for (int a = 0; a < dim; ++a) {
    sines[a] = std::sin(kx * x[a]);
    const double c = std::cos(kx * x[a]);
    f[a] = a % 2 == 0 ? 1.0 + s * kx * c : 1.0 - s * kx * c;
  }
  const double common = 4.0 * m.mu / density - c2;
  const double k = 4.0 * (m.lambda * (std::log(f.prod()) - 1.0) - m.mu) / density;
  const double scale = pi * pi / (length * length);
  Point<dim> b;
  for (int a = 0; a < dim; ++a)
    b[a] = a % 2 == 0 ? sines[a] * (common - k / (f[a] * f[a])) : -sines[a] * (common - k / (f[a] * f[a]));
  return scale * s * b;
}

template <int dim>
ExactMotion<dim> AxisAlignedVibration::motion() const {
  return {[v = *this](const Point<dim>& x, double t) { return v.displacement(x, t); },
          [v = *this](const Point<dim>& x, double t) { return v.velocity(x, t); },
          [v = *this](const Point<dim>& x, double t) { return v.cauchy_stress(x, t); },
          [v = *this](const Point<dim>& x, double t) { return v.body_force(x, t); }};
}

#define MFREE_VIBRATION_MEMBERS(dim)                                                                 \
  template Point<dim> AxisAlignedVibration::displacement(const Point<dim>&, double) const;           \
  template Point<dim> AxisAlignedVibration::velocity(const Point<dim>&, double) const;               \
  template Point<dim> AxisAlignedVibration::acceleration(const Point<dim>&, double) const;           \
  template Tensor2<dim> AxisAlignedVibration::deformation_gradient(const Point<dim>&, double) const; \
  template Tensor2<dim> AxisAlignedVibration::cauchy_stress(const Point<dim>&, double) const;        \
  template Point<dim> AxisAlignedVibration::body_force(const Point<dim>&, double) const;             \
  template ExactMotion<dim> AxisAlignedVibration::motion() const;
MFREE_VIBRATION_MEMBERS(2)
MFREE_VIBRATION_MEMBERS(3)
#undef MFREE_VIBRATION_MEMBERS

}  // namespace mfree

#pragma once
// The axis-aligned vibration problem (SPEC section 6; seed 000 after Sadeghirad et al.
// 2011): a manufactured large-deformation solution of rho0 u_tt = Div P + rho0 b for the
// compressible Neo-Hookean material on the square [0, L]^2, with c = sqrt(E / rho0):
//
//   u_x = A sin(2 pi X / L) sin(c pi t / L),   u_y = A sin(2 pi Y / L) sin(c pi t / L + pi)
//
// and the body force of SPEC section 6 (seed 000's eq. (42) with its missing square on pi
// restored), evaluated at reference positions. F is diagonal, so the walls X, Y in {0, L}
// carry no shear traction and the normal displacement vanishes there: slip walls. The period
// is 2 L / c. Units: SI as given (m, s, Pa, kg/m^3).
//
// On the cube [0, L]^3 the same with u_z = A sin(2 pi Z / L) sin(c pi t / L) (as u_x): with
// F = diag(F_ii), Div P_i = F_ii,i [mu (1 + 1 / F_ii^2) + lambda (1 - ln J) / F_ii^2] and
// F_ii,i = -(2 pi / L)^2 u_i, so b_i has the plane form with J = F_xx F_yy F_zz. The
// members are templates on the dimension (2, 3) of the point they take.

#include "mfree/core/exact_motion.hpp"
#include "mfree/core/types.hpp"
#include "mfree/materials/neo_hookean.hpp"

namespace mfree {

struct AxisAlignedVibration {
  double amplitude = 0.05;  ///< A [m]
  double length = 1.0;      ///< L [m]
  double youngs_modulus = 1e7;
  double poisson_ratio = 0.3;
  double density = 1000.0;  ///< rho0

  [[nodiscard]] double wave_speed() const;  ///< c = sqrt(E / rho0)
  [[nodiscard]] double period() const { return 2.0 * length / wave_speed(); }
  /// InputError for |A| >= L / (2 pi): F_ii = 1 + (2 pi A / L) sin(c pi t / L) cos(2 pi X_i / L)
  /// then reaches 0, the motion itself inverts the material and its body force (ln J) is not a
  /// number.
  void check_amplitude() const;
  [[nodiscard]] NeoHookean material() const { return {lame_constants(youngs_modulus, poisson_ratio)}; }

  template <int dim>
  [[nodiscard]] Point<dim> displacement(const Point<dim>& x, double t) const;
  template <int dim>
  [[nodiscard]] Point<dim> velocity(const Point<dim>& x, double t) const;
  template <int dim>
  [[nodiscard]] Point<dim> acceleration(const Point<dim>& x, double t) const;
  template <int dim>
  [[nodiscard]] Tensor2<dim> deformation_gradient(const Point<dim>& x, double t) const;
  template <int dim>
  [[nodiscard]] Tensor2<dim> cauchy_stress(const Point<dim>& x, double t) const;
  /// b (force per unit mass) with rho0 u_tt = Div P + rho0 b.
  template <int dim>
  [[nodiscard]] Point<dim> body_force(const Point<dim>& x, double t) const;
  /// The fields above as the solvers' error measures take them.
  template <int dim>
  [[nodiscard]] ExactMotion<dim> motion() const;
};

}  // namespace mfree

#pragma once
// Stress intensity factors K_I, K_II and the J-integral of a crack tip by the interaction
// integral in domain form: Yau, Wang & Corten, J. Appl. Mech. 47 (1980) 335 (the
// interaction of the actual field with an auxiliary one); Moran & Shih, Eng. Fract. Mech. 27
// (1987) 615 (the domain form); as used in XFEM by Moes, Dolbow & Belytschko, IJNME 46
// (1999) 131, section on stress intensity factors. A post-processor: it needs only samples
// of the solution.
//
// In crack-tip coordinates (near_tip_field.hpp: x1 along the crack's extension), with a
// weight q equal to 1 near the tip and 0 on the outer boundary of the domain A,
//   J         = int_A [sigma_ij u_i,1 - W delta_1j] q_,j dA,        W = sigma_ij eps_ij / 2,
//   I^(1,2)   = int_A [sigma_ij u^aux_i,1 + sigma^aux_ij u_i,1 - W^(1,2) delta_1j] q_,j dA,
//   W^(1,2)   = sigma_ij eps^aux_ij,
// and I^(1,2) = 2 (K_I K_I^aux + K_II K_II^aux) / E' (Yau et al.: J of the sum of the two
// fields less the two J's, with J = (K_I^2 + K_II^2) / E'), so with the auxiliary field
// Williams' mode I (K_I^aux = 1, K_II^aux = 0) K_I = E' I / 2, and with mode II
// K_II = E' I / 2; E' = E (plane stress), E / (1 - nu^2) (plane strain). J is I^(1,1) / 2,
// the actual field with itself. The domain form holds when the field is in equilibrium without
// body force in A, the crack faces in A are straight and traction free, and q = 0 on A's
// outer boundary.
//
// The weight q (DomainWeight) depends on the distance rho from the tip only: q = 1 for
// rho <= r0 (inner radius), q = 0 for rho >= r1 (outer radius), and between them either
//   linear: q = (r1 - rho) / (r1 - r0)  (gradient jumps at r0 and r1), or
//   smooth: q = 1 - (10 s^3 - 15 s^4 + 6 s^5), s = (rho - r0) / (r1 - r0)  (C^2 at r0, r1),
// so only the annulus r0 < rho < r1 contributes, and the tip itself is never evaluated.
//
// How a caller uses it:
// - Tip and frame: the crack tip position and the direction of extension (the crack's last
//   segment, pointing out of the crack).
// - Radii: r1 of 2-4 nodal spacings (the near-tip solution of a meshfree discretisation is
//   its least accurate part, and the annulus should hold a few layers of quadrature points),
//   r0 ~ r1 / 2 or one nodal spacing; the annulus must lie inside the body (coverage below)
//   and must not reach another crack or a loaded boundary. Comparing two or three radii
//   shows the discretisation error (the exact value is domain independent).
// - Samples: every quadrature point of the Galerkin rule with its weight, and the solution's
//   displacement gradient and stress there (points outside the annulus may be passed; they
//   contribute nothing). The stress should be the material's D sym(grad u) of the same
//   gradient. The smooth weight suits a background-cell rule that the circles cut (its
//   integrand has no kink): with the exact K-field on 4 x 4 Gauss cells of side r1 / 40,
//   K comes out to 5e-8 with it and to only 1e-4 to 1e-3 with the linear weight; the
//   linear one suits a rule whose cells follow the circles. The fields jump across the
//   crack, so a cell the crack crosses needs points on each side (a split cell). Points on
//   the crack line behind the tip go to the face their local x2 sign picks (atan2): give
//   the values of that face's side.
// - Coverage: the rule's sum of w |grad q| over the exact int |grad q| dA = pi (r0 + r1).
//   It drops below 1 when the annulus leaves the body or the rule misses part of it; the
//   call throws InputError when it is off 1 by more than the tolerance.

#include <span>

#include "mfree/core/types.hpp"
#include "mfree/galerkin/near_tip_field.hpp"
#include "mfree/materials/linear_elastic.hpp"

namespace mfree {

enum class WeightProfile { linear, smooth };

/// The weight q(rho) of the domain integral and its annulus r0 < rho < r1.
struct DomainWeight {
  double inner_radius = 0.0;  ///< r0 > 0 (length)
  double outer_radius = 0.0;  ///< r1 > r0 (length)
  WeightProfile profile = WeightProfile::smooth;

  /// Throws InputError naming the radii unless 0 < r0 < r1 (finite).
  void validate() const;
  /// q(rho) in [0, 1].
  [[nodiscard]] double value(double rho) const;
  /// dq / drho (<= 0; zero outside the annulus); grad q = (dq/drho) x / rho.
  [[nodiscard]] double slope(double rho) const;
  /// int |grad q| dA over the plane = 2 pi int |q'| rho drho = pi (r0 + r1) for both
  /// profiles.
  [[nodiscard]] double slope_integral() const;
};

/// The integrands at one point (per unit area, before q's gradient is summed with weights).
struct InteractionIntegrand {
  double mode_one = 0.0;  ///< I^(1, mode I aux with K = 1)
  double mode_two = 0.0;  ///< I^(1, mode II aux with K = 1)
  double j = 0.0;         ///< the J integrand
};

/// The per-point kernel, everything in crack-tip coordinates: the actual displacement
/// gradient H(i, j) = u_i,j and stress sigma_ij at a point with polar coordinates (r > 0,
/// theta) about the tip, and grad q there.
InteractionIntegrand interaction_integrand(const Mat2& grad_u, const Mat2& stress, double r, double theta,
                                           const Vec2& grad_q, const NearTipConstants& constants);

struct StressIntensity {
  double k1 = 0.0;        ///< K_I (stress * sqrt(length))
  double k2 = 0.0;        ///< K_II
  double j = 0.0;         ///< J (energy per unit crack area), directly from the field
  double coverage = 0.0;  ///< sum w |grad q| / (pi (r0 + r1)); 1 for a rule covering the annulus
  Index points_used = 0;  ///< samples inside the annulus
};

/// K_I, K_II and J of one tip from samples of the solution: points x_k (global coordinates)
/// with weights w_k (area), displacement gradients H_k(i, j) = u_i,j (global) and stresses
/// (Voigt xx, yy, xy, global). All spans have one entry per point.
/// Throws InputError for spans of different sizes, a bad tip, material or weight, or a
/// coverage off 1 by more than `coverage_tolerance`; NumericalError (naming the point) for
/// a non-finite sample inside the annulus.
StressIntensity interaction_integral(const CrackTipFrame& tip, const LinearElastic& material,
                                     const DomainWeight& weight, std::span<const Vec2> points,
                                     std::span<const double> weights,
                                     std::span<const Mat2> displacement_gradients,
                                     std::span<const Eigen::Vector3d> stresses,
                                     double coverage_tolerance = 0.02);

}  // namespace mfree

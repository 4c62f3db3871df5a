#pragma once
// Williams' near-tip field of a straight crack in an isotropic linear elastic body: the
// leading, square-root term of the series for modes I and II, in the forms of Anderson,
// Fracture Mechanics (3rd ed., 2005), Tables 2.1 (stresses) and 2.2 (displacements).
//
// Crack-tip frame: origin at the tip, axis e1 along the crack's extension (from the crack
// into the material ahead of the tip), e2 = e1 rotated by +90 degrees. Polar coordinates
// (r, theta) about the tip with theta in (-pi, pi] measured from e1 (theta = atan2(x2, x1)
// of the local coordinates): the crack faces are theta = +pi (upper face) and theta = -pi
// (lower face). A point on the line behind the tip goes to the face its x2 sign picks
// (+0 upper, -0 lower), as atan2 does.
//
// Units: K in stress * sqrt(length), r in length, displacements in length.

#include "mfree/core/types.hpp"
#include "mfree/materials/linear_elastic.hpp"

namespace mfree {

/// A crack tip and its frame. `direction` need not be normalised; it must be finite and
/// nonzero (validate()).
struct CrackTipFrame {
  Vec2 position = Vec2::Zero();
  Vec2 direction = Vec2::UnitX();

  /// Throws InputError naming the tip for a non-finite position or a zero or non-finite
  /// direction.
  void validate() const;
  /// Q = [e1 e2] (columns are the local axes in global coordinates): x = position + Q x'.
  [[nodiscard]] Mat2 rotation() const;
  /// Local coordinates x' = Q^T (x - position).
  [[nodiscard]] Vec2 to_local(const Vec2& x) const { return rotation().transpose() * (x - position); }
};

/// The elastic constants the near-tip fields use.
struct NearTipConstants {
  double shear_modulus = 0.0;      ///< mu = E / (2 (1 + nu))
  double kolosov = 0.0;            ///< kappa = 3 - 4 nu (plane strain), (3 - nu) / (1 + nu) (plane stress)
  double effective_modulus = 0.0;  ///< E' = E / (1 - nu^2) (plane strain), E (plane stress)
};
NearTipConstants near_tip_constants(const LinearElastic& material);

/// The field at one point, in crack-tip coordinates.
struct NearTipState {
  Vec2 displacement = Vec2::Zero();  ///< u'_i
  Mat2 gradient = Mat2::Zero();      ///< H'(i, j) = du'_i / dx'_j
  Mat2 stress = Mat2::Zero();        ///< sigma'_ij (symmetric; sigma_zz as the plane model implies)
};

/// Williams' field for stress intensity factors k1 (mode I) and k2 (mode II) at polar
/// coordinates (r, theta) about the tip. Displacements vanish at the tip (no rigid motion).
/// Throws NumericalError for r <= 0 or non-finite r or theta (the stresses are singular at
/// the tip).
NearTipState williams_field(double k1, double k2, double r, double theta, const NearTipConstants& c);

}  // namespace mfree

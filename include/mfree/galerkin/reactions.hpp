#pragma once
// Reactions of the essential boundary parts and the resultant of the applied loads: the
// force and the moment about the origin that each displacement or slip condition exerts on
// the body, beside those of the body force, tractions and pressures, so that equilibrium can
// be read off.
//
// Reaction of part Gamma_p (per unit thickness) on the reference boundary:
//
//   R_p = int_Gp lambda^h dS,   M_p = int_Gp x × lambda^h dS   (in the plane a × b = a_x b_y - a_y b_x),
//   lambda^h = Pi P(F^h) N - (beta M / h) Pi (u^h - ubar)
//
// the flux of Nitsche's form (total_lagrangian.hpp) at the boundary Gauss points: the first
// Piola traction of the state (the committed one, for laws with history; at small strain
// P = sigma) and the penalty term, both restricted by Pi (I for displacement, N N^T for slip:
// a wall carries only a normal force). The symmetrising term -int Pi (C : grad v) N . (u - ubar)
// is no flux: it tests the gap with the gradient of v and drops from every balance below.
//
// Applied loads: F = sum_K w_K b(X_K) + int_Gt tbar dS (tractions, dead pressures -p N, follower
// pressures -p R x,S on the current boundary), with their moments, at the domain and boundary
// quadrature points that the weak form uses.
//
// Moment arm: the reference position X for the small-strain laws (is_small_strain(): P = sigma
// symmetric, the theory's moment balance is about X), the current position x = X + u^h for
// the finite-strain laws (a finite-strain user expects the forces to act where the body is).
//
// Why sum_p R_p + F = 0 for the discrete solution. Test the discrete equations
// f_int(d) + f_c(d) - f_ext = 0 (f_c the boundary_force: Nitsche and follower terms) with the
// constant virtual displacement v_I = e (every coefficient e, so v^h = e by the partition of
// unity sum_I phi_I = 1):
//   - Nitsche: sum_I phi_I = 1 and sum_I grad phi_I = 0 (the boundary points' trial gradients
//     reproduce constants exactly), so the symmetrising term vanishes and the rest is
//     -e . sum_p R_p;
//   - applied: e . F (body force and tractions against sum_I phi_I = 1);
//   - internal: e . sum_K w_K P_K sum_I t_I(X_K), t_I the test gradients of row K.
// So  sum_p R_p + F = sum_K w_K P_K sum_I t_I(X_K) - sum_I r_I  (r the residual left by the
// solver: round-off for the linear solve, the Newton tolerance for load steps). Direct and
// projected gradients (and the symmetric correction, which keeps sum_I g_I = 0) make the first
// term vanish to round-off: the balance is exact whatever the discretisation error. VCI's
// test gradients t_I = g_I + xi_I^T m(c_K) do not sum to zero on a row: the imbalance is
// sum_K w_K P_K sum_I xi_I^T m(c_K), which vanishes for uniform stress (sum_K w_K t_I = b_I
// sums over I to sum_b w_b N_b = 0) and with refinement otherwise. Measured
// (tests/galerkin/test_reactions.cpp): the cantilever with Gauss cells and VCI, |R + F| / P =
// 5.2e-5, 3.1e-6, 1.9e-6 and the moment's 1.8e-4, 1.2e-6, 9.0e-7 of P L at h = 3, 1.5, 0.75;
// a quadratic field on a perturbed cloud (h = 1/8) 4.3e-5, equal to the nodal sum of f_int.
//
// Moments: the rotation v_I = W x_I (W the rotation by +90 degrees, x_I = X_I or X_I + d_I),
// v^h = W x by linear reproduction, gives the same with sum_K w_K P_K : (W sum_I x_I t_I^T)
// in place of the internal term; with t = g that is P : W (small strain, sigma symmetric) or
// P : W F (finite strain, P F^T = J sigma symmetric): zero. At finite strain the symmetrising
// term leaves int Pi (u - ubar) . (C : (W grad u)) N, of the order of the gap times the
// strain: the moment balance holds to that order (the force balance exactly). Measured on a
// Neo-Hookean block (4 x 1, h = 1/4, the load steps of the test): 5e-5 to 6e-4 of the largest
// force times the largest arm with beta = 100, 1e-5 to 1.5e-4 with beta = 1000.
//
// Dynamics: the equations are M a + f_int + f_c = f_ext, so sum_p R_p + F = sum_I (M a)_I = the
// rate of momentum d/dt int rho0 u_t^h (both masses: sum_I of a row is the row-sum mass), and
// the moments balance with sum_I x_I × (M a)_I. Reported as `inertia`.
//
// Units: in the plane forces per unit thickness [N/m], moments [N m / m]; in space [N], [N m];
// as the material's E is given.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/total_lagrangian.hpp"

namespace mfree {

/// A moment: in the plane its z component (counter-clockwise positive), in space the vector.
template <int dim>
using Moment = std::conditional_t<dim == 2, double, Point<3>>;
template <int dim>
Moment<dim> zero_moment() {
  if constexpr (dim == 2)
    return 0.0;
  else
    return Point<3>::Zero();
}

/// A force and its moment about the origin.
template <int dim>
struct Resultant {
  Point<dim> force = Point<dim>::Zero();
  Moment<dim> moment = zero_moment<dim>();
  Resultant& operator+=(const Resultant& o) {
    force += o.force;
    moment += o.moment;
    return *this;
  }
};

/// a × b: the z component of the cross product in the plane, the vector in space.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline Point<3> cross(const Point<3>& a, const Point<3>& b) { return a.cross(b); }
/// |moment|.
inline double magnitude(double m) { return std::abs(m); }
inline double magnitude(const Point<3>& m) { return m.norm(); }

/// Nitsche's flux at one point: lambda = Pi P N - (beta M / h) Pi (u - ubar), from the two
/// parts the model gives (TotalLagrangian<dim>::NitscheValues) and the penalty beta M / h.
template <int dim>
Point<dim> nitsche_flux(const Point<dim>& traction, const Point<dim>& gap, double penalty) {
  return traction - penalty * gap;
}

template <int dim>
struct PartReaction {
  std::string name;         ///< the condition's name
  Resultant<dim> reaction;  ///< what the support exerts on the body
  /// sum of |w lambda| over its points: the reaction's size where it balances itself (a
  /// support that pulls a ring outward all round exerts no net force)
  double magnitude = 0.0;
};

template <int dim>
struct Reactions {
  std::vector<PartReaction<dim>> parts;   ///< one per essential condition, in the conditions' order
  Resultant<dim> applied;                 ///< body force, tractions and pressures
  double applied_magnitude = 0.0;         ///< sum of |w t| and |w b|: the loads' size when they balance
  std::optional<Resultant<dim>> inertia;  ///< dynamics: sum_I (M a)_I and its moment
  bool current_arm = false;          ///< moments about x = X + u^h (finite strain), else X
  double arm = 0.0;                  ///< the largest |x| of a boundary point: the moments' scale

  /// sum_p R_p + F - inertia: zero for the exact discrete balance.
  [[nodiscard]] Resultant<dim> balance() const;
  /// |balance force| / the largest of |F|, the applied magnitude, |R_p| and the parts'
  /// magnitudes, |inertia| (0 when all vanish).
  [[nodiscard]] double force_imbalance() const;
  /// |balance moment| / (arm × that force scale).
  [[nodiscard]] double moment_imbalance() const;
};

/// The names of the essential conditions of `problem`, in order: the parts of reactions().
template <int dim>
std::vector<std::string> essential_parts(const SolidProblem<dim>& problem);

/// The reactions and applied loads of `model` at coefficients d and load `load` (dim 2, 3).
template <int dim>
Reactions<dim> reactions(const TotalLagrangian<dim>& model, const Eigen::VectorXd& d, const LoadState& load);

/// sum_I f_I and sum_I x_I × f_I of nodal forces f (dim N), x_I = X_I (+ d_I when current_arm):
/// the resultant of the forces the coefficients' equations hold, e.g. the inertia M a.
template <int dim>
Resultant<dim> nodal_resultant(const Eigen::VectorXd& f, const std::vector<Point<dim>>& nodes,
                               const Eigen::VectorXd& d, bool current_arm);

/// The reactions of a linear solve (solve_elasticity with these settings on `domain`): the
/// model rebuilt on its discretisation.
Reactions<2> elastic_reactions(const Domain& domain, const ElasticitySettings& settings,
                               const ElasticityResult& result);

}  // namespace mfree

#pragma once
// Integration consistency of the weak-form gradients (SPEC section 3).
//
// The patch test of order p needs, for every node I and every monomial m of degree < p
// (linear RK: m = 1; quadratic RK: m in {1, x, y}),
//
//     sum_K w_K [ g_I(x_K) m(c_K) + phi_I(x_K) grad m(x_K) ]
//         = sum over boundary points of w_b phi_I(x_b) m(x_b) n_b                      (IC_p)
//
// the discrete divergence theorem for phi_I m, with m at the row centroid c_K where the
// projected gradient of a field of degree p is exact (GalerkinQuadrature<2>). For m = 1 it
// reads sum_K w_K g_I(x_K) = b_I. Rows also reproduce gradients, sum_I g_I x_I^T = I and
// sum_I g_I = 0 (R; for quadratic RK the quadratic monomials too, at c_K). Projected
// gradients satisfy (R) exactly and (IC_p) up to the background lattice error. Two
// corrections restore (IC):
//
//   vci        variationally consistent integration (Chen, Hillman, Rueter 2013, "An
//              arbitrary order variationally consistent integration for Galerkin meshfree
//              methods", IJNME 95): test gradients
//                ghat_I(x_K) = g_I(x_K) + xi_I^T m(c_K)
//              on the rows holding I, xi_I (one 2-vector per monomial) solving the small
//              moment system M_I xi_I = R_I, M_I = sum_K w_K m(c_K) m(c_K)^T, R_I the
//              residual of (IC_p). Of the RK order: quadratic RK gets quadratic VCI, which
//              passes the quadratic patch test. For quadratic RK the conditions are imposed
//              for m in {1, x, y, x^2, xy, y^2}, one degree beyond the patch test: the test
//              side then integrates every quadratic stress field consistently, and the
//              quadrature error of Gauss cells stops capping the L2 rate (cantilever, 4 x 4
//              points: L2 rates 3.3 lattice and 3.5 perturbed against 1.75 and 0.65 with
//              {1, x, y}; verification/cantilever/README.md). Trial gradients keep (R): the stiffness is
//              non-symmetric (UMFPACK).
//   symmetric  (IC_1) only: the smallest correction delta of the gradients themselves (used
//              for test and trial alike) that meets (IC_1) and keeps the linear part of (R):
//              on row K,
//                delta_K = w_K (I - Q_K) lambda_K,
//              Q_K the orthogonal projector onto span{1, x_I, y_I} over the row's nodes (so
//              linear (R) is untouched), lambda per node solving, per component,
//                A lambda = r,  A = sum_K w_K^2 S_K^T (I - Q_K) S_K,
//              a symmetric positive semi-definite system whose null space span{1, x, y} is
//              orthogonal to r (sum_I r_I = 0 and sum_I r_I x_I^T = 0 hold whenever the
//              weights integrate 1 and x exactly). A is assembled on the node-to-node
//              pattern of the rows and solved for both components by the [solver]'s
//              method: CHOLMOD, or CG with GAMG on large clouds. It behaves like a
//              fourth-order operator: its CG iterations grow with the cloud (19 to 40 per
//              solve from 10^4 to 10^6 DOFs with GAMG's coarse level of 5000 equations).
//              The stiffness stays symmetric positive definite (CHOLMOD or CG). For
//              quadratic RK it breaks the quadratic part of (R), which caps the energy rate
//              near 1.5 instead of 2 (verification/cantilever/README.md).
//
// Monomials are taken in node-local scaled coordinates, m = [1, (x - x_I) / s_I,
// (y - y_I) / s_I] with s_I the largest |c_K - x_I| over the node's rows: (IC_p) for these is
// an invertible combination of (IC_p) for {1, x, y}, and M_I stays well conditioned.
//
// In space the conditions and VCI are the same with the monomials of x, y, z (1, 4 or 10 of
// them); the symmetric correction is plane only.

#include <string_view>
#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/galerkin/boundary_quadrature.hpp"
#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/linalg/linear_solver.hpp"
#include "mfree/linalg/node_pattern.hpp"

namespace mfree {

enum class Consistency { none, vci, symmetric };
/// symmetric, vci, none: the names scenes use.
const NameTable<Consistency>& consistency_names();
std::string_view to_string(Consistency c);

/// The conditions (IC_p) of one domain quadrature, boundary quadrature and RK order, in
/// dim = 2 or 3 (instantiated in the .cpp).
template <int dim>
class ConsistencyConditions {
 public:
  /// The monomials of degree <= 2: 1, then z_a, then z_a z_b (a <= b): 6 in the plane, 10 in space.
  static constexpr int max_monomials = (dim + 1) * (dim + 2) / 2;
  /// Row l of a node's matrix is the condition of monomial m_l (its dim components).
  using Moments = Eigen::Matrix<double, max_monomials, dim>;
  using Monomials = Eigen::Matrix<double, max_monomials, 1>;

  /// `at_boundary`: the trial functions sampled at bq's points. The arrays are viewed, not
  /// copied: q must outlive this object.
  ConsistencyConditions(const GalerkinQuadrature<dim>& q, const std::vector<Point<dim>>& nodes,
                        const GalerkinQuadrature<dim>& at_boundary, const BoundaryQuadrature<dim>& bq,
                        RKOrder order);

  /// r_I = b_I - sum_K w_K g_I(x_K), the residual of (IC_1), for every node.
  [[nodiscard]] std::vector<Point<dim>> linear_residuals(const std::vector<Point<dim>>& gradients) const;
  /// max over nodes and monomials of the residual of (IC_p) for the given gradients (same
  /// layout as q.grad), relative to max_I |b_I|: 0 for a consistent rule.
  [[nodiscard]] double defect(const std::vector<Point<dim>>& gradients) const;
  /// VCI test gradients (same layout as q.grad).
  [[nodiscard]] std::vector<Point<dim>> vci_test_gradients() const;

 private:
  /// m(c_K) of node i in its scaled coordinates.
  [[nodiscard]] Monomials monomial(Index i, const Point<dim>& x) const;
  /// grad m at x, row l for monomial m_l (1 / s_I times the gradient in scaled coordinates).
  [[nodiscard]] Moments monomial_gradient(Index i, const Point<dim>& x) const;
  /// The residual of (IC_p) at node i for the gradients g (rows beyond the order's monomials zero).
  [[nodiscard]] Moments residual(Index i, const std::vector<Point<dim>>& g) const;

  const GalerkinQuadrature<dim>& q_;
  const std::vector<Point<dim>>& nodes_;
  int monomials_;
  RowIncidence incidence_;
  std::vector<double> scale_;     ///< s_I
  std::vector<Moments> target_;   ///< boundary sum minus sum_K w_K phi_I(x_K) grad m, per node
};

struct SymmetricCorrection {
  double residual = 0.0;     ///< relative residual |A lambda - r| / |r| (worst component)
  SolverReport solver;       ///< the node system's solver and what it did
};
/// Applies the symmetric correction to q.grad in place; r: the residuals of (IC_1) of q.grad
/// (ConsistencyConditions::linear_residuals). The node system A is solved by the solver of
/// `solver` (linear_solver.hpp).
SymmetricCorrection make_consistent_symmetric(GalerkinQuadrature<2>& q, const std::vector<Vec2>& nodes,
                                              const std::vector<Vec2>& r, const SolverSettings& solver);

}  // namespace mfree

#pragma once
// Integration consistency of the weak-form gradients (SPEC section 3).
//
// The linear patch test needs, for every node I,
//
//     sum_K w_K g_I(x_K) = b_I := sum over boundary points of w_b phi_I(x_b) n_b       (IC)
//
// and at every quadrature point the gradient reproduction sum_I g_I x_I^T = I,
// sum_I g_I = 0 (R). Projected gradients satisfy (R) exactly and (IC) up to the background
// lattice error. Two corrections restore (IC):
//
//   vci        variationally consistent integration (Chen, Hillman, Rueter 2013): test
//              gradients ghat_I = g_I + eta_I on the rows holding I, with
//              eta_I = r_I / sum of w_K over those rows, r_I = b_I - sum_K w_K g_I(x_K).
//              Trial gradients stay: the stiffness is non-symmetric (UMFPACK).
//   symmetric  the smallest correction delta of the gradients themselves (used for test and
//              trial alike) that meets (IC) and keeps (R): on row K,
//                delta_K = w_K (I - Q_K) lambda_K,
//              Q_K the orthogonal projector onto span{1, x_I, y_I} over the row's nodes (so
//              (R) is untouched), lambda per node solving, per component,
//                A lambda = r,  A = sum_K w_K^2 S_K^T (I - Q_K) S_K,
//              a symmetric positive semi-definite system whose null space span{1, x, y} is
//              orthogonal to r (sum_I r_I = 0 and sum_I r_I x_I^T = 0 hold whenever the
//              weights integrate 1 and x exactly). A is assembled on the node-to-node
//              pattern of the rows and factorised once by CHOLMOD for both components:
//              it behaves like a fourth-order operator, too ill-conditioned for iterative
//              solvers. The stiffness stays symmetric positive definite (CHOLMOD).

#include <string_view>
#include <vector>

#include "mfree/galerkin/galerkin_quadrature.hpp"

namespace mfree {

enum class Consistency { none, vci, symmetric };
std::string_view to_string(Consistency c);

/// b_I for every node, from the trial functions sampled at the boundary points.
std::vector<Vec2> boundary_sums(const GalerkinQuadrature& at_boundary, const std::vector<Vec2>& normals,
                                const std::vector<double>& weights, Index nodes);

/// max_I |b_I - sum_K w_K g_I(x_K)| / max_I |b_I|: 0 for a consistent rule.
double consistency_defect(const GalerkinQuadrature& q, const std::vector<Vec2>& gradients,
                          const std::vector<Vec2>& b);

/// VCI test gradients (same layout as q.grad).
std::vector<Vec2> vci_test_gradients(const GalerkinQuadrature& q, const std::vector<Vec2>& b);

struct SymmetricCorrection {
  double residual = 0.0;     ///< relative residual |A lambda - r| / |r| (worst component)
};
/// Applies the symmetric correction to q.grad in place.
SymmetricCorrection make_consistent_symmetric(GalerkinQuadrature& q, const std::vector<Vec2>& nodes,
                                              const std::vector<Vec2>& b);

}  // namespace mfree

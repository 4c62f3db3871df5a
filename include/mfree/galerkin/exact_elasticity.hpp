#pragma once
// The interface of an exact solution of small-strain elasticity, as the solver sees it, and
// the error norms measured against one with an independent quadrature (never the solver's
// own). The concrete solutions are problems (problems/).

#include <functional>

#include "mfree/core/types.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/materials/linear_elastic.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

/// Displacement, stress and body force as functions of the position.
struct ExactElasticity {
  std::function<Vec2(const Vec2&)> displacement;
  std::function<Eigen::Vector3d(const Vec2&)> stress;  ///< Voigt (xx, yy, xy)
  std::function<Vec2(const Vec2&)> body_force;          ///< b with div sigma + b = 0
  /// Traction sigma n on a boundary with outward normal n.
  [[nodiscard]] Vec2 traction(const Vec2& x, const Vec2& n) const {
    const Eigen::Vector3d s = stress(x);
    return {s[0] * n.x() + s[2] * n.y(), s[2] * n.x() + s[1] * n.y()};
  }
};

struct ElasticErrors {
  double l2_displacement = 0.0;  ///< ||u^h - u||_L2 / ||u||_L2
  double energy = 0.0;           ///< (int (eps^h - eps) D (eps^h - eps))^1/2 / (int eps D eps)^1/2
  double l2_stress = 0.0;        ///< ||sigma^h - sigma||_L2 / ||sigma||_L2
  double strain_energy = 0.0;    ///< 1/2 int eps^h D eps^h of the discrete solution
};

/// The small-strain law at a point (of its region).
using LawAt = std::function<const LinearElastic&(const Vec2&)>;

/// Errors of u^h = sum phi_I d_I (strain from the true gradients of phi_I) on the rule, the
/// energy and the stress of the error by the law at each point.
ElasticErrors elastic_errors(const RKShapeFunctions<2>& trial, const Eigen::VectorXd& d, const LawAt& law_at,
                             const ExactElasticity& exact, const QuadratureRule<2>& rule);

}  // namespace mfree

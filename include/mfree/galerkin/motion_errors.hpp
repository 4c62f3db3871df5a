#pragma once
// Errors of a meshfree motion against an exact one, measured with an independent quadrature
// (Gauss points on cells, never the solver's own) as root-mean-square values over the body
// (seed 000 eq. (43) with the sum over particles replaced by the integral):
//
//   e_u = ( int |u^h - u|^2 / |Omega| )^1/2,  u^h = sum phi_I d_I
//   e_v = ( int |v^h - v|^2 / |Omega| )^1/2,  v^h = sum phi_I v_I (the coefficients' rates)
//   e_s = ( int |sigma^h - sigma|_F^2 / |Omega| )^1/2,  sigma^h the Cauchy stress of
//         F^h = I + sum d_I grad phi_I^T (true gradients), |.|_F the Frobenius norm.
//
// The shape functions are sampled at the points once; each evaluation is a pass over them.
// dim = 2 (plane) or 3; explicitly instantiated for both.

#include "mfree/core/exact_motion.hpp"
#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/materials/material.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

struct MotionErrors {
  double time = 0.0;
  double displacement = 0.0;  ///< RMS, length units
  double velocity = 0.0;      ///< RMS, length / time
  double stress = 0.0;        ///< RMS, stress units
};

template <int dim>
class MotionErrorSampler {
 public:
  /// law_at: the law at each of the rule's points (asked once per point).
  MotionErrorSampler(const RKShapeFunctions<dim>& trial, const QuadratureRule<dim>& rule,
                     const MaterialAt<dim>& law_at);
  [[nodiscard]] MotionErrors operator()(const Eigen::VectorXd& d, const Eigen::VectorXd& v, double time,
                                        const ExactMotion<dim>& exact) const;

 private:
  GalerkinQuadrature<dim> at_;
  std::vector<Material> law_;  ///< per point
  double volume_ = 0.0;
};

}  // namespace mfree

#pragma once
// The relative L2 and energy errors of a 3D solution u^h = sum phi_I d_I against an exact
// small-strain field (u, grad u), over a rule independent of the discretisation (e.g.
// gauss_cell_rule): |u^h - u|_L2 / |u|_L2 and a(e, e)^(1/2) / a(u, u)^(1/2) with e = u^h - u and
// a the 3D linear law's energy, sigma = lambda tr(eps) I + 2 mu eps, with the Lamé constants of
// the law at each point (a solid of several regions). The functions are sampled in
// blocks of points (all at once would take gigabytes on fine rules).

#include <Eigen/Dense>
#include <functional>

#include "mfree/core/types.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/materials/finite_strain.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

struct SmallStrainErrors {
  double l2 = 0.0, energy = 0.0;  ///< relative
};

/// sigma of the 3D linear law for a displacement gradient g.
Tensor2<3> linear_stress(const Lame& lame, const Tensor2<3>& g);

/// lame_at, exact_u and exact_grad are called from several threads at once (OpenMP).
SmallStrainErrors small_strain_errors(const RKShapeFunctions<3>& trial, const Eigen::VectorXd& d,
                                      const QuadratureRule<3>& rule,
                                      const std::function<Lame(const Point<3>&)>& lame_at,
                                      const std::function<Point<3>(const Point<3>&)>& exact_u,
                                      const std::function<Tensor2<3>(const Point<3>&)>& exact_grad);

}  // namespace mfree

#pragma once
// Small-strain elasticity on meshfree clouds with Nitsche's method for essential
// boundary conditions (SPEC section 4):
//
//   a(u, v) = sum_K w_K eps(v)_K . D eps(u)_K
//             - int_Gu [ v . (sigma(u) n) + (sigma(v) n) . u ] + (beta M / h) int_Gu v . u
//   l(v)    = sum_K w_K v_K . b_K + int_Gt v . tbar
//             - int_Gu (sigma(v) n) . ubar + (beta M / h) int_Gu v . ubar
//
// M the P-wave modulus of the law (lambda + 2 mu in plane strain, E / (1 - nu^2) in plane
// stress): the largest stiffness of the tractions sigma(u) n that the penalty must dominate.
// Scaled by E instead, the penalty falls below the consistency terms as nu -> 1/2 (lambda / E
// grows without bound) and the form loses coercivity.
//
// Domain terms at the quadrature points with the gradients of the GalerkinQuadrature<2> (test
// gradients may differ: VCI); boundary terms at the boundary Gauss points with the true
// gradients of the trial functions. Unknowns: d = (d_0x, d_0y, d_1x, ...), coefficients of the
// RK functions, not nodal displacements: u^h(x) = sum_I phi_I(x) d_I.
//
// Boundary parts: each boundary segment takes the first condition whose region box holds
// its midpoint; segments in no region are traction free. The system is the total-Lagrangian
// one (total_lagrangian.hpp) with the small-strain law, linearised at d = 0: one assembly
// path for both.

#include <functional>
#include <vector>

#include "mfree/galerkin/total_lagrangian.hpp"
#include "mfree/materials/linear_elastic.hpp"

namespace mfree {

using VectorField = std::function<Vec2(const Vec2&)>;

struct ElasticityProblem {
  LinearElastic material;  ///< the law everywhere, unless region_materials are given
  /// For a domain of several regions (Domain::regions()), the law of each, in their order;
  /// empty: `material` in every region.
  std::vector<LinearElastic> region_materials;
  VectorField body_force;  ///< b(x), force per volume; empty: none
  std::vector<BoundaryCondition<2>> conditions;
  double nitsche_beta = 100.0;  ///< penalty beta M / h (dimensionless beta)
  double spacing = 1.0;         ///< h in the penalty: nodal spacing

  /// The law of region r.
  [[nodiscard]] const LinearElastic& law(int region) const {
    return region_materials.empty() ? material : region_materials[static_cast<std::size_t>(region)];
  }
  /// The law at x of the domain (its region's; on the boundary, the nearest region's).
  [[nodiscard]] const LinearElastic& law_at(const Domain& domain, const Vec2& x) const {
    return region_materials.empty() ? material : law(domain.nearest_region(x).first);
  }
};
/// The same problem as the total-Lagrangian solver takes it, with the small-strain laws (a
/// caller may swap in other Materials) and the penalty modulus M, the largest of the laws'.
SolidProblem<2> solid_problem(const ElasticityProblem& problem);

struct ElasticitySystem {
  SparseMatrix stiffness;  ///< 2N x 2N
  Eigen::VectorXd load;
  bool symmetric = true;
};

/// Assembles the system. `test_gradients` (same layout as q.grad) replaces q.grad for the
/// test functions when non-null (then the system is non-symmetric).
ElasticitySystem assemble_elasticity(const ElasticityProblem& problem, const Domain& domain, Index nodes,
                                     const GalerkinQuadrature<2>& q, const std::vector<Vec2>* test_gradients,
                                     const BoundaryQuadrature<2>& bq,
                                     const GalerkinQuadrature<2>& at_boundary);

/// Voigt strain at quadrature point k of q for coefficients d: (eps_xx, eps_yy, gamma_xy).
Eigen::Vector3d strain_at(const GalerkinQuadrature<2>& q, Index k, const Eigen::VectorXd& d);
/// u^h = sum_I phi_I d_I at point k of q (dim = 2, 3).
template <int dim>
Point<dim> displacement_at(const GalerkinQuadrature<dim>& q, Index k, const Eigen::VectorXd& d);

}  // namespace mfree

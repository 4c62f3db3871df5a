#include "mfree/galerkin/small_strain_elasticity.hpp"

#include <algorithm>

namespace mfree {

Eigen::Vector3d strain_at(const GalerkinQuadrature<2>& q, Index k, const Eigen::VectorXd& d) {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  for (Index s = q.row_begin(k); s < q.row_end(k); ++s) {
    const Index i = q.nodes[s];
    const Vec2& g = q.grad[s];
    e[0] += g.x() * d[2 * i];
    e[1] += g.y() * d[2 * i + 1];
    e[2] += g.y() * d[2 * i] + g.x() * d[2 * i + 1];
  }
  return e;
}

template <int dim>
Point<dim> displacement_at(const GalerkinQuadrature<dim>& q, Index k, const Eigen::VectorXd& d) {
  Point<dim> u = Point<dim>::Zero();
  for (Index s = q.row_begin(k); s < q.row_end(k); ++s) u += q.phi[s] * d.segment<dim>(dim * q.nodes[s]);
  return u;
}
template Point<2> displacement_at(const GalerkinQuadrature<2>&, Index, const Eigen::VectorXd&);
template Point<3> displacement_at(const GalerkinQuadrature<3>&, Index, const Eigen::VectorXd&);

SolidProblem<2> solid_problem(const ElasticityProblem& problem) {
  SolidProblem<2> solid;
  solid.material = problem.material;
  solid.region_materials.assign(problem.region_materials.begin(), problem.region_materials.end());
  if (problem.body_force) solid.body_force = [b = problem.body_force](const Vec2& x, double) { return b(x); };
  solid.conditions = problem.conditions;
  solid.nitsche_beta = problem.nitsche_beta;
  solid.spacing = problem.spacing;
  return solid;
}

ElasticitySystem assemble_elasticity(const ElasticityProblem& problem, const Domain& domain, Index nodes,
                                     const GalerkinQuadrature<2>& q, const std::vector<Vec2>* test_gradients,
                                     const BoundaryQuadrature<2>& bq,
                                     const GalerkinQuadrature<2>& at_boundary) {
  if (problem.region_materials.empty()) problem.material.validate();
  for (const LinearElastic& m : problem.region_materials) m.validate();
  const TotalLagrangian<2> model(solid_problem(problem), domain, nodes, q, test_gradients, bq, at_boundary);
  // The residual is affine in d: K = its tangent anywhere, f = -residual(0).
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.dofs());
  ElasticitySystem sys;
  sys.symmetric = model.symmetric();
  sys.stiffness = model.zero_matrix();
  model.tangent(zero, {}, sys.stiffness);
  sys.load = model.external_force({}) - model.boundary_force(zero, {});
  return sys;
}

}  // namespace mfree

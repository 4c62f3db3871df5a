#include "mfree/galerkin/reactions.hpp"

#include <algorithm>

namespace mfree {

namespace {

template <int dim>
bool is_essential(const BoundaryCondition<dim>& c) {
  return c.type == BoundaryCondition<dim>::Type::displacement || c.type == BoundaryCondition<dim>::Type::slip;
}

/// sum_s phi_s d_{node s} on row k of q: u^h at point k.
template <int dim>
Point<dim> row_value(const GalerkinQuadrature<dim>& q, Index k, const Eigen::VectorXd& d) {
  Point<dim> u = Point<dim>::Zero();
  for (Index s = q.row_begin(k); s < q.row_end(k); ++s) u += q.phi[s] * d.segment<dim>(dim * q.nodes[s]);
  return u;
}

/// w f and its moment about the arm.
template <int dim>
Resultant<dim> weighted(double w, const Point<dim>& f, const Point<dim>& arm) {
  return {w * f, w * cross(arm, f)};
}

}  // namespace

template <int dim>
Resultant<dim> Reactions<dim>::balance() const {
  Resultant<dim> sum = applied;
  for (const PartReaction<dim>& p : parts) sum += p.reaction;
  if (inertia) {
    sum.force -= inertia->force;
    sum.moment -= inertia->moment;
  }
  return sum;
}

namespace {

template <int dim>
double force_scale(const Reactions<dim>& r) {
  double scale = std::max(r.applied.force.norm(), r.applied_magnitude);
  for (const PartReaction<dim>& p : r.parts) scale = std::max({scale, p.reaction.force.norm(), p.magnitude});
  if (r.inertia) scale = std::max(scale, r.inertia->force.norm());
  return scale;
}

}  // namespace

template <int dim>
double Reactions<dim>::force_imbalance() const {
  const double scale = force_scale(*this);
  return scale > 0.0 ? balance().force.norm() / scale : 0.0;
}

template <int dim>
double Reactions<dim>::moment_imbalance() const {
  const double scale = arm * force_scale(*this);
  return scale > 0.0 ? magnitude(balance().moment) / scale : 0.0;
}

template <int dim>
std::vector<std::string> essential_parts(const SolidProblem<dim>& problem) {
  std::vector<std::string> names;
  for (const BoundaryCondition<dim>& c : problem.conditions)
    if (is_essential(c)) names.push_back(c.name);
  return names;
}

template <int dim>
Reactions<dim> reactions(const TotalLagrangian<dim>& model, const Eigen::VectorXd& d, const LoadState& load) {
  const SolidProblem<dim>& problem = model.problem();
  const BoundaryQuadrature<dim>& bq = model.boundary();
  const GalerkinQuadrature<dim>& at = model.at_boundary();
  Reactions<dim> r;
  const std::vector<Material> laws = problem.laws();
  r.current_arm =
      !std::all_of(laws.begin(), laws.end(), [](const Material& m) { return is_small_strain(m); });
  const auto boundary_arm = [&](Index p) -> Point<dim> {
    return r.current_arm ? Point<dim>(bq.points[p] + row_value(at, p, d)) : bq.points[p];
  };
  for (Index p = 0; p < bq.size(); ++p) r.arm = std::max(r.arm, boundary_arm(p).norm());

  // Essential parts: Nitsche's flux at their points, summed per condition.
  std::vector<std::size_t> part_of(problem.conditions.size(), 0);
  for (std::size_t c = 0; c < problem.conditions.size(); ++c)
    if (is_essential(problem.conditions[c])) {
      part_of[c] = r.parts.size();
      r.parts.push_back({problem.conditions[c].name, {}});
    }
  for (std::size_t b = 0; b < model.nitsche_points(); ++b) {
    const typename TotalLagrangian<dim>::NitscheValues v = model.nitsche_values(b, d, load);
    const std::size_t c = static_cast<std::size_t>(v.condition - problem.conditions.data());
    const Point<dim> flux = nitsche_flux<dim>(v.traction, v.gap, v.penalty);
    r.parts[part_of[c]].reaction += weighted(bq.weights[v.point], flux, boundary_arm(v.point));
    r.parts[part_of[c]].magnitude += std::abs(bq.weights[v.point]) * flux.norm();
  }

  // Applied: tractions and pressures at the boundary points, the body force at the domain's.
  for (Index p = 0; p < bq.size(); ++p) {
    const Point<dim> t = model.boundary_load(p, d, load);
    if (t != Point<dim>::Zero()) {
      r.applied += weighted(bq.weights[p], t, boundary_arm(p));
      r.applied_magnitude += std::abs(bq.weights[p]) * t.norm();
    }
  }
  if (problem.body_force) {
    const GalerkinQuadrature<dim>& q = model.quadrature();
    for (Index k = 0; k < q.size(); ++k) {
      const Point<dim> arm = r.current_arm ? Point<dim>(q.points[k] + row_value(q, k, d)) : q.points[k];
      const Point<dim> b = load.factor * problem.body_force(q.points[k], load.time);
      r.applied += weighted(q.weights[k], b, arm);
      r.applied_magnitude += std::abs(q.weights[k]) * b.norm();
    }
  }
  return r;
}

template <int dim>
Resultant<dim> nodal_resultant(const Eigen::VectorXd& f, const std::vector<Point<dim>>& nodes,
                               const Eigen::VectorXd& d, bool current_arm) {
  Resultant<dim> sum;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Index at = dim * static_cast<Eigen::Index>(i);
    const Point<dim> fi = f.segment<dim>(at);
    const Point<dim> arm = current_arm ? Point<dim>(nodes[i] + d.segment<dim>(at)) : nodes[i];
    sum += {fi, cross(arm, fi)};
  }
  return sum;
}

Reactions<2> elastic_reactions(const Domain& domain, const ElasticitySettings& settings,
                               const ElasticityResult& result) {
  ElasticityProblem problem = settings.problem;
  problem.spacing = settings.nodes.spacing;  // as solve_elasticity takes it
  const TotalLagrangian<2> model(solid_problem(problem), domain, result.node_count(), result.quadrature,
                                 result.test(), result.boundary, result.at_boundary);
  return reactions(model, result.coefficients, {});
}

template struct Reactions<2>;
template struct Reactions<3>;
template std::vector<std::string> essential_parts(const SolidProblem<2>&);
template std::vector<std::string> essential_parts(const SolidProblem<3>&);
template Reactions<2> reactions(const TotalLagrangian<2>&, const Eigen::VectorXd&, const LoadState&);
template Reactions<3> reactions(const TotalLagrangian<3>&, const Eigen::VectorXd&, const LoadState&);
template Resultant<2> nodal_resultant(const Eigen::VectorXd&, const std::vector<Point<2>>&,
                                      const Eigen::VectorXd&, bool);
template Resultant<3> nodal_resultant(const Eigen::VectorXd&, const std::vector<Point<3>>&,
                                      const Eigen::VectorXd&, bool);

}  // namespace mfree

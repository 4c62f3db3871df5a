#include "mfree/galerkin/reactions.hpp"

#include <algorithm>

namespace mfree {

namespace {

bool is_essential(const BoundaryCondition<2>& c) {
  return c.type == BoundaryCondition<2>::Type::displacement || c.type == BoundaryCondition<2>::Type::slip;
}

/// sum_s phi_s d_{node s} on row k of q: u^h at point k.
Vec2 row_value(const GalerkinQuadrature<2>& q, Index k, const Eigen::VectorXd& d) {
  Vec2 u = Vec2::Zero();
  for (Index s = q.row_begin(k); s < q.row_end(k); ++s) u += q.phi[s] * d.segment<2>(2 * q.nodes[s]);
  return u;
}

/// w f and its moment about the arm.
Resultant weighted(double w, const Vec2& f, const Vec2& arm) { return {w * f, w * cross(arm, f)}; }

}  // namespace

Resultant Reactions::balance() const {
  Resultant sum = applied;
  for (const PartReaction& p : parts) sum += p.reaction;
  if (inertia) {
    sum.force -= inertia->force;
    sum.moment -= inertia->moment;
  }
  return sum;
}

namespace {

double force_scale(const Reactions& r) {
  double scale = std::max(r.applied.force.norm(), r.applied_magnitude);
  for (const PartReaction& p : r.parts) scale = std::max({scale, p.reaction.force.norm(), p.magnitude});
  if (r.inertia) scale = std::max(scale, r.inertia->force.norm());
  return scale;
}

}  // namespace

double Reactions::force_imbalance() const {
  const double scale = force_scale(*this);
  return scale > 0.0 ? balance().force.norm() / scale : 0.0;
}

double Reactions::moment_imbalance() const {
  const double scale = arm * force_scale(*this);
  return scale > 0.0 ? std::abs(balance().moment) / scale : 0.0;
}

std::vector<std::string> essential_parts(const SolidProblem<2>& problem) {
  std::vector<std::string> names;
  for (const BoundaryCondition<2>& c : problem.conditions)
    if (is_essential(c)) names.push_back(c.name);
  return names;
}

Reactions reactions(const TotalLagrangian<2>& model, const Eigen::VectorXd& d, const LoadState& load) {
  const SolidProblem<2>& problem = model.problem();
  const BoundaryQuadrature<2>& bq = model.boundary();
  const GalerkinQuadrature<2>& at = model.at_boundary();
  Reactions r;
  r.current_arm = !is_small_strain(problem.material);
  for (const Material& m : problem.region_materials) r.current_arm = r.current_arm || !is_small_strain(m);
  const auto boundary_arm = [&](Index p) -> Vec2 {
    return r.current_arm ? Vec2(bq.points[p] + row_value(at, p, d)) : bq.points[p];
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
    const TotalLagrangian<2>::NitscheValues v = model.nitsche_values(b, d, load);
    const std::size_t c = static_cast<std::size_t>(v.condition - problem.conditions.data());
    const Vec2 flux = nitsche_flux(v.traction, v.gap, v.penalty);
    r.parts[part_of[c]].reaction += weighted(bq.weights[v.point], flux, boundary_arm(v.point));
    r.parts[part_of[c]].magnitude += std::abs(bq.weights[v.point]) * flux.norm();
  }

  // Applied: tractions and pressures at the boundary points, the body force at the domain's.
  for (Index p = 0; p < bq.size(); ++p) {
    const Vec2 t = model.boundary_load(p, d, load);
    if (t != Vec2::Zero()) {
      r.applied += weighted(bq.weights[p], t, boundary_arm(p));
      r.applied_magnitude += std::abs(bq.weights[p]) * t.norm();
    }
  }
  if (problem.body_force) {
    const GalerkinQuadrature<2>& q = model.quadrature();
    for (Index k = 0; k < q.size(); ++k) {
      const Vec2 arm = r.current_arm ? Vec2(q.points[k] + row_value(q, k, d)) : q.points[k];
      const Vec2 b = load.factor * problem.body_force(q.points[k], load.time);
      r.applied += weighted(q.weights[k], b, arm);
      r.applied_magnitude += std::abs(q.weights[k]) * b.norm();
    }
  }
  return r;
}

Resultant nodal_resultant(const Eigen::VectorXd& f, std::span<const Vec2> nodes, const Eigen::VectorXd& d,
                          bool current_arm) {
  Resultant sum;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Index at = 2 * static_cast<Eigen::Index>(i);
    const Vec2 fi = f.segment<2>(at);
    const Vec2 arm = current_arm ? Vec2(nodes[i] + d.segment<2>(at)) : nodes[i];
    sum += {fi, cross(arm, fi)};
  }
  return sum;
}

Reactions elastic_reactions(const Domain& domain, const ElasticitySettings& settings,
                            const ElasticityResult& result) {
  ElasticityProblem problem = settings.problem;
  problem.spacing = settings.nodes.spacing;  // as solve_elasticity takes it
  const TotalLagrangian<2> model(solid_problem(problem), domain, result.node_count(), result.quadrature,
                                 result.test(), result.boundary, result.at_boundary);
  return reactions(model, result.coefficients, {});
}

}  // namespace mfree

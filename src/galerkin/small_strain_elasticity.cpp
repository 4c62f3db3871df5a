#include "mfree/galerkin/small_strain_elasticity.hpp"

#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"

namespace mfree {

Eigen::Vector3d strain_at(const GalerkinQuadrature& q, Index k, const Eigen::VectorXd& d) {
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

Vec2 displacement_at(const GalerkinQuadrature& q, Index k, const Eigen::VectorXd& d) {
  Vec2 u = Vec2::Zero();
  for (Index s = q.row_begin(k); s < q.row_end(k); ++s) u += q.phi[s] * d.segment<2>(2 * q.nodes[s]);
  return u;
}

namespace {

/// Global strain-displacement matrix: rows 3K..3K+2 (Voigt strain at point K), columns 2I, 2I+1.
SparseMatrix strain_matrix(const GalerkinQuadrature& q, const std::vector<Vec2>& grad, Index nodes) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(4 * q.nodes.size());
  for (Index k = 0; k < q.size(); ++k)
    for (Index s = q.row_begin(k); s < q.row_end(k); ++s) {
      const Index i = q.nodes[s];
      const Vec2& g = grad[s];
      t.emplace_back(3 * k, 2 * i, g.x());
      t.emplace_back(3 * k + 1, 2 * i + 1, g.y());
      t.emplace_back(3 * k + 2, 2 * i, g.y());
      t.emplace_back(3 * k + 2, 2 * i + 1, g.x());
    }
  SparseMatrix b(3 * q.size(), 2 * nodes);
  b.setFromTriplets(t.begin(), t.end());
  return b;
}

/// Traction operator at a boundary point: t = N_n sigma with N_n = [[nx, 0, ny], [0, ny, nx]].
Eigen::Matrix<double, 2, 3> normal_operator(const Vec2& n) {
  Eigen::Matrix<double, 2, 3> m;
  m << n.x(), 0.0, n.y(), 0.0, n.y(), n.x();
  return m;
}

}  // namespace

ElasticitySystem assemble_elasticity(const ElasticityProblem& problem, const Domain& domain, Index nodes,
                                     const GalerkinQuadrature& q, const std::vector<Vec2>* test_gradients,
                                     const BoundaryQuadrature& bq, const GalerkinQuadrature& at_boundary) {
  problem.material.validate();
  if (!(problem.nitsche_beta > 0.0))
    throw InputError(fmt::format("Nitsche penalty beta must be positive, got {}", problem.nitsche_beta));
  const Eigen::Matrix3d d = problem.material.voigt_tangent();
  ElasticitySystem sys;
  sys.symmetric = test_gradients == nullptr;

  // Domain term: K = B_test^T (W D) B_trial, W = diag(w_K).
  const SparseMatrix b = strain_matrix(q, q.grad, nodes);
  SparseMatrix wdb(3 * q.size(), 3 * q.size());
  {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(9 * q.size());
    for (Index k = 0; k < q.size(); ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          if (d(r, c) != 0.0) t.emplace_back(3 * k + r, 3 * k + c, q.weights[k] * d(r, c));
    wdb.setFromTriplets(t.begin(), t.end());
  }
  const SparseMatrix db = wdb * b;
  if (test_gradients) {
    const SparseMatrix bt = strain_matrix(q, *test_gradients, nodes);
    sys.stiffness = SparseMatrix(bt.transpose()) * db;
  } else {
    sys.stiffness = SparseMatrix(b.transpose()) * db;
  }

  // Body force.
  sys.load = Eigen::VectorXd::Zero(2 * nodes);
  if (problem.body_force)
    for (Index k = 0; k < q.size(); ++k) {
      const Vec2 f = q.weights[k] * problem.body_force(q.points[k]);
      for (Index s = q.row_begin(k); s < q.row_end(k); ++s) sys.load.segment<2>(2 * q.nodes[s]) += q.phi[s] * f;
    }

  // Boundary terms, segment by segment.
  const auto& segments = domain.boundary();
  std::vector<const BoundaryCondition*> condition(segments.size(), nullptr);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const Vec2 mid = 0.5 * (segments[s].a + segments[s].b);
    for (const BoundaryCondition& c : problem.conditions)
      if (c.region.contains(mid)) {
        condition[s] = &c;
        break;
      }
  }
  const double penalty = problem.nitsche_beta * problem.material.youngs_modulus / problem.spacing;
  std::vector<Eigen::Triplet<double>> t;
  for (Index p = 0; p < bq.size(); ++p) {
    const BoundaryCondition* c = condition[bq.segment[p]];
    if (!c) continue;
    const Vec2 x = bq.points[p];
    const double w = bq.weights[p];
    const Vec2 value = c->value(x);
    const Index begin = at_boundary.row_begin(p), end = at_boundary.row_end(p);
    if (c->type == BoundaryCondition::Type::traction) {
      for (Index s = begin; s < end; ++s) sys.load.segment<2>(2 * at_boundary.nodes[s]) += w * at_boundary.phi[s] * value;
      continue;
    }
    // Nitsche: T_I = N_n D B_I (2 x 2) maps d_I to the traction sigma(phi_I d_I) n.
    const Eigen::Matrix<double, 2, 3> nd = normal_operator(bq.normals[p]) * d;
    const Index m = end - begin;
    std::vector<Eigen::Matrix2d> traction(m);
    for (Index a = 0; a < m; ++a) {
      const Vec2& g = at_boundary.grad[begin + a];
      Eigen::Matrix<double, 3, 2> bi;
      bi << g.x(), 0.0, 0.0, g.y(), g.y(), g.x();
      traction[a] = nd * bi;
    }
    for (Index a = 0; a < m; ++a) {
      const Index i = at_boundary.nodes[begin + a];
      const double phi_i = at_boundary.phi[begin + a];
      // l(v): - (sigma(v) n) . ubar + penalty v . ubar
      sys.load.segment<2>(2 * i) += w * (-traction[a].transpose() * value + penalty * phi_i * value);
      for (Index bb = 0; bb < m; ++bb) {
        const Index j = at_boundary.nodes[begin + bb];
        const double phi_j = at_boundary.phi[begin + bb];
        const Eigen::Matrix2d kij = w * (-phi_i * traction[bb] - traction[a].transpose() * phi_j +
                                         penalty * phi_i * phi_j * Eigen::Matrix2d::Identity());
        for (int r = 0; r < 2; ++r)
          for (int cc = 0; cc < 2; ++cc) t.emplace_back(2 * i + r, 2 * j + cc, kij(r, cc));
      }
    }
  }
  if (!t.empty()) {
    SparseMatrix kb(2 * nodes, 2 * nodes);
    kb.setFromTriplets(t.begin(), t.end());
    sys.stiffness += kb;
  }
  sys.stiffness.makeCompressed();
  return sys;
}

}  // namespace mfree

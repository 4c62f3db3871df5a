#include "mfree/galerkin/small_strain_elasticity.hpp"

#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/linalg/node_pattern.hpp"

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

/// Adds the domain term of a(u, v), block by block:
///
///   K_IJ += w_K Bt_I^T D B_J,   B_J = [[gx, 0], [0, gy], [gy, gx]] (trial gradient of J at x_K),
///
/// Bt_I likewise with the test gradient of I, over every row K holding I and J. Node J's two
/// columns are written only by the thread that owns J, with the rows holding J in increasing
/// order: no two threads touch one value, and the sums are the same on any thread count.
/// With symmetric = true (test gradients = trial gradients) only the blocks I >= J are summed
/// (rows are sorted: from J's own slot on), and the others copied, K_IJ = K_JI^T: half the
/// work, and K symmetric to the last bit.
void add_domain_stiffness(const GalerkinQuadrature& q, const std::vector<Vec2>& test, bool symmetric,
                          const Eigen::Matrix3d& d, const RowIncidence& rows, const NodePattern& pattern,
                          double* values) {
  const Index n = pattern.size();
  parallel_ranges(n, [&](int, Index begin, Index end) {
    std::vector<Index> at(n);  // at[I] = p with P_J[p] = I, for the current J
    for (Index j = begin; j < end; ++j) {
      const std::span<const Index> p = pattern.neighbours(j);
      for (std::size_t a = 0; a < p.size(); ++a) at[p[a]] = static_cast<Index>(a);
      // Column 2J holds (2I, 2I + 1) at 2p, 2p + 1 for I = P_J[p]; column 2J + 1 follows it.
      double* col0 = values + 4 * pattern.offsets[j];
      double* col1 = col0 + 2 * p.size();
      const std::span<const Index> ks = rows.rows_of(j), slots = rows.slots_of(j);
      for (std::size_t e = 0; e < ks.size(); ++e) {
        const Index k = ks[e];
        const Vec2& g = q.grad[slots[e]];
        Eigen::Matrix<double, 3, 2> bj;
        bj << g.x(), 0.0, 0.0, g.y(), g.y(), g.x();
        const Eigen::Matrix<double, 3, 2> db = q.weights[k] * (d * bj);
        for (Index s = symmetric ? slots[e] : q.row_begin(k); s < q.row_end(k); ++s) {
          const Vec2& t = test[s];
          const std::int64_t a = 2 * std::int64_t{at[q.nodes[s]]};
          // Bt_I^T (w D B_J) with Bt_I^T = [[tx, 0, ty], [0, ty, tx]].
          col0[a] += t.x() * db(0, 0) + t.y() * db(2, 0);
          col0[a + 1] += t.y() * db(1, 0) + t.x() * db(2, 0);
          col1[a] += t.x() * db(0, 1) + t.y() * db(2, 1);
          col1[a + 1] += t.y() * db(1, 1) + t.x() * db(2, 1);
        }
      }
    }
  });
  if (!symmetric) return;
  // Upper blocks I < J of column J from the lower blocks J > I of column I: reads and writes
  // never meet.
  parallel_blocks(n, 1024, [&](Index begin, Index end) {
    for (Index j = begin; j < end; ++j) {
      const std::span<const Index> p = pattern.neighbours(j);
      const std::int64_t size = static_cast<std::int64_t>(p.size());
      double* col0 = values + 4 * pattern.offsets[j];
      double* col1 = col0 + 2 * size;
      std::int64_t a = 0;
      for (; a < size && p[a] < j; ++a) {
        // K_IJ(r, c) = K_JI(c, r), entry (2J + c, 2I + r) in column 2I + r.
        const Index i = p[a];
        const std::int64_t from = block_slot(pattern, 2, j, i, 0, 0);
        const std::int64_t column = 2 * (pattern.offsets[i + 1] - pattern.offsets[i]);
        for (int r = 0; r < 2; ++r) {
          col0[2 * a + r] = values[from + r * column];
          col1[2 * a + r] = values[from + r * column + 1];
        }
      }
      // The diagonal block (p[a] = J, present whenever a row holds J): K_JJ(0, 1) = K_JJ(1, 0).
      if (a < size) col1[2 * a] = col0[2 * a + 1];
    }
  });
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

  // Boundary condition of each boundary segment.
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
  const auto nitsche = [&](Index p) {
    const BoundaryCondition* c = condition[bq.segment[p]];
    return c && c->type == BoundaryCondition::Type::displacement;
  };

  // Sparsity: node pairs sharing a quadrature row, and pairs sharing the row of a boundary
  // point under Nitsche's terms (outside the domain pattern when the quadrature rows are
  // narrower than the supports, as with Gauss cells).
  std::vector<Index> boundary_offsets{0}, boundary_nodes;
  for (Index p = 0; p < bq.size(); ++p)
    if (nitsche(p)) {
      boundary_nodes.insert(boundary_nodes.end(), at_boundary.nodes.begin() + at_boundary.row_begin(p),
                            at_boundary.nodes.begin() + at_boundary.row_end(p));
      boundary_offsets.push_back(static_cast<Index>(boundary_nodes.size()));
    }
  const RowIncidence domain_rows(q.offsets, q.nodes, nodes);
  const RowIncidence boundary_rows(boundary_offsets, boundary_nodes, nodes);
  const RowIncidence* const sets[] = {&domain_rows, &boundary_rows};
  const NodePattern pattern = node_pattern(sets);
  sys.stiffness = block_matrix(pattern, 2);
  double* values = sys.stiffness.valuePtr();
  add_domain_stiffness(q, test_gradients ? *test_gradients : q.grad, sys.symmetric, d, domain_rows, pattern, values);

  // Body force.
  sys.load = Eigen::VectorXd::Zero(2 * nodes);
  if (problem.body_force)
    for (Index k = 0; k < q.size(); ++k) {
      const Vec2 f = q.weights[k] * problem.body_force(q.points[k]);
      for (Index s = q.row_begin(k); s < q.row_end(k); ++s) sys.load.segment<2>(2 * q.nodes[s]) += q.phi[s] * f;
    }

  const double penalty = problem.nitsche_beta * problem.material.youngs_modulus / problem.spacing;
  for (Index p = 0; p < bq.size(); ++p) {
    const BoundaryCondition* c = condition[bq.segment[p]];
    if (!c) continue;
    const Vec2 x = bq.points[p];
    const double w = bq.weights[p];
    const Vec2 value = c->value(x, bq.normals[p]);
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
          for (int cc = 0; cc < 2; ++cc) values[block_slot(pattern, 2, i, j, r, cc)] += kij(r, cc);
      }
    }
  }
  return sys;
}

}  // namespace mfree

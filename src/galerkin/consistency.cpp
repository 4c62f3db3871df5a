#include "mfree/galerkin/consistency.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/linalg/node_pattern.hpp"
#include "mfree/linalg/sparse_solver.hpp"

namespace mfree {

std::string_view to_string(Consistency c) {
  switch (c) {
    case Consistency::none: return "none";
    case Consistency::vci: return "vci";
    case Consistency::symmetric: return "symmetric";
  }
  return "?";
}

std::vector<Vec2> boundary_sums(const GalerkinQuadrature& at_boundary, const std::vector<Vec2>& normals,
                                const std::vector<double>& weights, Index nodes) {
  std::vector<Vec2> b(nodes, Vec2::Zero());
  for (Index p = 0; p < at_boundary.size(); ++p)
    for (Index s = at_boundary.row_begin(p); s < at_boundary.row_end(p); ++s)
      b[at_boundary.nodes[s]] += weights[p] * at_boundary.phi[s] * normals[p];
  return b;
}

namespace {
/// sum_K w_K g_I(x_K) for every node.
std::vector<Vec2> weighted_gradient_sums(const GalerkinQuadrature& q, const std::vector<Vec2>& g,
                                         std::size_t nodes) {
  std::vector<Vec2> s(nodes, Vec2::Zero());
  for (Index k = 0; k < q.size(); ++k)
    for (Index i = q.row_begin(k); i < q.row_end(k); ++i) s[q.nodes[i]] += q.weights[k] * g[i];
  return s;
}
}  // namespace

double consistency_defect(const GalerkinQuadrature& q, const std::vector<Vec2>& gradients,
                          const std::vector<Vec2>& b) {
  const std::vector<Vec2> s = weighted_gradient_sums(q, gradients, b.size());
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    worst = std::max(worst, (b[i] - s[i]).norm());
    scale = std::max(scale, b[i].norm());
  }
  return scale > 0.0 ? worst / scale : worst;
}

std::vector<Vec2> vci_test_gradients(const GalerkinQuadrature& q, const std::vector<Vec2>& b) {
  const std::vector<Vec2> s = weighted_gradient_sums(q, q.grad, b.size());
  std::vector<double> support(b.size(), 0.0);
  for (Index k = 0; k < q.size(); ++k)
    for (Index i = q.row_begin(k); i < q.row_end(k); ++i) support[q.nodes[i]] += q.weights[k];
  std::vector<Vec2> eta(b.size(), Vec2::Zero());
  for (std::size_t i = 0; i < b.size(); ++i)
    if (support[i] > 0.0) eta[i] = (b[i] - s[i]) / support[i];
  std::vector<Vec2> test = q.grad;
  for (std::size_t s2 = 0; s2 < test.size(); ++s2) test[s2] += eta[q.nodes[s2]];
  return test;
}

SymmetricCorrection make_consistent_symmetric(GalerkinQuadrature& q, const std::vector<Vec2>& nodes,
                                              const std::vector<Vec2>& b) {
  const Index nk = q.size();
  const Index n = static_cast<Index>(nodes.size());
  // Per row: centre, scale and the inverse Gram matrix (P^T P)^-1 of P = [1, (x_I - x_K) / s].
  std::vector<Eigen::Matrix3d> gram_inv(nk);
  std::vector<double> scale(nk);
  const auto basis = [&](Index k, Index slot) {
    const Vec2 z = (nodes[q.nodes[slot]] - q.points[k]) / scale[k];
    return Eigen::Vector3d(1.0, z.x(), z.y());
  };
  parallel_blocks(nk, 1024, [&](Index b0, Index e0) {
    for (Index k = b0; k < e0; ++k) {
      double s = 0.0;
      for (Index i = q.row_begin(k); i < q.row_end(k); ++i) s = std::max(s, (nodes[q.nodes[i]] - q.points[k]).norm());
      scale[k] = s > 0.0 ? s : 1.0;
      Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
      for (Index i = q.row_begin(k); i < q.row_end(k); ++i) {
        const Eigen::Vector3d p = basis(k, i);
        g += p * p.transpose();
      }
      bool invertible = false;
      double det = 0.0;
      g.computeInverseAndDetWithCheck(gram_inv[k], det, invertible, 1e-14);
      if (!invertible)
        throw NumericalError(fmt::format(
            "consistency correction: the {} nodes of quadrature point {} at ({:.6g}, {:.6g}) lie on "
            "one line; the symmetric correction needs them spread in 2D (use larger supports)",
            q.row_end(k) - q.row_begin(k), k, q.points[k].x(), q.points[k].y()));
    }
  });

  // A = diag(sum_K w_K^2 [I in row K]) - V U^T with U_{I,3K+j} = w_K P_K(I, j) and
  // V = U blockdiag(M_K): the rank-3 projector of each row, assembled by one sparse product.
  // The null space span{1, x, y} is removed by pinning lambda at three nodes spanning a
  // large triangle: the pinned equations then hold too, since r and A lambda are both
  // orthogonal to that null space.
  Index p0 = 0, p1 = 0, p2 = 0;
  for (Index i = 0; i < n; ++i)
    if ((nodes[i] - nodes[p0]).squaredNorm() > (nodes[p1] - nodes[p0]).squaredNorm()) p1 = i;
  double best = 0.0;
  for (Index i = 0; i < n; ++i) {
    const Vec2 e1 = nodes[p1] - nodes[p0], e2 = nodes[i] - nodes[p0];
    const double area = std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    if (area > best) best = area, p2 = i;
  }
  const auto pinned = [&](Index i) { return i == p0 || i == p1 || i == p2; };

  // A_IJ = sum over rows K holding I and J of w_K^2 (d_IJ - P_K(I)^T M_K P_K(J)), on the
  // node-to-node pattern of the rows, column by column: each thread owns whole columns.
  const RowIncidence incidence(q.offsets, q.nodes, n);
  const RowIncidence* sets[] = {&incidence};
  const NodePattern pattern = node_pattern(sets);
  SparseMatrix a = block_matrix(pattern, 1);
  double* values = a.valuePtr();
  parallel_blocks(n, 256, [&](Index begin, Index end) {
    for (Index j = begin; j < end; ++j) {
      const std::span<const Index> rows = incidence.rows_of(j), slots = incidence.slots_of(j);
      for (std::size_t m = 0; m < rows.size(); ++m) {
        const Index k = rows[m];
        const double w2 = q.weights[k] * q.weights[k];
        const Eigen::Vector3d mj = gram_inv[k] * basis(k, slots[m]);
        for (Index s2 = q.row_begin(k); s2 < q.row_end(k); ++s2) {
          const Index i = q.nodes[s2];
          values[pattern.offsets[j] + pattern.position(i, j)] += w2 * ((i == j) - basis(k, s2).dot(mj));
        }
      }
      for (std::int64_t e = pattern.offsets[j]; e < pattern.offsets[j + 1]; ++e) {
        const Index i = pattern.nodes[e];
        if (pinned(i) || pinned(j)) values[e] = i == j ? 1.0 : 0.0;
      }
    }
  });
  SparseSolver solver(SolverKind::cholmod);
  solver.analyze(a);
  solver.factorize(a);

  const std::vector<Vec2> s = weighted_gradient_sums(q, q.grad, nodes.size());
  SymmetricCorrection report;
  for (int c = 0; c < 2; ++c) {
    Eigen::VectorXd r(n);
    for (Index i = 0; i < n; ++i) r[i] = b[i][c] - s[i][c];
    for (Index i : {p0, p1, p2}) r[i] = 0.0;
    const Eigen::VectorXd lambda = solver.solve(r);
    const double rn = r.norm();
    if (rn > 0.0) report.residual = std::max(report.residual, (a * lambda - r).norm() / rn);
    // delta_K = w_K (I - Q_K) lambda_K on every row.
    parallel_blocks(nk, 1024, [&](Index b0, Index e0) {
      for (Index k = b0; k < e0; ++k) {
        Eigen::Vector3d pt = Eigen::Vector3d::Zero();
        for (Index i = q.row_begin(k); i < q.row_end(k); ++i) pt += basis(k, i) * lambda[q.nodes[i]];
        const Eigen::Vector3d cc = gram_inv[k] * pt;
        for (Index i = q.row_begin(k); i < q.row_end(k); ++i)
          q.grad[i][c] += q.weights[k] * (lambda[q.nodes[i]] - basis(k, i).dot(cc));
      }
    });
  }
  return report;
}

}  // namespace mfree

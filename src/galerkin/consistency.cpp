#include "mfree/galerkin/consistency.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>
#include <cmath>
#include <numeric>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/linalg/node_pattern.hpp"

namespace mfree {

const NameTable<Consistency>& consistency_names() {
  static const NameTable<Consistency> table{{"symmetric", Consistency::symmetric}, {"vci", Consistency::vci}, {"none", Consistency::none}};
  return table;
}

std::string_view to_string(Consistency c) { return consistency_names().name(c); }

template <int dim>
ConsistencyConditions<dim>::ConsistencyConditions(const GalerkinQuadrature<dim>& q,
                                                  const std::vector<Point<dim>>& nodes,
                                                  const GalerkinQuadrature<dim>& at_boundary,
                                                  const BoundaryQuadrature<dim>& bq, RKOrder order)
    : q_(q),
      nodes_(nodes),
      monomials_(order == RKOrder::linear ? 1 : max_monomials),
      incidence_(q.offsets, q.nodes, static_cast<Index>(nodes.size())),
      scale_(nodes.size(), 1.0),
      target_(nodes.size(), Moments::Zero()) {
  const Index n = static_cast<Index>(nodes.size());
  const RowIncidence on_boundary(at_boundary.offsets, at_boundary.nodes, n);
  parallel_blocks(n, 256, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) {
      const std::span<const Index> rows = incidence_.rows_of(i), slots = incidence_.slots_of(i);
      double s = 0.0;
      for (Index k : rows) s = std::max(s, (q.centroids[k] - nodes[i]).norm());
      if (s > 0.0) scale_[i] = s;
      // Boundary sum of phi_I m n, minus the volume part sum_K w_K phi_I(x_K) grad m(x_K) of
      // the divergence theorem.
      Moments t = Moments::Zero();
      const std::span<const Index> bp = on_boundary.rows_of(i), bs = on_boundary.slots_of(i);
      for (std::size_t a = 0; a < bp.size(); ++a) {
        const Index p = bp[a];
        const Monomials m = monomial(i, bq.points[p]);
        t += (bq.weights[p] * at_boundary.phi[bs[a]]) * m * bq.normals[p].transpose();
      }
      if (monomials_ > 1)
        for (std::size_t a = 0; a < rows.size(); ++a)
          t -= q.weights[rows[a]] * q.phi[slots[a]] * monomial_gradient(i, q.points[rows[a]]);
      t.bottomRows(max_monomials - monomials_).setZero();
      target_[i] = t;
    }
  });
}

template <int dim>
typename ConsistencyConditions<dim>::Monomials ConsistencyConditions<dim>::monomial(
    Index i, const Point<dim>& p) const {
  const Point<dim> z = (p - nodes_[i]) / scale_[i];
  Monomials m;
  m[0] = 1.0;
  int l = 1;
  for (int a = 0; a < dim; ++a) m[l++] = z[a];
  for (int a = 0; a < dim; ++a)
    for (int b = a; b < dim; ++b) m[l++] = z[a] * z[b];
  return m;
}

template <int dim>
typename ConsistencyConditions<dim>::Moments ConsistencyConditions<dim>::monomial_gradient(
    Index i, const Point<dim>& p) const {
  const Point<dim> z = (p - nodes_[i]) / scale_[i];
  Moments g = Moments::Zero();
  int l = 1;
  for (int a = 0; a < dim; ++a) g(l++, a) = 1.0;
  for (int a = 0; a < dim; ++a)
    for (int b = a; b < dim; ++b, ++l) {
      // d(z_a z_b) / dz_c: z_b for c = a, z_a for c = b (2 z_a when a = b).
      g(l, a) += z[b];
      g(l, b) += z[a];
    }
  return g / scale_[i];
}

template <int dim>
typename ConsistencyConditions<dim>::Moments ConsistencyConditions<dim>::residual(
    Index i, const std::vector<Point<dim>>& g) const {
  Moments r = target_[i];
  const std::span<const Index> rows = incidence_.rows_of(i), slots = incidence_.slots_of(i);
  for (std::size_t a = 0; a < rows.size(); ++a) {
    const Index k = rows[a];
    r -= q_.weights[k] * monomial(i, q_.centroids[k]) * g[slots[a]].transpose();
  }
  r.bottomRows(max_monomials - monomials_).setZero();
  return r;
}

template <int dim>
std::vector<Point<dim>> ConsistencyConditions<dim>::linear_residuals(
    const std::vector<Point<dim>>& gradients) const {
  const Index n = static_cast<Index>(nodes_.size());
  std::vector<Point<dim>> r(n);
  parallel_blocks(n, 256, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) r[i] = residual(i, gradients).row(0).transpose();
  });
  return r;
}

template <int dim>
double ConsistencyConditions<dim>::defect(const std::vector<Point<dim>>& gradients) const {
  const Index n = static_cast<Index>(nodes_.size());
  std::vector<double> worst(n, 0.0);
  parallel_blocks(n, 256, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) worst[i] = residual(i, gradients).rowwise().norm().maxCoeff();
  });
  double scale = 0.0;
  for (const Moments& t : target_) scale = std::max(scale, t.row(0).norm());
  const double w = n > 0 ? *std::max_element(worst.begin(), worst.end()) : 0.0;
  return scale > 0.0 ? w / scale : w;
}

template <int dim>
std::vector<Point<dim>> ConsistencyConditions<dim>::vci_test_gradients() const {
  const Index n = static_cast<Index>(nodes_.size());
  std::vector<Point<dim>> test = q_.grad;
  parallel_blocks(n, 256, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) {
      const std::span<const Index> rows = incidence_.rows_of(i), slots = incidence_.slots_of(i);
      if (rows.empty()) continue;
      // M_I xi_I = R_I on the order's monomials; for linear RK the unused rows of M_I are
      // (sum_K w_K) I, and those of R_I zero, so that xi_I is zero there.
      using MomentMatrix = Eigen::Matrix<double, max_monomials, max_monomials>;
      MomentMatrix m = MomentMatrix::Zero();
      for (Index k : rows) {
        const Monomials p = monomial(i, q_.centroids[k]);
        m += q_.weights[k] * p * p.transpose();
      }
      if (monomials_ == 1) m = m(0, 0) * MomentMatrix::Identity();
      const Eigen::LDLT<MomentMatrix> ldlt(m);
      if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-12))
        throw NumericalError(
            fmt::format("VCI: the moment matrix of node {} at ({:.6g}) is singular ({} quadrature points in "
                        "its support); use larger supports",
                        i, fmt::join(nodes_[i].begin(), nodes_[i].end(), ", "), rows.size()));
      const Moments xi = ldlt.solve(residual(i, q_.grad));
      for (std::size_t a = 0; a < rows.size(); ++a)
        test[slots[a]] += xi.transpose() * monomial(i, q_.centroids[rows[a]]);
    }
  });
  return test;
}

template class ConsistencyConditions<2>;
template class ConsistencyConditions<3>;

namespace {

/// Three nodes spanning a large triangle in each set of nodes that the rows join (union-find
/// over the rows): the pins of the symmetric correction's null space.
std::vector<Index> pinned_nodes(const GalerkinQuadrature<2>& q, const std::vector<Vec2>& nodes) {
  const Index n = static_cast<Index>(nodes.size());
  std::vector<Index> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](Index i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (Index k = 0; k < q.size(); ++k)
    for (Index s = q.row_begin(k) + 1; s < q.row_end(k); ++s) {
      const Index a = root(q.nodes[q.row_begin(k)]), b = root(q.nodes[s]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<std::vector<Index>> sets(n);
  for (Index i = 0; i < n; ++i) sets[root(i)].push_back(i);
  std::vector<Index> pins;
  for (const std::vector<Index>& set : sets) {
    if (set.empty()) continue;
    Index p0 = set.front(), p1 = p0, p2 = p0;
    for (Index i : set)
      if ((nodes[i] - nodes[p0]).squaredNorm() > (nodes[p1] - nodes[p0]).squaredNorm()) p1 = i;
    double best = 0.0;
    for (Index i : set) {
      const Vec2 e1 = nodes[p1] - nodes[p0], e2 = nodes[i] - nodes[p0];
      const double area = std::abs(e1.x() * e2.y() - e1.y() * e2.x());
      if (area > best) best = area, p2 = i;
    }
    pins.insert(pins.end(), {p0, p1, p2});
  }
  return pins;
}

}  // namespace

SymmetricCorrection make_consistent_symmetric(GalerkinQuadrature<2>& q, const std::vector<Vec2>& nodes,
                                              const std::vector<Vec2>& residuals,
                                              const SolverSettings& settings) {
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
  // The null space is span{1, x, y} on each set of nodes the rows join (the whole cloud, or
  // each part of a domain that interfaces cut through): it is removed by pinning lambda at
  // three nodes of each set spanning a large triangle; the pinned equations then hold too,
  // since r and A lambda are both orthogonal to that null space.
  const std::vector<Index> pins = pinned_nodes(q, nodes);

  // A_IJ = sum over rows K holding I and J of w_K^2 (d_IJ - P_K(I)^T M_K P_K(J)), on the
  // node-to-node pattern of the rows, column by column: each thread owns whole columns and
  // finds entry (I, J) through a dense map of P_J. Only I >= J is summed (a row's nodes are
  // sorted: from J's own slot on); the upper triangle is copied from the lower, so that A is
  // symmetric to the last bit.
  const RowIncidence incidence(q.offsets, q.nodes, n);
  const RowIncidence* sets[] = {&incidence};
  const NodePattern pattern = node_pattern(sets);
  SparseMatrix a = block_matrix(pattern, 1);
  double* values = a.valuePtr();
  parallel_ranges(n, [&](int, Index begin, Index end) {
    std::vector<Index> at(n);  // at[I] = p with P_J[p] = I, for the current J
    for (Index j = begin; j < end; ++j) {
      const std::span<const Index> p = pattern.neighbours(j);
      for (std::size_t e = 0; e < p.size(); ++e) at[p[e]] = static_cast<Index>(e);
      double* column = values + pattern.offsets[j];
      const std::span<const Index> rows = incidence.rows_of(j), slots = incidence.slots_of(j);
      for (std::size_t m = 0; m < rows.size(); ++m) {
        const Index k = rows[m];
        const double w2 = q.weights[k] * q.weights[k];
        const Eigen::Vector3d mj = gram_inv[k] * basis(k, slots[m]);
        for (Index s2 = slots[m]; s2 < q.row_end(k); ++s2) {
          const Index i = q.nodes[s2];
          column[at[i]] += w2 * ((i == j) - basis(k, s2).dot(mj));
        }
      }
    }
  });
  parallel_blocks(n, 1024, [&](Index begin, Index end) {
    for (Index j = begin; j < end; ++j) {
      for (std::int64_t e = pattern.offsets[j]; e < pattern.offsets[j + 1] && pattern.nodes[e] < j; ++e) {
        const Index i = pattern.nodes[e];
        values[e] = values[pattern.offsets[i] + pattern.position(j, i)];
      }
    }
  });
  // The pinned equations, after the copy: their rows and columns of the identity.
  for (Index pin : pins)
    for (std::int64_t e = pattern.offsets[pin]; e < pattern.offsets[pin + 1]; ++e) {
      const Index i = pattern.nodes[e];
      values[e] = i == pin ? 1.0 : 0.0;
      values[pattern.offsets[i] + pattern.position(pin, i)] = i == pin ? 1.0 : 0.0;
    }
  const std::unique_ptr<LinearSolver> solver =
      make_linear_solver(settings, {"consistency node", true, 1, nodes}, n);
  solver->analyze(a);
  solver->factorize(a);

  SymmetricCorrection report;
  for (int c = 0; c < 2; ++c) {
    Eigen::VectorXd r(n);
    for (Index i = 0; i < n; ++i) r[i] = residuals[i][c];
    for (Index i : pins) r[i] = 0.0;
    const Eigen::VectorXd lambda = solver->solve(r);
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
  report.solver = mfree::report(*solver);
  return report;
}

}  // namespace mfree

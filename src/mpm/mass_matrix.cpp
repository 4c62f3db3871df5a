#include "mfree/mpm/mass_matrix.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"

namespace mfree {

const NameTable<GridMapping>& grid_mapping_names() {
  static const NameTable<GridMapping> table{{"lumped", GridMapping::lumped}, {"pseudo_inverse", GridMapping::pseudo_inverse}};
  return table;
}

GridMassMatrix::GridMassMatrix(const Grid& grid, int radius, double filter)
    : grid_(grid),
      nodes_(grid.size()),
      nx_(grid.nx()),
      radius_(radius),
      width_(2 * radius + 1),
      filter_(filter) {
  if (!(filter >= 0.0))
    throw std::invalid_argument(fmt::format("MPM mass matrix: filter {} is not >= 0", filter));
}

template <class F>
void GridMassMatrix::for_each_in_stencil(Index i, F&& f) const {
  const Index ny = nodes_ / nx_, ix = i % nx_, iy = i / nx_;
  for (Index dy = std::max<Index>(-radius_, -iy); dy <= std::min<Index>(radius_, ny - 1 - iy); ++dy)
    for (Index dx = std::max<Index>(-radius_, -ix); dx <= std::min<Index>(radius_, nx_ - 1 - ix); ++dx)
      f(i + dx + nx_ * dy, static_cast<std::size_t>((dx + radius_) + width_ * (dy + radius_)));
}

int GridMassMatrix::offset(Index i, Index j) const {
  const Index dx = j % nx_ - i % nx_, dy = j / nx_ - i / nx_;
  if (std::abs(dx) > radius_ || std::abs(dy) > radius_) return -1;
  return static_cast<int>((dx + radius_) + width_ * (dy + radius_));
}

void GridMassMatrix::assemble(const WeightTable& weights, const std::vector<double>& mass,
                              const std::vector<double>& volume) {
  scatter<double>(weights, nodes_, cover_, partial_cover_, [&](Index q) {
    const double V = volume[q];
    return [V](double S, const Vec2&) { return S * V; };
  });
  for (Index i = 0; i < nodes_; ++i)
    cover_[i] /= grid_.x_axis().integral(static_cast<int>(i % nx_)) * grid_.y_axis().integral(static_cast<int>(i / nx_));
  const auto row = static_cast<std::size_t>(width_) * width_;
  partial_.resize(static_cast<std::size_t>(thread_count()));
  parallel_ranges(weights.points(), [&](int t, Index begin, Index end) {
    partial_[t].assign(static_cast<std::size_t>(nodes_) * row, 0.0);
    double* m = partial_[t].data();
    // A point's distinct nodes and their weights (the CPDIs list a node once per element
    // node that reaches it).
    std::array<Index, 32> node{};
    std::array<double, 32> S{};
    for (Index q = begin; q < end; ++q) {
      int n = 0;
      weights.for_each(q, [&](Index i, double s, const Vec2&) {
        if (s == 0.0) return;
        int k = 0;
        while (k < n && node[k] != i) ++k;
        if (k == n) {
          node[n] = i;
          S[n++] = 0.0;
        }
        S[k] += s;
      });
      for (int a = 0; a < n; ++a) {
        const double ms = mass[q] * S[a];
        double* r = m + static_cast<std::size_t>(node[a]) * row;
        for (int b = 0; b < n; ++b) {
          const int o = offset(node[a], node[b]);
          if (o < 0)
            throw NumericalError(fmt::format(
                "MPM mass matrix: point {} reaches nodes {} and {}, more than {} nodes apart along an axis (its domain "
                "outgrew the mass matrix's stencil)",
                q, node[a], node[b], radius_));
          r[o] += ms * S[b];
        }
      }
    }
  });
  values_.resize(static_cast<std::size_t>(nodes_) * row);
  parallel_ranges(static_cast<Index>(values_.size()), [&](int, Index begin, Index end) {
    for (Index k = begin; k < end; ++k) {
      double sum = 0.0;
      for (const std::vector<double>& p : partial_) sum += p[k];
      values_[k] = sum;
    }
  });
  // m_i, and the diagonal of M~: M_ii + beta sum_j D_ij^2 / m_j.
  const std::size_t centre = static_cast<std::size_t>(radius_) * (width_ + 1);
  lumped_.resize(static_cast<std::size_t>(nodes_));
  diagonal_.resize(static_cast<std::size_t>(nodes_));
  for (Index i = 0; i < nodes_; ++i) lumped_[i] = row_sum(i);
  for (Index i = 0; i < nodes_; ++i) {
    const double* r = values_.data() + i * row;
    double filtered = 0.0;
    for_each_in_stencil(i, [&](Index j, std::size_t o) {
      const double D = (o == centre ? lumped_[i] : 0.0) - r[o];
      if (lumped_[j] > 0.0) filtered += D * D / lumped_[j];
    });
    diagonal_[i] = r[centre] + filter_ * filtered;
  }
}

double GridMassMatrix::entry(Index i, Index j) const {
  const int o = offset(i, j);
  return o < 0 ? 0.0 : values_[static_cast<std::size_t>(i) * width_ * width_ + o];
}

double GridMassMatrix::row_sum(Index i) const {
  const auto row = static_cast<std::size_t>(width_) * width_;
  double sum = 0.0;
  for (std::size_t k = 0; k < row; ++k) sum += values_[i * row + k];
  return sum;
}

void GridMassMatrix::multiply(const std::vector<Vec2>& x, std::vector<Vec2>& y) const {
  const auto row = static_cast<std::size_t>(width_) * width_;
  y.resize(x.size());
  parallel_blocks(nodes_, 1024, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) {
      const double* r = values_.data() + i * row;
      Vec2 sum = Vec2::Zero();
      for_each_in_stencil(i, [&](Index j, std::size_t o) { sum += r[o] * x[j]; });
      y[i] = sum;
    }
  });
}

void GridMassMatrix::multiply_filtered(const std::vector<Vec2>& x, std::vector<Vec2>& y, std::vector<Vec2>& d,
                                       std::vector<Vec2>& f) const {
  multiply(x, y);
  if (filter_ == 0.0) return;
  // d = L^-1 D x (zero on empty nodes, whose rows of D vanish), then y += beta D d.
  for (std::size_t i = 0; i < y.size(); ++i)
    d[i] = lumped_[i] > 0.0 ? Vec2(x[i] - y[i] / lumped_[i]) : Vec2(Vec2::Zero());
  multiply(d, f);
  for (std::size_t i = 0; i < y.size(); ++i) y[i] += filter_ * (lumped_[i] * d[i] - f[i]);
}

std::vector<Vec2> GridMassMatrix::filtered_product(const std::vector<Vec2>& x) const {
  std::vector<Vec2> y(x.size()), d(x.size()), f(x.size());
  multiply_filtered(x, y, d, f);
  return y;
}

std::vector<Vec2> GridMassMatrix::solve(const std::vector<Vec2>& q, const std::vector<double>& lumped,
                                        const std::vector<unsigned char>& held, double floor) const {
  const auto n = static_cast<std::size_t>(nodes_);
  // known[i]: the components of node i with a value (bit 0: x, bit 1: y); free[i]: those
  // of them the system determines, the others keep their lumped value.
  std::vector<unsigned char> known(n), free(n);
  for (std::size_t i = 0; i < n; ++i) {
    known[i] = std::abs(lumped[i]) > floor ? static_cast<unsigned char>(~held[i] & 3) : 0;
    free[i] = cover_[i] >= 0.2 ? known[i] : 0;
  }
  const auto masked = [&](std::size_t i, const Vec2& v) {
    return Vec2((free[i] & 1) ? v.x() : 0.0, (free[i] & 2) ? v.y() : 0.0);
  };
  // The lumped values of the known components; the system solves for the free ones.
  std::vector<Vec2> lumped_value(n), coupling(n), u(n), r(n), z(n), p(n), Mp(n);
  std::vector<Vec2> d(filter_ > 0.0 ? n : 0), f(filter_ > 0.0 ? n : 0);  // the filter's work vectors
  // The diagonal preconditioner on the free components (rows without one have no diagonal).
  const auto precondition = [&](std::size_t i, const Vec2& v) {
    return free[i] ? masked(i, v.cwiseQuotient(Vec2::Constant(diagonal_[i]) + coupling[i]))
                   : Vec2(Vec2::Zero());
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 v = known[i] ? Vec2(q[i] / lumped[i]) : Vec2(Vec2::Zero());
    lumped_value[i] = Vec2((known[i] & 1) ? v.x() : 0.0, (known[i] & 2) ? v.y() : 0.0);
    // The components that keep their lumped value, as an indicator.
    p[i] = Vec2((known[i] & ~free[i] & 1) ? 1.0 : 0.0, (known[i] & ~free[i] & 2) ? 1.0 : 0.0);
  }
  // A free component's coupling to lumped ones, sum_j M_ij over those j, joins its diagonal,
  // as the lumped component's joins its own (its row sum m_j): the matrix stays symmetric
  // with the row sums m_i, so the mapping conserves momentum and, in the time step, the
  // kinetic energy 1/2 v^T M v. (Taking the lumped values as known in the free rows instead
  // made the system unsymmetric: a rubber wedge bouncing on a floor gained 67 % energy.)
  multiply_filtered(p, coupling, d, f);
  const auto apply = [&](const std::vector<Vec2>& x, std::vector<Vec2>& y) {
    multiply_filtered(x, y, d, f);
    for (std::size_t i = 0; i < n; ++i) y[i] = masked(i, y[i] + coupling[i].cwiseProduct(x[i]));
  };
  // Start from the lumped values: exact where the particles move rigidly.
  double qq = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    u[i] = masked(i, lumped_value[i]);
    qq += masked(i, q[i]).squaredNorm();
  }
  const auto finish = [&] {
    for (std::size_t i = 0; i < n; ++i) {
      if ((known[i] & ~free[i] & 1) != 0) u[i].x() = lumped_value[i].x();
      if ((known[i] & ~free[i] & 2) != 0) u[i].y() = lumped_value[i].y();
    }
  };
  if (qq == 0.0) {  // nothing to solve for: the lumped values (zero where q is)
    finish();
    return u;
  }
  const double tolerance = 1e-26 * qq;  // |r|^2
  apply(u, Mp);
  double rz = 0.0, rr = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    r[i] = masked(i, q[i]) - Mp[i];
    z[i] = precondition(i, r[i]);
    p[i] = z[i];
    rz += r[i].dot(z[i]);
    rr += r[i].squaredNorm();
  }
  const int limit = 2000;
  for (int iteration = 0; rr > tolerance; ++iteration) {
    if (iteration == limit)
      throw NumericalError(fmt::format(
          "MPM pseudo-inverse mapping: conjugate gradients on the mass matrix did not converge in {} iterations "
          "(residual {:.3g} of the right-hand side): too few particles determine some nodes (the pseudo-inverse needs "
          "at least two particles per cell and direction); use mapping = \"lumped\"",
          limit, std::sqrt(rr / qq)));
    apply(p, Mp);
    double pMp = 0.0;
    for (std::size_t i = 0; i < n; ++i) pMp += p[i].dot(Mp[i]);
    if (!(pMp > 0.0))
      throw NumericalError(
          "MPM pseudo-inverse mapping: the mass matrix is singular on the nodes the particles reach (too few particles "
          "to determine them: the pseudo-inverse needs at least two particles per cell and direction); use mapping = "
          "\"lumped\"");
    const double alpha = rz / pMp;
    double rz_next = 0.0;
    rr = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      u[i] += alpha * p[i];
      r[i] -= alpha * Mp[i];
      z[i] = precondition(i, r[i]);
      rz_next += r[i].dot(z[i]);
      rr += r[i].squaredNorm();
    }
    const double beta = rz_next / rz;
    rz = rz_next;
    for (std::size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
  }
  finish();
  // Ill-determined rows show as values far outside the data's: the iteration fitted
  // round-off (or a near-null space) instead of particle data.
  double largest = 0.0, data = 0.0;
  std::size_t worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!known[i]) continue;
    data = std::max(data, (q[i] / lumped[i]).cwiseAbs().maxCoeff());
    if (u[i].cwiseAbs().maxCoeff() > largest) {
      largest = u[i].cwiseAbs().maxCoeff();
      worst = i;
    }
  }
  if (largest > 100.0 * data) {
    const Vec2 x = grid_.node(static_cast<Index>(worst));
    throw NumericalError(fmt::format(
        "MPM pseudo-inverse mapping: the particles do not determine the nodal values near ({:.6g}, {:.6g}) (a nodal "
        "value {:.3g} times the largest of the particle data's lumped values): the mass matrix is (nearly) singular "
        "there, as where a body's edge leaves fewer than two particles per cell and direction; use mapping = "
        "\"lumped\"",
        x.x(), x.y(), largest / data));
  }
  return u;
}

}  // namespace mfree

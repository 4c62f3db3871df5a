#include "mfree/quadrature/background_lattice.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/geometry/polygon_integrals.hpp"
#include "mfree/quadrature/gauss_cells.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"
#include "mfree/quadrature/rule_on_cracks.hpp"

namespace mfree {

namespace {

// Lagrange functions L_i of equispaced nodes on [0, 1] and their antiderivatives
// Lambda_i(t) = integral from 0 to t of L_i, as polynomial coefficients (ascending powers).
// Order 1: L = {1 - t, t}. Order 2: L = {2t^2 - 3t + 1, 4t - 4t^2, 2t^2 - t}.
// Lambda_i(1) are the Newton–Cotes weights: {1/2, 1/2} and {1/6, 2/3, 1/6}.
constexpr int max_order = 2;
using Poly = std::array<double, 4>;
constexpr std::array<std::array<Poly, 3>, 2> lagrange = {{
    {{{1.0, -1.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0}, {}}},
    {{{1.0, -3.0, 2.0, 0.0}, {0.0, 4.0, -4.0, 0.0}, {0.0, -1.0, 2.0, 0.0}}},
}};
constexpr std::array<std::array<Poly, 3>, 2> antiderivative = {{
    {{{0.0, 1.0, -0.5, 0.0}, {0.0, 0.0, 0.5, 0.0}, {}}},
    {{{0.0, 1.0, -1.5, 2.0 / 3.0}, {0.0, 0.0, 2.0, -4.0 / 3.0}, {0.0, 0.0, -0.5, 2.0 / 3.0}}},
}};

double horner(const Poly& c, double t) { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }

/// Monomials of degree <= order in the cell coordinates u = (x - centre) / side:
/// 1, u, v (order 1) and u^2, u v, v^2 (order 2).
int monomial_count(int order) { return order == 1 ? 3 : 6; }
void monomials(const Vec2& u, int order, double* out) {
  out[0] = 1.0;
  out[1] = u.x();
  out[2] = u.y();
  if (order == 2) {
    out[3] = u.x() * u.x();
    out[4] = u.x() * u.y();
    out[5] = u.y() * u.y();
  }
}

/// Integrals over the region bounded by `rings` of the monomials above, by Green's
/// theorem: integral of u^a v^b = ring integral of u^(a+1) v^b / (a+1) dv, a polynomial of
/// degree <= 3 along each straight edge, so 2 Gauss points per edge are exact.
void monomial_moments(const std::vector<Ring>& rings, const Vec2& centre, double side, int order,
                      double* out) {
  static const GaussLegendre1D g = gauss_legendre(2);
  const int m = monomial_count(order);
  std::fill(out, out + m, 0.0);
  for (const Ring& ring : rings)
    for (std::size_t e = 0; e < ring.size(); ++e) {
      const Vec2 p = (ring[e] - centre) / side, q = (ring[(e + 1) % ring.size()] - centre) / side;
      const double dv = q.y() - p.y();
      if (dv == 0.0) continue;
      for (std::size_t k = 0; k < g.points.size(); ++k) {
        const Vec2 u = p + g.points[k] * (q - p);
        const double f = g.weights[k] * dv;
        out[0] += f * u.x();
        out[1] += f * u.x() * u.x() / 2.0;
        out[2] += f * u.x() * u.y();
        if (order == 2) {
          out[3] += f * u.x() * u.x() * u.x() / 3.0;
          out[4] += f * u.x() * u.x() * u.y() / 2.0;
          out[5] += f * u.x() * u.y() * u.y();
        }
      }
    }
  for (int k = 0; k < m; ++k) out[k] *= side * side;
}

/// A quadrature rule for the part of one cell inside the domain (`rings`, from
/// Domain::clip), with every point in the closed domain and exact for polynomials of degree
/// <= order. Points: the rings' vertices and edge midpoints (on the boundary of the cut
/// part; they make a degree-2 unisolvent set even for a sliver triangle) and the cell's
/// (order + 1)^2 Gauss points that lie inside. Weights: the equal-share weights corrected
/// by the least change that matches the exact moments (moment fitting):
///   w = w0 + V^T (V V^T)^-1 (m - V w0),  V_jk = monomial j at point k.
/// Keeping the points inside the domain matters: the quadrature-cloud functions need not
/// be defined outside it (a point inside a hole may see its neighbours on one line).
void cut_cell_rule(const Domain& domain, const std::vector<Ring>& rings, const Vec2& lo,
                   double side, int order, std::vector<Vec2>& points, std::vector<double>& weights) {
  const int m = monomial_count(order);
  const Vec2 centre = lo + Vec2(0.5 * side, 0.5 * side);
  std::vector<Vec2> x;
  for (const Ring& ring : rings)
    for (std::size_t e = 0; e < ring.size(); ++e) {
      x.push_back(ring[e]);
      x.push_back(0.5 * (ring[e] + ring[(e + 1) % ring.size()]));
    }
  const GaussLegendre1D g = gauss_legendre(order + 1);
  for (double gy : g.points)
    for (double gx : g.points) {
      const Vec2 p = lo + side * Vec2(gx, gy);
      if (domain.contains(p)) x.push_back(p);
    }
  const Index n = static_cast<Index>(x.size());
  Eigen::MatrixXd v(m, n);
  for (Index k = 0; k < n; ++k) monomials((x[k] - centre) / side, order, v.col(k).data());
  Eigen::VectorXd moments(m);
  monomial_moments(rings, centre, side, order, moments.data());
  const Eigen::VectorXd w0 = Eigen::VectorXd::Constant(n, moments[0] / n);
  const Eigen::VectorXd w =
      w0 + v.transpose() * (v * v.transpose()).ldlt().solve(moments - v * w0);
  for (Index k = 0; k < n; ++k) {
    points.push_back(x[k]);
    weights.push_back(w[k]);
  }
}

/// InputError for a spacing that is not positive or an order other than 1 and 2.
void check_lattice(double spacing, int order) {
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw InputError(fmt::format("background lattice: spacing must be positive, got {}", spacing));
  if (order < 1 || order > max_order)
    throw InputError(
        fmt::format("background lattice: order must be 1 (trapezoid) or 2 (Simpson), "
                    "got {}",
                    order));
}

}  // namespace

void lagrange_cell_integrals(const std::vector<Ring>& rings, const Vec2& lo, double side,
                             int order, double* out) {
  const int n = order + 1;
  std::fill(out, out + n * n, 0.0);
  // Green's theorem: integral over the region of L_i(s) L_j(t) = ring integral of
  // Lambda_i(s) L_j(t) dt, in cell coordinates (s, t) = (x - lo) / side. Along a straight
  // edge the integrand is a polynomial of degree 2 order + 1: order + 1 Gauss points are exact.
  static const GaussLegendre1D gauss[max_order] = {gauss_legendre(2), gauss_legendre(3)};
  const GaussLegendre1D& g = gauss[order - 1];
  const auto& L = lagrange[order - 1];
  const auto& A = antiderivative[order - 1];
  for (const Ring& ring : rings) {
    for (std::size_t e = 0; e < ring.size(); ++e) {
      const Vec2 p = (ring[e] - lo) / side;
      const Vec2 q = (ring[(e + 1) % ring.size()] - lo) / side;
      const double dt = q.y() - p.y();
      if (dt == 0.0) continue;
      for (std::size_t k = 0; k < g.points.size(); ++k) {
        const Vec2 x = p + g.points[k] * (q - p);
        for (int j = 0; j < n; ++j) {
          const double lj = horner(L[j], x.y()) * g.weights[k] * dt;
          for (int i = 0; i < n; ++i) out[j * n + i] += horner(A[i], x.x()) * lj;
        }
      }
    }
  }
  for (int k = 0; k < n * n; ++k) out[k] *= side * side;
}

template <>
BackgroundLattice<2>::BackgroundLattice(const Domain& domain, double spacing, int order)
    : spacing_(spacing), order_(order) {
  check_lattice(spacing, order);
  const Box box = domain.bounding_box();
  const double side = order * spacing;  // integration cell side
  const Index ncx = std::max<Index>(1, static_cast<Index>(std::ceil(box.size().x() / side - 1e-9)));
  const Index ncy = std::max<Index>(1, static_cast<Index>(std::ceil(box.size().y() / side - 1e-9)));
  const Index nvx = ncx * order + 1, nvy = ncy * order + 1;
  if (static_cast<double>(nvx) * nvy > 2e9)
    throw InputError(fmt::format("background lattice: {} x {} vertices is too many; increase the "
                                 "lattice spacing",
                                 nvx, nvy));
  const Vec2 origin = box.lo;
  const auto cell_lo = [&](Index ci, Index cj) {
    return Vec2(origin.x() + ci * side, origin.y() + cj * side);
  };

  // Cells that a boundary segment's bounding box touches may be cut; the rest are wholly
  // inside or outside, decided by their centre.
  // A cell that an interface's bounding box touches may hold two regions' parts.
  enum : char { whole = 0, cut = 1, interface = 2 };
  std::vector<char> maybe_cut(static_cast<std::size_t>(ncx) * ncy, whole);
  const double pad = 1e-9 * side;
  for (const BoundarySegment& s : domain.boundary()) {
    const char mark = s.crack >= 0 && domain.cracks()[s.crack].interface() ? interface : cut;
    const Vec2 lo = s.a.cwiseMin(s.b).array() - pad, hi = s.a.cwiseMax(s.b).array() + pad;
    const auto cell = [&](double v, double o, Index n) {
      return std::clamp<Index>(static_cast<Index>(std::floor((v - o) / side)), 0, n - 1);
    };
    for (Index cj = cell(lo.y(), origin.y(), ncy); cj <= cell(hi.y(), origin.y(), ncy); ++cj)
      for (Index ci = cell(lo.x(), origin.x(), ncx); ci <= cell(hi.x(), origin.x(), ncx); ++ci)
        maybe_cut[static_cast<std::size_t>(cj) * ncx + ci] |= mark;
  }

  const int n = order + 1;
  std::array<double, (max_order + 1) * (max_order + 1)> full{};
  {
    const Vec2 lo = Vec2::Zero();
    const std::vector<Ring> square = {{lo, Vec2(side, 0.0), Vec2(side, side), Vec2(0.0, side)}};
    lagrange_cell_integrals(square, lo, side, order, full.data());
  }

  // Cell by cell. Whole cells scatter their Newton–Cotes weights to the lattice vertices,
  // each thread into its own copy (added in thread order: the result does not depend on
  // scheduling); cut cells get their own moment-fitted points (cut_cell_rule).
  const Index ncells = ncx * ncy;
  const int nt = thread_count();
  std::vector<std::vector<double>> partial(nt);
  std::vector<std::vector<Vec2>> cut_points(nt);
  std::vector<std::vector<double>> cut_weights(nt);
  std::vector<Index> cut_count(nt, 0);
  parallel_ranges(ncells, [&](int t, Index begin, Index end) {
    std::vector<double>& c = partial[t];
    c.assign(static_cast<std::size_t>(nvx) * nvy, 0.0);
    for (Index cell = begin; cell < end; ++cell) {
      const Index ci = cell % ncx, cj = cell / ncx;
      const Vec2 lo = cell_lo(ci, cj);
      if ((maybe_cut[cell] & interface) || (maybe_cut[cell] && crack_crosses(domain, Box{lo, lo + Vec2(side, side)}))) {
        // Each region's part apart, quartered where a crack crosses, by interior points
        // (gauss_cells.hpp, degree 2 order + 1): no point straddles a jump of the functions or the law.
        QuadratureRule<2> parts;
        add_cell_points(domain, Box{lo, lo + Vec2(side, side)}, order + 1, parts);
        cut_points[t].insert(cut_points[t].end(), parts.points.begin(), parts.points.end());
        cut_weights[t].insert(cut_weights[t].end(), parts.weights.begin(), parts.weights.end());
        ++cut_count[t];
        continue;
      }
      if (maybe_cut[cell]) {
        const std::vector<Ring> inside = domain.clip(Box{lo, lo + Vec2(side, side)});
        if (inside.empty()) continue;
        double area = 0.0;
        for (const Ring& r : inside) area += ring_area(r);
        if (std::abs(area - side * side) > 1e-12 * side * side) {
          cut_cell_rule(domain, inside, lo, side, order, cut_points[t], cut_weights[t]);
          ++cut_count[t];
          continue;
        }
      } else if (!domain.contains(lo + Vec2(0.5 * side, 0.5 * side))) {
        continue;
      }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          c[static_cast<std::size_t>(cj * order + j) * nvx + ci * order + i] += full[j * n + i];
    }
  });
  std::vector<double> c = std::move(partial[0]);
  for (std::size_t t = 1; t < partial.size(); ++t)
    for (std::size_t v = 0; v < c.size(); ++v) c[v] += partial[t][v];
  for (Index k : cut_count) cut_cells_ += k;

  for (Index vj = 0; vj < nvy; ++vj)
    for (Index vi = 0; vi < nvx; ++vi) {
      const double cv = c[static_cast<std::size_t>(vj) * nvx + vi];
      if (cv == 0.0) continue;
      points_.emplace_back(origin.x() + vi * spacing, origin.y() + vj * spacing);
      weights_.push_back(cv);
    }
  for (int t = 0; t < nt; ++t) {
    points_.insert(points_.end(), cut_points[t].begin(), cut_points[t].end());
    weights_.insert(weights_.end(), cut_weights[t].begin(), cut_weights[t].end());
  }
  QuadratureRule<2> split =
      split_rule_on_cracks(domain, QuadratureRule<2>{std::move(points_), std::move(weights_)}, spacing);
  points_ = std::move(split.points);
  weights_ = std::move(split.weights);
  cells_ = ncells;
}

template <>
BackgroundLattice<3>::BackgroundLattice(const Solid& solid, double spacing, int order)
    : spacing_(spacing), order_(order) {
  check_lattice(spacing, order);
  const AlignedBox<3>& box = solid.bounding_box();
  const Point<3> size = box.sizes();
  // Per axis: cells of side size / cells (about order * spacing), and the composite
  // Newton–Cotes weight of each vertex: the sum over the cells holding it of side Lambda_i(1)
  // (above: {1/2, 1/2} trapezoid, {1/6, 2/3, 1/6} Simpson).
  std::array<std::vector<double>, 3> axis;
  std::array<double, 3> step;
  double vertices = 1.0;
  for (int c = 0; c < 3; ++c) {
    const Index cells = std::max<Index>(1, static_cast<Index>(std::ceil(size[c] / (order * spacing) - 1e-9)));
    const double side = size[c] / cells;
    step[c] = side / order;
    axis[c].assign(static_cast<std::size_t>(cells) * order + 1, 0.0);
    for (Index cell = 0; cell < cells; ++cell)
      for (int i = 0; i <= order; ++i)
        axis[c][static_cast<std::size_t>(cell) * order + i] +=
            side * horner(antiderivative[order - 1][i], 1.0);
    vertices *= static_cast<double>(axis[c].size());
    cells_ = c == 0 ? cells : cells_ * cells;
  }
  if (vertices > 2e9)
    throw InputError(
        fmt::format("background lattice: {} x {} x {} vertices is too many; increase the lattice spacing",
                    axis[0].size(), axis[1].size(), axis[2].size()));
  check_memory(vertices * (sizeof(Point<3>) + sizeof(double)),
               fmt::format("a background lattice of {:.3g} vertices", vertices));
  points_.reserve(static_cast<std::size_t>(vertices));
  weights_.reserve(static_cast<std::size_t>(vertices));
  // The last vertex of each axis snapped onto the box's face.
  const auto coordinate = [&](int c, std::size_t i) {
    return i + 1 == axis[c].size() ? box.max()[c] : box.min()[c] + static_cast<double>(i) * step[c];
  };
  for (std::size_t k = 0; k < axis[2].size(); ++k)
    for (std::size_t j = 0; j < axis[1].size(); ++j)
      for (std::size_t i = 0; i < axis[0].size(); ++i) {
        points_.emplace_back(coordinate(0, i), coordinate(1, j), coordinate(2, k));
        weights_.push_back(axis[0][i] * axis[1][j] * axis[2][k]);
      }
}

template class BackgroundLattice<2>;
template class BackgroundLattice<3>;

}  // namespace mfree

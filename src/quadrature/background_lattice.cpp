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
#include "mfree/geometry/tetrahedral_mesh.hpp"
#include "mfree/geometry/tetrahedron.hpp"
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

/// The weights nearest w0 that integrate the monomials exactly (moment fitting):
///   w = w0 + V^T (V V^T)^-1 (m - V w0),  V_jk = monomial j at point k.
Eigen::VectorXd moment_fitted(const Eigen::MatrixXd& v, const Eigen::VectorXd& moments,
                              const Eigen::VectorXd& w0) {
  return w0 + v.transpose() * (v * v.transpose()).ldlt().solve(moments - v * w0);
}

/// A quadrature rule for the part of one cell inside the domain (`rings`, from
/// Domain::clip), with every point in the closed domain and exact for polynomials of degree
/// <= order. Points: the rings' vertices and edge midpoints (on the boundary of the cut
/// part; they make a degree-2 unisolvent set even for a sliver triangle) and the cell's
/// (order + 1)^2 Gauss points that lie inside. Weights: the equal-share weights corrected
/// by the least change that matches the exact moments (moment_fitted).
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
  const Eigen::VectorXd w = moment_fitted(v, moments, Eigen::VectorXd::Constant(n, moments[0] / n));
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

namespace {

/// The 1 + 3 (order 1) or 10 (order 2) monomials of degree <= order in u.
int monomial_count_3d(int order) { return order == 1 ? 4 : 10; }
void monomials(const Point<3>& u, int order, double* out) {
  out[0] = 1.0;
  for (int c = 0; c < 3; ++c) out[1 + c] = u[c];
  if (order == 2)
    for (int a = 0, k = 4; a < 3; ++a)
      for (int b = a; b < 3; ++b) out[k++] = u[a] * u[b];
}

/// The same monomials integrated over a tetrahedron (closed forms: volume, centroid and
/// tetrahedron_second_moments), added to out.
void add_monomial_moments(const Tetrahedron& t, int order, double* out) {
  const double volume = tetrahedron_volume(t);
  const Point<3> centroid = tetrahedron_centroid(t);
  out[0] += volume;
  for (int c = 0; c < 3; ++c) out[1 + c] += volume * centroid[c];
  if (order == 2) {
    const Tensor2<3> m = tetrahedron_second_moments(t);
    for (int a = 0, k = 4; a < 3; ++a)
      for (int b = a; b < 3; ++b) out[k++] += m(a, b);
  }
}

/// A quadrature rule for the part of a cut cell inside the solid, from the tetrahedra of the
/// solid's mesh that meet it (`tets`): each clipped to the cell, then to the cell's s^3
/// sub-boxes (s = 2 order - 1); each sub-box's part is one point, its centroid, with its volume
/// as weight (a sub-box part whose centroid lies outside the solid, a part that is not convex,
/// gives the centroids of its pieces instead: those lie in their tetrahedra). These weights
/// integrate degree 1 exactly; for order 2 they are corrected by the least change that
/// integrates the 10 monomials of degree <= 2 exactly (moment_fitted), where the points allow
/// it (at least 10 of them, unisolvent; a cell the surface only grazes keeps the degree-1
/// weights, as more points there would cost more than their accuracy gains). Every point lies
/// in the closed solid. With `region` >= 0 the tetrahedra are that region's (a cell at a tied
/// interface is integrated region by region) and a centroid must lie in it.
void cut_cell_rule(const Solid& solid, const std::vector<Tetrahedron>& tets, int region,
                   const AlignedBox<3>& cell, int order, std::vector<Point<3>>& points,
                   std::vector<double>& weights) {
  const int s = 2 * order - 1;
  const Point<3> lo = cell.min(), side = cell.sizes(), centre = cell.center();
  const double volume_scale = side.prod();
  std::vector<std::vector<Tetrahedron>> parts(static_cast<std::size_t>(s * s * s));
  std::vector<Tetrahedron> pieces, sub_pieces;
  const int m = monomial_count_3d(order);
  Eigen::VectorXd moments = Eigen::VectorXd::Zero(m);
  for (const Tetrahedron& tet : tets) {
    pieces.clear();
    clip_to_box(tet, cell, pieces);
    for (const Tetrahedron& piece : pieces) {
      Tetrahedron local;  // in the cell coordinates u = (x - centre) / side
      for (int k = 0; k < 4; ++k) local[k] = (piece[k] - centre).cwiseQuotient(side);
      add_monomial_moments(local, order, moments.data());
      if (s == 1) {
        parts[0].push_back(piece);
        continue;
      }
      AlignedBox<3> bounds(piece[0]);
      for (const Point<3>& v : piece) bounds.extend(v);
      std::array<int, 3> from, to;
      for (int c = 0; c < 3; ++c) {
        const auto sub = [&](double x) {
          return std::clamp(static_cast<int>(std::floor((x - lo[c]) / side[c] * s)), 0, s - 1);
        };
        from[c] = sub(bounds.min()[c]);
        to[c] = sub(bounds.max()[c]);
      }
      for (int z = from[2]; z <= to[2]; ++z)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int x = from[0]; x <= to[0]; ++x) {
            const Point<3> a = lo + Point<3>(x, y, z).cwiseProduct(side) / s;
            sub_pieces.clear();
            clip_to_box(piece, AlignedBox<3>(a, Point<3>(a + side / s)), sub_pieces);
            auto& part = parts[static_cast<std::size_t>((z * s + y) * s + x)];
            part.insert(part.end(), sub_pieces.begin(), sub_pieces.end());
          }
    }
  }
  std::vector<Point<3>> x;
  std::vector<double> w0;
  for (const std::vector<Tetrahedron>& part : parts) {
    double volume = 0.0;
    Point<3> first = Point<3>::Zero();
    for (const Tetrahedron& piece : part) {
      const double v = tetrahedron_volume(piece);
      volume += v;
      first += v * tetrahedron_centroid(piece);
    }
    if (!(volume > 1e-14 * volume_scale)) continue;
    const Point<3> centroid = first / volume;
    if (region < 0 ? solid.contains(centroid) : solid.region_at(centroid) == region) {
      x.push_back(centroid);
      w0.push_back(volume);
      continue;
    }
    for (const Tetrahedron& piece : part)
      if (const double v = tetrahedron_volume(piece); v > 0.0) {
        x.push_back(tetrahedron_centroid(piece));
        w0.push_back(v);
      }
  }
  const auto n = static_cast<Index>(x.size());
  Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(w0.data(), n);
  if (order == 2 && n >= m) {
    Eigen::MatrixXd v(m, n);
    for (Index k = 0; k < n; ++k)
      monomials(Point<3>((x[k] - centre).cwiseQuotient(side)), order, v.col(k).data());
    const Eigen::VectorXd fitted = moment_fitted(v, moments, w / volume_scale) * volume_scale;
    // Points on (or near) a quadric cannot fit: keep the degree-1 weights there.
    if (fitted.allFinite() && (v * fitted / volume_scale - moments).norm() <= 1e-10 * moments[0]) w = fitted;
  }
  for (Index k = 0; k < n; ++k) {
    points.push_back(x[k]);
    weights.push_back(w[k]);
  }
}

/// The first and last cell per axis whose interior meets the box `bounds`: cells k with
/// lo + k side < max and lo + (k + 1) side > min (from > to on an axis: none).
std::pair<std::array<Index, 3>, std::array<Index, 3>> cells_meeting(const AlignedBox<3>& bounds,
                                                                    const std::array<Index, 3>& cells,
                                                                    const Point<3>& lo,
                                                                    const std::array<double, 3>& side) {
  std::array<Index, 3> from, to;
  for (int c = 0; c < 3; ++c) {
    from[c] = std::max<Index>(0, static_cast<Index>(std::floor((bounds.min()[c] - lo[c]) / side[c])));
    to[c] =
        std::min<Index>(cells[c] - 1, static_cast<Index>(std::ceil((bounds.max()[c] - lo[c]) / side[c])) - 1);
  }
  return {from, to};
}

/// The cells of the lattice that a surface triangle may cross: those whose interior meets
/// the triangle's bounding box (a triangle in a cell's face plane crosses none).
std::vector<char> cells_crossed(const Solid& solid, const std::array<Index, 3>& cells, const Point<3>& lo,
                                const std::array<double, 3>& side) {
  std::vector<char> cut(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2], 0);
  const auto mark = [&](const std::array<Point<3>, 3>& vertices, double grow) {
    AlignedBox<3> bounds(vertices[0]);
    for (const Point<3>& v : vertices) bounds.extend(v);
    bounds.min().array() -= grow;
    bounds.max().array() += grow;
    const auto [from, to] = cells_meeting(bounds, cells, lo, side);
    for (Index z = from[2]; z <= to[2]; ++z)
      for (Index y = from[1]; y <= to[1]; ++y)
        for (Index x = from[0]; x <= to[0]; ++x)
          cut[(static_cast<std::size_t>(z) * cells[1] + y) * cells[0] + x] = 1;
  };
  for (const SurfaceTriangle& tri : solid.surface()) mark(tri.vertices, 0.0);
  // A whole cell may not touch a tied interface either: its vertices would lie on the face.
  const double touch = 1e-9 * *std::min_element(side.begin(), side.end());
  for (const InterfaceTriangle& tri : solid.interfaces()) mark(tri.vertices, touch);
  return cut;
}

}  // namespace

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
  std::array<double, 3> step, side;
  std::array<Index, 3> cells;
  double vertices = 1.0;
  for (int c = 0; c < 3; ++c) {
    cells[c] = std::max<Index>(1, static_cast<Index>(std::ceil(size[c] / (order * spacing) - 1e-9)));
    side[c] = size[c] / cells[c];
    step[c] = side[c] / order;
    axis[c].assign(static_cast<std::size_t>(cells[c]) * order + 1, 0.0);
    for (Index cell = 0; cell < cells[c]; ++cell)
      for (int i = 0; i <= order; ++i)
        axis[c][static_cast<std::size_t>(cell) * order + i] +=
            side[c] * horner(antiderivative[order - 1][i], 1.0);
    vertices *= static_cast<double>(axis[c].size());
  }
  cells_ = cells[0] * cells[1] * cells[2];
  if (vertices > 2e9)
    throw InputError(
        fmt::format("background lattice: {} x {} x {} vertices is too many; increase the lattice spacing",
                    axis[0].size(), axis[1].size(), axis[2].size()));
  check_memory(vertices * (sizeof(Point<3>) + sizeof(double)),
               fmt::format("a background lattice of {:.3g} vertices", vertices));
  // The last vertex of each axis snapped onto the box's face.
  const auto coordinate = [&](int c, std::size_t i) {
    return i + 1 == axis[c].size() ? box.max()[c] : box.min()[c] + static_cast<double>(i) * step[c];
  };
  const auto vertex = [&](std::size_t i, std::size_t j, std::size_t k) {
    return Point<3>(coordinate(0, i), coordinate(1, j), coordinate(2, k));
  };
  if (solid.mesh() == nullptr) {
    // A box: every cell whole, the weights the tensor product of the axes'.
    points_.reserve(static_cast<std::size_t>(vertices));
    weights_.reserve(static_cast<std::size_t>(vertices));
    for (std::size_t k = 0; k < axis[2].size(); ++k)
      for (std::size_t j = 0; j < axis[1].size(); ++j)
        for (std::size_t i = 0; i < axis[0].size(); ++i) {
          points_.push_back(vertex(i, j, k));
          weights_.push_back(axis[0][i] * axis[1][j] * axis[2][k]);
        }
    return;
  }
  // A meshed solid: cells crossed by its surface are cut; the others are whole when their
  // centre is inside, and give their vertices the tensor Newton–Cotes weights.
  const std::vector<char> cut = cells_crossed(solid, cells, box.min(), side);
  const auto cell_index = [&](Index x, Index y, Index z) {
    return (static_cast<std::size_t>(z) * cells[1] + y) * cells[0] + x;
  };
  std::vector<double> weight(static_cast<std::size_t>(vertices), 0.0);
  std::array<double, 3> newton_cotes{};
  for (int i = 0; i <= order; ++i) newton_cotes[i] = horner(antiderivative[order - 1][i], 1.0);
  const double cell_volume = side[0] * side[1] * side[2];
  for (Index z = 0; z < cells[2]; ++z)
    for (Index y = 0; y < cells[1]; ++y)
      for (Index x = 0; x < cells[0]; ++x) {
        if (cut[cell_index(x, y, z)]) continue;
        const Point<3> centre =
            box.min() + Point<3>((x + 0.5) * side[0], (y + 0.5) * side[1], (z + 0.5) * side[2]);
        if (!solid.contains(centre)) continue;
        for (int c = 0; c <= order; ++c)
          for (int b = 0; b <= order; ++b)
            for (int a = 0; a <= order; ++a)
              weight[(static_cast<std::size_t>(z * order + c) * axis[1].size() +
                      static_cast<std::size_t>(y * order + b)) *
                         axis[0].size() +
                     static_cast<std::size_t>(x * order + a)] +=
                  cell_volume * newton_cotes[a] * newton_cotes[b] * newton_cotes[c];
      }
  for (std::size_t k = 0, v = 0; k < axis[2].size(); ++k)
    for (std::size_t j = 0; j < axis[1].size(); ++j)
      for (std::size_t i = 0; i < axis[0].size(); ++i, ++v)
        if (weight[v] != 0.0) {
          points_.push_back(vertex(i, j, k));
          weights_.push_back(weight[v]);
        }
  // The cut cells: the tetrahedra meeting each (bounding boxes overlapping its interior).
  const TetrahedralMesh& mesh = *solid.mesh();
  std::vector<std::pair<std::size_t, Index>> meets;  // (cut cell, tetrahedron)
  for (Index t = 0; t < mesh.size(); ++t) {
    const Tetrahedron tet = mesh.tetrahedron(t);
    AlignedBox<3> bounds(tet[0]);
    for (const Point<3>& v : tet) bounds.extend(v);
    const auto [from, to] = cells_meeting(bounds, cells, box.min(), side);
    for (Index z = from[2]; z <= to[2]; ++z)
      for (Index y = from[1]; y <= to[1]; ++y)
        for (Index x = from[0]; x <= to[0]; ++x)
          if (cut[cell_index(x, y, z)]) meets.emplace_back(cell_index(x, y, z), t);
  }
  std::sort(meets.begin(), meets.end());
  std::vector<std::size_t> starts;  // the first entry of each cut cell in `meets`
  for (std::size_t e = 0; e < meets.size(); ++e)
    if (e == 0 || meets[e].first != meets[e - 1].first) starts.push_back(e);
  starts.push_back(meets.size());
  const auto n_cut = static_cast<Index>(starts.size() - 1);
  std::vector<std::vector<Point<3>>> cut_points(static_cast<std::size_t>(n_cut));
  std::vector<std::vector<double>> cut_weights(static_cast<std::size_t>(n_cut));
  parallel_blocks(n_cut, 64, [&](Index begin, Index end) {
    std::vector<Tetrahedron> tets;
    for (Index c = begin; c < end; ++c) {
      const auto u = static_cast<std::size_t>(c);
      const std::size_t cell = meets[starts[u]].first;
      const auto x = static_cast<Index>(cell % static_cast<std::size_t>(cells[0]));
      const auto y =
          static_cast<Index>(cell / static_cast<std::size_t>(cells[0]) % static_cast<std::size_t>(cells[1]));
      const auto z = static_cast<Index>(
          cell / (static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1])));
      const Point<3> a = box.min() + Point<3>(x * side[0], y * side[1], z * side[2]);
      const AlignedBox<3> box_of_cell(a, Point<3>(a + Point<3>(side[0], side[1], side[2])));
      if (solid.interfaces().empty()) {
        tets.clear();
        for (std::size_t e = starts[u]; e < starts[u + 1]; ++e)
          tets.push_back(mesh.tetrahedron(meets[e].second));
        cut_cell_rule(solid, tets, -1, box_of_cell, order, cut_points[u], cut_weights[u]);
        continue;
      }
      for (std::size_t e = starts[u]; e < starts[u + 1];
           ++e) {  // region by region, in order of first meeting
        const int region = mesh.region(meets[e].second);
        bool done = false;
        for (std::size_t f = starts[u]; f < e && !done; ++f) done = mesh.region(meets[f].second) == region;
        if (done) continue;
        tets.clear();
        for (std::size_t f = e; f < starts[u + 1]; ++f)
          if (mesh.region(meets[f].second) == region) tets.push_back(mesh.tetrahedron(meets[f].second));
        cut_cell_rule(solid, tets, region, box_of_cell, order, cut_points[u], cut_weights[u]);
      }
    }
  });
  cut_cells_ = n_cut;
  for (Index c = 0; c < n_cut; ++c) {
    const auto u = static_cast<std::size_t>(c);
    points_.insert(points_.end(), cut_points[u].begin(), cut_points[u].end());
    weights_.insert(weights_.end(), cut_weights[u].begin(), cut_weights[u].end());
  }
}

template class BackgroundLattice<2>;
template class BackgroundLattice<3>;

}  // namespace mfree

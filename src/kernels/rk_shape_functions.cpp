#include "mfree/kernels/rk_shape_functions.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "mfree/core/error.hpp"
#include "mfree/kernels/rk_moment.hpp"

namespace mfree {

const NameTable<Window>& window_names() {
  static const NameTable<Window> table{{"cubic_bspline", Window::cubic_bspline}, {"quadratic_spline", Window::quadratic_spline}};
  return table;
}

std::string_view to_string(Window kind) { return window_names().name(kind); }

const NameTable<RKOrder>& order_names() {
  static const NameTable<RKOrder> table{{"linear", RKOrder::linear}, {"quadratic", RKOrder::quadratic}};
  return table;
}

std::string_view to_string(RKOrder order) { return order_names().name(order); }

const NameTable<SupportShape>& support_names() {
  static const NameTable<SupportShape> table{{"circular", SupportShape::circular}, {"tensor", SupportShape::tensor}};
  return table;
}

std::string_view to_string(SupportShape shape) { return support_names().name(shape); }

namespace {

/// Window value and gradient (with respect to x) for the offset d = x - x_I.
template <int dim>
struct WindowSample {
  double w;
  std::array<double, dim> g;
};

template <Window W>
WindowValue window(double r) {
  if constexpr (W == Window::cubic_bspline) return cubic_bspline(r);
  else return quadratic_spline(r);
}

template <int dim, Window W, SupportShape S>
WindowSample<dim> sample_window(const std::array<double, dim>& d, double inv_a) {
  // inv_a: 1 / a_I of the node whose window this is.
  WindowSample<dim> out;
  if constexpr (S == SupportShape::circular) {
    double d2 = d[0] * d[0];
    for (int c = 1; c < dim; ++c) d2 += d[c] * d[c];
    const double dist = std::sqrt(d2);
    const WindowValue v = window<W>(dist * inv_a);
    // w'(0) = 0 for both windows, so the node's own gradient is zero, not 0/0.
    const double g = dist > 0.0 ? v.dw * inv_a / dist : 0.0;
    out.w = v.w;
    for (int c = 0; c < dim; ++c) out.g[c] = g * d[c];
  } else {
    std::array<WindowValue, dim> v;
    for (int c = 0; c < dim; ++c) v[c] = window<W>(std::abs(d[c]) * inv_a);
    out.w = v[0].w;
    for (int c = 1; c < dim; ++c) out.w *= v[c].w;
    // d w / d x_c = sign(d_c) / a w'(|d_c| / a) times the other axes' windows in axis order.
    for (int c = 0; c < dim; ++c) {
      out.g[c] = std::copysign(inv_a, d[c]) * v[c].dw;
      for (int e = 0; e < dim; ++e)
        if (e != c) out.g[c] *= v[e].w;
    }
  }
  return out;
}

/// H(z) and dH/dz_j of a point's scaled offset, from its scalar components.
template <int dim, int Order, class Z>
auto basis_value(const Z& z) {
  using Basis = PolynomialBasis<dim, Order>;
  if constexpr (dim == 2)
    return Basis::value(z[0], z[1]);
  else
    return Basis::value(z[0], z[1], z[2]);
}

template <int dim, int Order, int j, class Z>
auto basis_derivative(const Z& z) {
  using Basis = PolynomialBasis<dim, Order>;
  if constexpr (dim == 2) {
    if constexpr (j == 0)
      return Basis::d1(z[0], z[1]);
    else
      return Basis::d2(z[0], z[1]);
  } else {
    if constexpr (j == 0)
      return Basis::d1(z[0], z[1], z[2]);
    else if constexpr (j == 1)
      return Basis::d2(z[0], z[1], z[2]);
    else
      return Basis::d3(z[0], z[1], z[2]);
  }
}

/// f(std::integral_constant<int, j>) for j = 0 .. dim - 1: the axis a compile-time constant,
/// so each axis's basis derivative is the plain function of its scalars.
template <int dim, class F>
void for_axes(F&& f) {
  [&]<int... j>(std::integer_sequence<int, j...>) { (f(std::integral_constant<int, j>{}), ...); }
  (std::make_integer_sequence<int, dim>{});
}

/// The per-point RK construction for one basis, window and support (SPEC section 1).
/// `out.nodes` holds the neighbours on entry; phi and grad are filled. With Given, the
/// windows are given on entry instead (supports that respect the domain): out.phi[k] holds
/// w_I and out.grad[k] its gradient, for every neighbour, whether or not with_gradient.
///
/// Per-neighbour quantities are scalars and arrays of them (polynomial_basis.hpp), not
/// small Eigen vectors, and M is summed in its upper triangle: every operand of the three
/// passes stays in registers.
template <int dim, int Order, Window W, SupportShape S, bool Given>
void rk_point(const Point<dim>& x, std::span<const Point<dim>> nodes, const RKSettings& s,
              ShapeValues<dim>& out, bool with_gradient) {
  using Basis = PolynomialBasis<dim, Order>;
  constexpr int nb = Basis::size;
  using Terms = typename Basis::Terms;
  using Matrix = typename RKMoment<dim, Order>::Matrix;

  const std::size_t n = out.nodes.size();
  if constexpr (!Given) {
    out.phi.resize(n);
    out.grad.resize(with_gradient ? n : 0);
  }
  out.z.resize(n);
  const double inv_a = 1.0 / s.radius;  // basis scale
  const bool per_node = !s.node_radii.empty();
  if (n < static_cast<std::size_t>(nb)) throw_moment_failure(x, n, s, -1.0);

  // Pass 1: windows and M; phi temporarily holds w_I, grad holds grad w_I.
  RKMoment<dim, Order> moment;
  for (std::size_t k = 0; k < n; ++k) {
    const Point<dim>& node = nodes[out.nodes[k]];
    // The offsets as scalars: the basis reads them from registers, not back from out.z.
    std::array<double, dim> d, z;
    for (int c = 0; c < dim; ++c) {
      d[c] = x[c] - node[c];
      z[c] = d[c] * inv_a;
      out.z[k][c] = z[c];
    }
    if constexpr (Given) {
      moment.add(out.phi[k], basis_value<dim, Order>(z));
    } else {
      const WindowSample<dim> ws =
          sample_window<dim, W, S>(d, per_node ? 1.0 / s.node_radii[out.nodes[k]] : inv_a);
      moment.add(ws.w, basis_value<dim, Order>(z));
      out.phi[k] = ws.w;
      if (with_gradient)
        for (int c = 0; c < dim; ++c) out.grad[k][c] = ws.g[c];
    }
  }
  if constexpr (Given)
    if (!with_gradient) out.grad.clear();
  // M^-1 explicitly: it serves b and every d b / d x_j.
  Matrix minv;
  const double rcond = moment.invert(minv);
  if (!(rcond >= s.rcond_min)) throw_moment_failure(x, n, s, rcond);

  // b = M^-1 H(0), H(0) = e_1 in the shifted basis: phi_I = b . H(z_I) w_I.
  Terms b;
  for (int i = 0; i < nb; ++i) b[i] = minv(i, 0);
  if (!with_gradient) {
    for (std::size_t k = 0; k < n; ++k) out.phi[k] *= dot_terms(b, basis_value<dim, Order>(out.z[k]));
    return;
  }

  // Pass 2: (d M / d x_j) b, accumulated as vectors (O(n nb) instead of O(n nb^2)):
  // d M / d x_j = sum_I (d w_I / d x_j) H H^T + w_I (H_,j H^T + H H_,j^T), H_,j = dH/dz_j / a.
  std::array<Terms, dim> dmb{};
  for (std::size_t k = 0; k < n; ++k) {
    const Terms h = basis_value<dim, Order>(out.z[k]);
    const double hb = dot_terms(h, b);
    const double w = out.phi[k];
    const double e = w * hb * inv_a;
    for_axes<dim>([&](auto j) {
      const Terms hj = basis_derivative<dim, Order, j>(out.z[k]);
      const double c = out.grad[k][j] * hb + w * inv_a * dot_terms(hj, b);
      for (int i = 0; i < nb; ++i) dmb[j][i] += c * h[i] + e * hj[i];
    });
  }
  // d b / d x_j = -M^-1 (d M / d x_j) b.
  std::array<Terms, dim> db{};
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < nb; ++i)
      for (int c = 0; c < dim; ++c) db[c][i] -= minv(i, j) * dmb[c][j];

  // Pass 3: phi_I and grad phi_I = (db . H + b . dH) w_I + (b . H) grad w_I.
  for (std::size_t k = 0; k < n; ++k) {
    const Terms h = basis_value<dim, Order>(out.z[k]);
    const double hb = dot_terms(h, b);
    const double w = out.phi[k];
    out.phi[k] = hb * w;
    for_axes<dim>([&](auto j) {
      out.grad[k][j] =
          (dot_terms(db[j], h) + dot_terms(b, basis_derivative<dim, Order, j>(out.z[k])) * inv_a) * w +
          hb * out.grad[k][j];
    });
  }
}

template <int dim>
using PointKernel = void (*)(const Point<dim>&, std::span<const Point<dim>>, const RKSettings&,
                             ShapeValues<dim>&, bool);

template <int dim, int Order, bool Given>
PointKernel<dim> select_kernel(Window w, SupportShape s) {
  if (w == Window::cubic_bspline)
    return s == SupportShape::circular
               ? &rk_point<dim, Order, Window::cubic_bspline, SupportShape::circular, Given>
               : &rk_point<dim, Order, Window::cubic_bspline, SupportShape::tensor, Given>;
  return s == SupportShape::circular
             ? &rk_point<dim, Order, Window::quadratic_spline, SupportShape::circular, Given>
             : &rk_point<dim, Order, Window::quadratic_spline, SupportShape::tensor, Given>;
}

template <int dim, bool Given>
PointKernel<dim> select_kernel(const RKSettings& s) {
  return s.order == RKOrder::linear ? select_kernel<dim, 1, Given>(s.window, s.support)
                                    : select_kernel<dim, 2, Given>(s.window, s.support);
}

}  // namespace

int rk_basis_size(int dim, RKOrder order) {
  if (dim == 2) return order == RKOrder::linear ? PolynomialBasis<2, 1>::size : PolynomialBasis<2, 2>::size;
  return order == RKOrder::linear ? PolynomialBasis<3, 1>::size : PolynomialBasis<3, 2>::size;
}

template <int dim>
RKShapeFunctions<dim>::RKShapeFunctions(std::vector<Point> nodes, RKSettings settings)
    : nodes_(std::move(nodes)), settings_(settings) {
  if (nodes_.empty()) throw InputError("RK shape functions: the node cloud is empty");
  if (!(settings_.radius > 0.0) || !std::isfinite(settings_.radius))
    throw InputError(
        fmt::format("RK shape functions: support radius must be positive, got {}", settings_.radius));
  if (!settings_.node_radii.empty()) {
    if (settings_.node_radii.size() != nodes_.size())
      throw InputError(fmt::format("RK shape functions: {} node radii for {} nodes",
                                   settings_.node_radii.size(), nodes_.size()));
    for (double a : settings_.node_radii)
      if (!(a >= settings_.radius) || !std::isfinite(a))
        throw InputError(fmt::format("RK shape functions: node radius {} is below the base radius {}",
                                     a, settings_.radius));
    max_radius_ = *std::max_element(settings_.node_radii.begin(), settings_.node_radii.end());
  } else {
    max_radius_ = settings_.radius;
  }
  // Cells of half the support: a query's box of side 2a then covers about (5 a / 2)^2 of
  // candidates instead of (3 a)^2, 30 % fewer to test.
  cells_ = CellList<dim>(nodes_, 0.5 * max_radius_);
  if (settings_.rule != SupportRule::plain && settings_.surface_obstacles &&
      !settings_.surface_obstacles->empty()) {
    if (dim != 3) throw InputError("RK shape functions: surface obstacles are for clouds in a solid");
    if (settings_.rule != SupportRule::visibility)
      throw InputError(
          fmt::format("RK shape functions: the {} support rule is for plane clouds; in a solid supports take "
                      "\"visibility\"",
                      to_string(settings_.rule)));
    visibility_ = std::make_shared<const SurfaceVisibility>(
        *settings_.surface_obstacles, support_reach(settings_.support, max_radius_, dim));
    node_clearance_.resize(nodes_.size());
    parallel_blocks(size(), 1024, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i) {
        if constexpr (dim == 3) node_clearance_[i] = visibility_->clearance(nodes_[i]);
      }
    });
  }
  if (settings_.region_of) {
    if constexpr (dim == 2)
      throw InputError("RK shape functions: regions as separate bodies are for clouds in a solid");
    node_region_.resize(nodes_.size());
    parallel_blocks(size(), 1024, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i) {
        if constexpr (dim == 3) node_region_[i] = settings_.region_of(nodes_[i]);
      }
    });
    for (Index i = 0; i < size(); ++i)
      if (node_region_[i] < 0)
        throw InputError(fmt::format("RK shape functions: node {} ({:.6g}) lies in no region", i,
                                     fmt::join(nodes_[i].begin(), nodes_[i].end(), ", ")));
  }
  if (settings_.rule != SupportRule::plain && settings_.obstacles && !settings_.obstacles->empty()) {
    if constexpr (dim == 3)
      throw InputError("RK shape functions: segment obstacles are for plane clouds; a solid's are triangles");
    if (settings_.rule == SupportRule::geodesic && settings_.support != SupportShape::circular)
      throw InputError(
          "RK shape functions: the geodesic support rule measures distances along paths and needs "
          "circular supports; tensor supports take the visibility rule");
    paths_ = std::make_shared<const SupportPaths>(*settings_.obstacles, settings_.rule, max_radius_);
  }
}

template <int dim>
void throw_moment_failure(const Point<dim>& x, std::size_t n, const RKSettings& s, double rcond) {
  const int nb = rk_basis_size(dim, s.order);
  const std::string what = rcond >= 0.0
                               ? fmt::format("badly conditioned (reciprocal condition {:.2e} < {:.1e})",
                                             rcond, s.rcond_min)
                               : std::string("singular");
  throw NumericalError(fmt::format(
      "RK moment matrix at point ({:.6g}) is {}: {} neighbour(s) within the {} support of "
      "radius {:.4g}; a {} basis needs at least {} neighbours, not all on one {}. Increase the support "
      "radius "
      "(kernel support factor) or make the cloud denser or more regular near this point.",
      fmt::join(x.begin(), x.end(), ", "), what, n, to_string(s.support), s.radius, to_string(s.order), nb,
      dim == 2 ? (s.order == RKOrder::linear ? "line" : "conic")
               : (s.order == RKOrder::linear ? "plane" : "quadric")));
}

template <int dim>
std::vector<double> nodal_support_radii(const std::vector<Point<dim>>& nodes, double h, double factor,
                                        int k) {
  const CellList<dim> cells(nodes, 2.0 * h);
  std::vector<double> radii(nodes.size());
  parallel_blocks(static_cast<Index>(nodes.size()), 1024, [&](Index begin, Index end) {
    std::vector<double> d2;
    for (Index i = begin; i < end; ++i) {
      double r = 2.0 * h;
      for (;;) {  // widen the search until k other nodes are found
        d2.clear();
        cells.for_each_in_box(nodes[i], r, [&](Index j, const Point<dim>& p) {
          if (j != i) d2.push_back((p - nodes[i]).squaredNorm());
        });
        if (static_cast<int>(d2.size()) >= k || d2.size() + 1 == nodes.size()) break;
        r *= 2.0;
      }
      double dk = 0.0;
      if (!d2.empty()) {
        const auto kth = d2.begin() + std::min<std::size_t>(k, d2.size()) - 1;
        std::nth_element(d2.begin(), kth, d2.end());
        dk = std::sqrt(*kth);
      }
      radii[i] = factor * std::max(h, dk);
    }
  });
  return radii;
}

template <int dim>
void RKShapeFunctions<dim>::evaluate(const Point& x, Values& out, bool with_gradient) const {
  out.nodes.clear();
  if constexpr (dim == 2)
    if (paths_ && paths_->prepare(x, out.paths)) {
      evaluate_along_paths(x, out, with_gradient);
      return;
    }
  // In a solid with obstacles near x, a node reaches x only along a visible segment.
  // Of tied regions, only the nodes of x's region (x outside every region: all).
  bool shadows = false;
  int region = -1;
  if constexpr (dim == 3) {
    shadows = visibility_ && visibility_->prepare(x, out.shadows);
    if (!node_region_.empty()) region = settings_.region_of(x);
  }
  const auto reaches = [&](Index i, const Point& p) {
    if constexpr (dim == 3)
      return (region < 0 || node_region_[i] == region) &&
             (!shadows || visibility_->visible(p, node_clearance_[i], x, out.shadows));
    else
      return true;
  };
  if (settings_.support == SupportShape::circular) {
    cells_.for_each_in_box(x, max_radius_, [&](Index i, const Point& p) {
      const double a = support_radius(i);
      if ((p - x).squaredNorm() < a * a && reaches(i, p)) out.nodes.push_back(i);
    });
  } else {
    cells_.for_each_in_box(x, max_radius_, [&](Index i, const Point& p) {
      const double a = support_radius(i);
      if (((p - x).cwiseAbs().array() < a).all() && reaches(i, p)) out.nodes.push_back(i);
    });
  }
  select_kernel<dim, false>(settings_)(x, nodes_, settings_, out, with_gradient);
}

template <int dim>
void RKShapeFunctions<dim>::evaluate_along_paths(const Point& x, Values& out, bool with_gradient) const {
  if constexpr (dim == 3) {
    (void)x, (void)out, (void)with_gradient;  // no obstacles in 3D (refused at construction)
  } else {
    // The straight distance never exceeds the path's, so the straight search finds every
    // candidate; the rule then decides which reach x and with what window.
    out.phi.clear();
    out.grad.clear();
    const bool circular = settings_.support == SupportShape::circular;
    cells_.for_each_in_box(x, max_radius_, [&](Index i, const Vec2& p) {
      const double a = support_radius(i);
      if (circular ? (p - x).squaredNorm() >= a * a
                   : (std::abs(p.x() - x.x()) >= a || std::abs(p.y() - x.y()) >= a))
        return;
      Vec2 direction;
      const double d = paths_->distance(p, x, out.paths, direction);
      if (!(d < (circular ? a : std::numeric_limits<double>::infinity()))) return;
      out.nodes.push_back(i);
      if (circular) {
        const WindowValue v = evaluate_window(settings_.window, d / a);
        out.phi.push_back(v.w);
        out.grad.push_back(v.dw / a * direction);
      } else {
        const WindowValue vx = evaluate_window(settings_.window, std::abs(x.x() - p.x()) / a);
        const WindowValue vy = evaluate_window(settings_.window, std::abs(x.y() - p.y()) / a);
        out.phi.push_back(vx.w * vy.w);
        out.grad.emplace_back(std::copysign(1.0 / a, x.x() - p.x()) * vx.dw * vy.w,
                              std::copysign(1.0 / a, x.y() - p.y()) * vy.dw * vx.w);
      }
    });
    select_kernel<dim, true>(settings_)(x, nodes_, settings_, out, with_gradient);
  }
}

template class RKShapeFunctions<2>;
template class RKShapeFunctions<3>;
template std::vector<double> nodal_support_radii(const std::vector<Point<2>>&, double, double, int);
template std::vector<double> nodal_support_radii(const std::vector<Point<3>>&, double, double, int);
template void throw_moment_failure(const Point<2>&, std::size_t, const RKSettings&, double);
template void throw_moment_failure(const Point<3>&, std::size_t, const RKSettings&, double);

}  // namespace mfree

#include "mfree/kernels/rk_shape_functions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

/// Window value and gradient (with respect to x) for the offset (dx, dy) = x - x_I.
struct WindowSample {
  double w, gx, gy;
};

template <Window W>
WindowValue window(double r) {
  if constexpr (W == Window::cubic_bspline) return cubic_bspline(r);
  else return quadratic_spline(r);
}

template <Window W, SupportShape S>
WindowSample sample_window(double dx, double dy, double inv_a) {
  // inv_a: 1 / a_I of the node whose window this is.
  if constexpr (S == SupportShape::circular) {
    const double dist = std::sqrt(dx * dx + dy * dy);
    const WindowValue v = window<W>(dist * inv_a);
    // w'(0) = 0 for both windows, so the node's own gradient is zero, not 0/0.
    const double g = dist > 0.0 ? v.dw * inv_a / dist : 0.0;
    return {v.w, g * dx, g * dy};
  } else {
    const WindowValue vx = window<W>(std::abs(dx) * inv_a);
    const WindowValue vy = window<W>(std::abs(dy) * inv_a);
    const double sx = std::copysign(inv_a, dx), sy = std::copysign(inv_a, dy);
    return {vx.w * vy.w, sx * vx.dw * vy.w, sy * vy.dw * vx.w};
  }
}

/// The per-point RK construction for one basis, window and support (SPEC section 1).
/// `out.nodes` holds the neighbours on entry; phi and grad are filled. With Given, the
/// windows are given on entry instead (supports that respect the domain): out.phi[k] holds
/// w_I and out.grad[k] its gradient, for every neighbour, whether or not with_gradient.
///
/// Per-neighbour quantities are scalars and arrays of them (polynomial_basis.hpp), not
/// small Eigen vectors, and M is summed in its upper triangle: every operand of the three
/// passes stays in registers.
template <int Order, Window W, SupportShape S, bool Given>
void rk_point(const Vec2& x, std::span<const Vec2> nodes, const RKSettings& s, ShapeValues& out,
              bool with_gradient) {
  using Basis = PolynomialBasis<2, Order>;
  constexpr int nb = Basis::size;
  using Terms = typename Basis::Terms;
  using Matrix = typename RKMoment<2, Order>::Matrix;

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
  RKMoment<2, Order> moment;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2& node = nodes[out.nodes[k]];
    const double dx = x.x() - node.x(), dy = x.y() - node.y();
    const double z1 = dx * inv_a, z2 = dy * inv_a;
    out.z[k] = Vec2(z1, z2);
    if constexpr (Given) {
      moment.add(out.phi[k], Basis::value(z1, z2));
    } else {
      const WindowSample ws =
          sample_window<W, S>(dx, dy, per_node ? 1.0 / s.node_radii[out.nodes[k]] : inv_a);
      moment.add(ws.w, Basis::value(z1, z2));
      out.phi[k] = ws.w;
      if (with_gradient) out.grad[k] = Vec2(ws.gx, ws.gy);
    }
  }
  if constexpr (Given)
    if (!with_gradient) out.grad.clear();
  // M^-1 explicitly (3x3 or 6x6): it serves b and both d b / d x_j.
  Matrix minv;
  const double rcond = moment.invert(minv);
  if (!(rcond >= s.rcond_min)) throw_moment_failure(x, n, s, rcond);

  // b = M^-1 H(0), H(0) = e_1 in the shifted basis: phi_I = b . H(z_I) w_I.
  Terms b;
  for (int i = 0; i < nb; ++i) b[i] = minv(i, 0);
  if (!with_gradient) {
    for (std::size_t k = 0; k < n; ++k) out.phi[k] *= dot_terms(b, Basis::value(out.z[k].x(), out.z[k].y()));
    return;
  }

  // Pass 2: (d M / d x_j) b, accumulated as vectors (O(n nb) instead of O(n nb^2)):
  // d M / d x_j = sum_I (d w_I / d x_j) H H^T + w_I (H_,j H^T + H H_,j^T), H_,j = dH/dz_j / a.
  Terms dmb1{}, dmb2{};
  for (std::size_t k = 0; k < n; ++k) {
    const double z1 = out.z[k].x(), z2 = out.z[k].y();
    const Terms h = Basis::value(z1, z2), h1 = Basis::d1(z1, z2), h2 = Basis::d2(z1, z2);
    const double hb = dot_terms(h, b);
    const double w = out.phi[k];
    const double c1 = out.grad[k].x() * hb + w * inv_a * dot_terms(h1, b);
    const double c2 = out.grad[k].y() * hb + w * inv_a * dot_terms(h2, b);
    const double e = w * hb * inv_a;
    for (int i = 0; i < nb; ++i) {
      dmb1[i] += c1 * h[i] + e * h1[i];
      dmb2[i] += c2 * h[i] + e * h2[i];
    }
  }
  // d b / d x_j = -M^-1 (d M / d x_j) b.
  Terms db1{}, db2{};
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < nb; ++i) {
      db1[i] -= minv(i, j) * dmb1[j];
      db2[i] -= minv(i, j) * dmb2[j];
    }

  // Pass 3: phi_I and grad phi_I = (db . H + b . dH) w_I + (b . H) grad w_I.
  for (std::size_t k = 0; k < n; ++k) {
    const double z1 = out.z[k].x(), z2 = out.z[k].y();
    const Terms h = Basis::value(z1, z2);
    const double hb = dot_terms(h, b);
    const double w = out.phi[k];
    const double gx = out.grad[k].x(), gy = out.grad[k].y();
    out.phi[k] = hb * w;
    out.grad[k] = Vec2((dot_terms(db1, h) + dot_terms(b, Basis::d1(z1, z2)) * inv_a) * w + hb * gx,
                       (dot_terms(db2, h) + dot_terms(b, Basis::d2(z1, z2)) * inv_a) * w + hb * gy);
  }
}

using PointKernel = void (*)(const Vec2&, std::span<const Vec2>, const RKSettings&, ShapeValues&,
                             bool);

template <int Order, bool Given>
PointKernel select_kernel(Window w, SupportShape s) {
  if (w == Window::cubic_bspline)
    return s == SupportShape::circular
               ? &rk_point<Order, Window::cubic_bspline, SupportShape::circular, Given>
               : &rk_point<Order, Window::cubic_bspline, SupportShape::tensor, Given>;
  return s == SupportShape::circular
             ? &rk_point<Order, Window::quadratic_spline, SupportShape::circular, Given>
             : &rk_point<Order, Window::quadratic_spline, SupportShape::tensor, Given>;
}

template <bool Given>
PointKernel select_kernel(const RKSettings& s) {
  return s.order == RKOrder::linear ? select_kernel<1, Given>(s.window, s.support)
                                    : select_kernel<2, Given>(s.window, s.support);
}

}  // namespace

RKShapeFunctions::RKShapeFunctions(std::vector<Vec2> nodes, RKSettings settings)
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
  cells_ = CellList<2>(nodes_, 0.5 * max_radius_);
  if (settings_.rule != SupportRule::plain && settings_.obstacles && !settings_.obstacles->empty()) {
    if (settings_.rule == SupportRule::geodesic && settings_.support != SupportShape::circular)
      throw InputError(
          "RK shape functions: the geodesic support rule measures distances along paths and needs "
          "circular supports; tensor supports take the visibility rule");
    paths_ = std::make_shared<const SupportPaths>(*settings_.obstacles, settings_.rule, max_radius_);
  }
}

void throw_moment_failure(const Vec2& x, std::size_t n, const RKSettings& s, double rcond) {
  const int nb = s.order == RKOrder::linear ? 3 : 6;
  const std::string what = rcond >= 0.0
                               ? fmt::format("badly conditioned (reciprocal condition {:.2e} < {:.1e})",
                                             rcond, s.rcond_min)
                               : std::string("singular");
  throw NumericalError(fmt::format(
      "RK moment matrix at point ({:.6g}, {:.6g}) is {}: {} neighbour(s) within the {} support of "
      "radius {:.4g}; a {} basis needs at least {} neighbours, not all on one {}. Increase the support radius "
      "(kernel support factor) or make the cloud denser or more regular near this point.",
      x.x(), x.y(), what, n, to_string(s.support), s.radius, to_string(s.order), nb,
      s.order == RKOrder::linear ? "line" : "conic"));
}

std::vector<double> nodal_support_radii(const std::vector<Vec2>& nodes, double h, double factor,
                                        int k) {
  const CellList<2> cells(nodes, 2.0 * h);
  std::vector<double> radii(nodes.size());
  parallel_blocks(static_cast<Index>(nodes.size()), 1024, [&](Index begin, Index end) {
    std::vector<double> d2;
    for (Index i = begin; i < end; ++i) {
      double r = 2.0 * h;
      for (;;) {  // widen the search until k other nodes are found
        d2.clear();
        cells.for_each_in_box(nodes[i], r, [&](Index j, const Vec2& p) {
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

void RKShapeFunctions::evaluate(const Vec2& x, ShapeValues& out, bool with_gradient) const {
  out.nodes.clear();
  if (paths_ && paths_->prepare(x, out.paths)) {
    evaluate_along_paths(x, out, with_gradient);
    return;
  }
  if (settings_.support == SupportShape::circular) {
    cells_.for_each_in_box(x, max_radius_, [&](Index i, const Vec2& p) {
      const double a = support_radius(i);
      if ((p - x).squaredNorm() < a * a) out.nodes.push_back(i);
    });
  } else {
    cells_.for_each_in_box(x, max_radius_, [&](Index i, const Vec2& p) {
      const double a = support_radius(i);
      if (std::abs(p.x() - x.x()) < a && std::abs(p.y() - x.y()) < a) out.nodes.push_back(i);
    });
  }
  select_kernel<false>(settings_)(x, nodes_, settings_, out, with_gradient);
}

void RKShapeFunctions::evaluate_along_paths(const Vec2& x, ShapeValues& out, bool with_gradient) const {
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
  select_kernel<true>(settings_)(x, nodes_, settings_, out, with_gradient);
}

}  // namespace mfree

#include "mfree/mpm/particle_basis.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "mfree/core/error.hpp"
#include "mfree/mpm/grid_transfer.hpp"

namespace mfree {

const NameTable<MPMMethodChoice>& mpm_method_names() {
  static const NameTable<MPMMethodChoice> table{{"classic", {MPMMethod::classic, 1}},
                                                {"ugimp", {MPMMethod::ugimp, 1}},
                                                {"cpgimp", {MPMMethod::cpgimp, 1}},
                                                {"cpdi", {MPMMethod::cpdi, 1}},
                                                {"qcpdi", {MPMMethod::qcpdi, 1}},
                                                {"cpdi2", {MPMMethod::cpdi2, 1}},
                                                {"bspline", {MPMMethod::bspline, 2}},
                                                {"bspline_cubic", {MPMMethod::bspline, 3}},
                                                {"bspline_cpgimp", {MPMMethod::bspline_cpgimp, 2}},
                                                {"bspline_cpgimp_cubic", {MPMMethod::bspline_cpgimp, 3}},
                                                {"bspline_mls", {MPMMethod::bspline_mls, 2}}};
  return table;
}

std::string_view to_string(MPMMethod m) {
  for (const auto& [name, choice] : mpm_method_names().entries())
    if (choice.method == m) return name;
  throw std::logic_error("MPM: a method without a name");
}

bool uses_domains(MPMMethod m) {
  switch (m) {
    case MPMMethod::ugimp:
    case MPMMethod::cpgimp:
    case MPMMethod::cpdi:
    case MPMMethod::qcpdi:
    case MPMMethod::cpdi2:
    case MPMMethod::bspline_cpgimp:
      return true;
    case MPMMethod::classic:
    case MPMMethod::bspline:
    case MPMMethod::bspline_mls: return false;
  }
  throw std::logic_error("MPM: a method without a kind");
}

bool is_bspline(MPMMethod m) {
  return m == MPMMethod::bspline || m == MPMMethod::bspline_cpgimp || m == MPMMethod::bspline_mls;
}
int grid_padding(MPMMethod m) { return uses_domains(m) && !is_bspline(m) ? 1 : 0; }

namespace {

/// int_{-1}^{s} max(0, 1 - |t|) dt: the antiderivative of the unit hat.
double hat_integral(double s) {
  if (s <= -1.0) return 0.0;
  if (s <= 0.0) return 0.5 * (1.0 + s) * (1.0 + s);
  if (s < 1.0) return 1.0 - 0.5 * (1.0 - s) * (1.0 - s);
  return 1.0;
}
double hat(double s) { return std::max(0.0, 1.0 - std::abs(s)); }

/// The GIMPs in one direction: averages over [x - l, x + l] of the hats of a degree-1 axis and
/// the averages of their derivatives, (N_i(x + l) - N_i(x - l)) / (2 l), in a slot of n hats.
template <int n>
struct GimpAxis {
  int first = 0;
  std::array<double, n> value{};
  std::array<double, n> derivative{};
};
/// False (and g untouched) when the interval touches more than n hats: the hats i with
/// x_i - h < x + l and x_i + h > x - l, from floor((x - l - lo) / h) to ceil((x + l - lo) / h).
template <int n>
bool gimp_axis(const BSplineAxis& a, double x, double l, GimpAxis<n>& g) {
  const double h = a.spacing();
  const int touched = std::max(0, static_cast<int>(std::floor((x - l - a.lo()) / h)));
  const int last = std::min(a.size() - 1, static_cast<int>(std::ceil((x + l - a.lo()) / h)));
  if (last - touched >= n) return false;
  // A slot of n hats, all on the axis: at its far end the slot starts before the first hat
  // the domain touches, and the extra hats keep zero weight (a padded axis has at least 4).
  g.first = std::min(touched, a.size() - n);
  for (int i = touched; i <= last; ++i) {
    const double node = a.lo() + i * h;  // = a.node(i): a hat's Greville node is its peak, a knot
    const double sa = (x - l - node) / h, sb = (x + l - node) / h;
    g.value[i - g.first] = h / (2.0 * l) * (hat_integral(sb) - hat_integral(sa));
    g.derivative[i - g.first] = (hat(sb) - hat(sa)) / (2.0 * l);
  }
  return true;
}

/// B-spline cpGIMP in one direction: the averages over [a, b] = [x - l, x + l], clipped to the
/// axis' ends, of the functions N_i of a degree-p axis, (1 / (b - a)) int_a^b N_i, and of their
/// derivatives, (N_i(b) - N_i(a)) / (b - a), in a slot of p + 2 functions. Each cell's piece of
/// [a, b] is integrated on that cell's polynomials by two-point Gauss–Legendre, exact for
/// p <= 3. False (and g untouched) when [a, b] meets more than two cells.
template <int p>
bool bspline_average_axis(const BSplineAxis& ax, double x, double l, GimpAxis<p + 2>& g) {
  constexpr int n = p + 2;
  const double h = ax.spacing();
  const double a = std::max(ax.lo(), x - l), b = std::min(ax.hi(), x + l);
  const int c0 = ax.cell_of(a);
  const int c1 = std::clamp(static_cast<int>(std::ceil((b - ax.lo()) / h)) - 1, c0, ax.cells() - 1);
  if (c1 - c0 > 1) return false;
  g.first = std::min(c0, ax.size() - n);  // at the far end the slot starts a function early
  const double inv = 1.0 / (b - a);
  constexpr double r = 0.28867513459481287;  // the Gauss points mid -+ (e - s) / (2 sqrt(3))
  for (int c = c0; c <= c1; ++c) {
    const double s = std::max(a, ax.lo() + c * h), e = std::min(b, ax.lo() + (c + 1) * h);
    if (!(e > s)) continue;
    const double mid = 0.5 * (s + e), w = 0.5 * (e - s) * inv;
    for (const double y : {mid - r * (e - s), mid + r * (e - s)}) {
      const BSplineAxis::Values v = ax.evaluate_on<p>(c, y);
      for (int k = 0; k <= p; ++k) g.value[v.first - g.first + k] += w * v.value[k];
    }
  }
  const BSplineAxis::Values va = ax.evaluate_on<p>(c0, a), vb = ax.evaluate_on<p>(c1, b);
  for (int k = 0; k <= p; ++k) {
    g.derivative[va.first - g.first + k] -= inv * va.value[k];
    g.derivative[vb.first - g.first + k] += inv * vb.value[k];
  }
  return true;
}

NumericalError domain_too_large(const char* method, const Vec2& x, const Vec2& half, int n, double h) {
  return NumericalError(
      fmt::format("{}: the particle domain at ({:.6g}, {:.6g}) with half sizes ({:.4g}, {:.4g}) touches more "
                  "than the {} functions "
                  "per axis of its slot (cells of size {:.4g}): it has grown too large; use more particles "
                  "per cell or another method",
                  method, x.x(), x.y(), half.x(), half.y(), n, h));
}

}  // namespace

ParticleBasis::ParticleBasis(MPMMethod method, const Grid& grid) : method_(method), grid_(grid) {
  const int p = grid.x_axis().degree();
  if (is_bspline(method) != (p >= 2))
    throw InputError(fmt::format("MPM: method {} does not use degree-{} functions", to_string(method), p));
  if (grid_padding(method) > 0 && grid.extent().lo.x() >= grid.box().lo.x())
    throw InputError(fmt::format("MPM: method {} needs a grid padded by one cell", to_string(method)));
  switch (method) {
    case MPMMethod::ugimp: axis_ = 3; break;
    case MPMMethod::cpgimp: axis_ = 4; break;
    case MPMMethod::bspline_cpgimp:
      axis_ = p + 2;
      break;
    case MPMMethod::cpdi:
    case MPMMethod::cpdi2:
    case MPMMethod::qcpdi: axis_ = 0; break;
    default: axis_ = p + 1;
  }
  if (method == MPMMethod::bspline_cpgimp && grid.x_axis().size() < axis_)
    throw InputError(fmt::format("MPM: method {} needs at least two cells per axis", to_string(method)));
  stride_ = method == MPMMethod::qcpdi ? 32 : axis_ == 0 ? 16 : axis_ * axis_;
}

void ParticleBasis::resize(WeightTable& table, Index points) const { table.resize(points, stride_, axis_, grid_.nx()); }

void ParticleBasis::check_on_grid(const Vec2& y, const char* what, const Vec2& particle) const {
  const Box e = grid_.extent();
  if (e.contains(y)) return;
  const std::string of = y == particle ? std::string()
                                        : fmt::format(" (of the particle at ({:.6g}, {:.6g}))", particle.x(), particle.y());
  throw NumericalError(fmt::format("MPM: {} at ({:.6g}, {:.6g}){} left the grid [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]",
                                   what, y.x(), y.y(), of, e.lo.x(), e.hi.x(), e.lo.y(), e.hi.y()));
}

template <int p>
void ParticleBasis::point_weights(const Vec2& x, WeightTable& table, Index q) const {
  const BSplineAxis::Values vx = grid_.x_axis().evaluate_as<p>(x.x());
  const BSplineAxis::Values vy = grid_.y_axis().evaluate_as<p>(x.y());
  table.set_tensor<p + 1>(q, grid_.index(vx.first, vy.first), vx, vy);  // N_ij = N_i N_j, eqs. (4)-(5)
}

template <int n>
void ParticleBasis::gimp_weights(const Vec2& x, const Vec2& half, WeightTable& table, Index q) const {
  const bool stretched = method_ == MPMMethod::cpgimp;
  const char* method = stretched ? "cpGIMP" : "uGIMP";
  const char* what = stretched ? "a cpGIMP particle domain" : "a uGIMP particle domain";
  check_on_grid(x - half, what, x);
  check_on_grid(x + half, what, x);
  GimpAxis<n> gx, gy;
  if (!gimp_axis<n>(grid_.x_axis(), x.x(), half.x(), gx) || !gimp_axis<n>(grid_.y_axis(), x.y(), half.y(), gy))
    throw domain_too_large(method, x, half, n, grid_.spacing());
  table.set_tensor<n>(q, grid_.index(gx.first, gy.first), gx, gy);  // the averages factor by axis
}

template <int p>
void ParticleBasis::bspline_gimp_weights(const Vec2& x, const Vec2& half, WeightTable& table, Index q) const {
  check_on_grid(x, "a particle", x);  // the domain is clipped to the grid, the walls
  GimpAxis<p + 2> gx, gy;
  if (!bspline_average_axis<p>(grid_.x_axis(), x.x(), half.x(), gx) ||
      !bspline_average_axis<p>(grid_.y_axis(), x.y(), half.y(), gy))
    throw domain_too_large("B-spline cpGIMP", x, half, p + 2, grid_.spacing());
  table.set_tensor<p + 2>(q, grid_.index(gx.first, gy.first), gx, gy);
}

template <int n>
void ParticleBasis::node_sum(const DomainNodes<n>& nodes, const Vec2& x, const char* what, WeightTable& table,
                             Index q) const {
  const WeightSlot out = table.slot(q);
  std::fill(out.node, out.node + stride_, 0);
  std::fill(out.S, out.S + stride_, 0.0);
  std::fill(out.G, out.G + stride_, Vec2::Zero());
  for (const Vec2& y : nodes.point) check_on_grid(y, what, x);
  const double inv_volume = 1.0 / nodes.volume;
  int used = 0;
  for (int k = 0; k < n; ++k) {
    const BSplineAxis::Values vx = grid_.x_axis().evaluate_as<1>(nodes.point[k].x());
    const BSplineAxis::Values vy = grid_.y_axis().evaluate_as<1>(nodes.point[k].y());
    const Vec2 g = inv_volume * nodes.gradient[k];
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        const Index node = grid_.index(vx.first + a, vy.first + b);
        const double N = vx.value[a] * vy.value[b];
        int e = 0;
        while (e < used && out.node[e] != node) ++e;
        if (e == used) out.node[used++] = node;  // at most n nodes x 4 hats = stride
        out.S[e] += nodes.weight[k] * N;         // sum_k w_k N_i(y_k)
        out.G[e] += N * g;                       // (1 / V) sum_k N_i(y_k) int grad M_k
      }
  }
}

void ParticleBasis::evaluate_quadrilateral(const DomainCorners& c, const Vec2& x, WeightTable& table, Index q) const {
  if (method_ == MPMMethod::cpdi2)
    return node_sum<4>(bilinear_nodes(c, x, "CPDI2"), x, "a CPDI2 particle corner", table, q);
  if (method_ == MPMMethod::cpdi)
    return node_sum<4>(bilinear_nodes(c, x, "CPDI"), x, "a CPDI particle corner", table, q);
  throw std::logic_error("MPM: only CPDI and CPDI2 weigh a quadrilateral's corners");
}

Vec2 ParticleBasis::stretched_half(const Vec2& x, const Mat2& F, const Vec2& half) const {
  const Vec2 l = half.cwiseProduct(F.diagonal());
  if (!(l.x() > 0.0 && l.y() > 0.0))
    throw NumericalError(fmt::format("cpGIMP: the particle domain at ({:.6g}, {:.6g}) has stretches F_xx = {:.4g}, "
                                     "F_yy = {:.4g}: a half size is not positive",
                                     x.x(), x.y(), F(0, 0), F(1, 1)));
  return l;
}

void ParticleBasis::evaluate(const Vec2& x, const Mat2& F, const Vec2& half, WeightTable& table, Index q) const {
  switch (method_) {
    case MPMMethod::ugimp: return gimp_weights<3>(x, half, table, q);
    case MPMMethod::cpgimp: return gimp_weights<4>(x, stretched_half(x, F, half), table, q);
    case MPMMethod::bspline_cpgimp:
      return axis_ == 4 ? bspline_gimp_weights<2>(x, stretched_half(x, F, half), table, q)
                        : bspline_gimp_weights<3>(x, stretched_half(x, F, half), table, q);
    case MPMMethod::cpdi: return evaluate_quadrilateral(parallelogram_corners(x, F, half), x, table, q);
    case MPMMethod::qcpdi: return node_sum<8>(serendipity_nodes(x, F, half), x, "a qCPDI particle node", table, q);
    case MPMMethod::cpdi2: throw std::logic_error("MPM: CPDI2's weights come from its tracked corners");
    default:
      check_on_grid(x, "a particle", x);
      switch (axis_) {  // once per particle, not per axis
        case 2: return point_weights<1>(x, table, q);
        case 3: return point_weights<2>(x, table, q);
        default: return point_weights<3>(x, table, q);
      }
  }
}

void ParticleBasis::evaluate(const Particles& P, Index p, WeightTable& table, Index q) const {
  if (method_ == MPMMethod::cpdi2) return evaluate_quadrilateral(P.corners[p], P.position[p], table, q);
  evaluate(P.position[p], P.deformation[p], uses_domains(method_) ? P.half_size[p] : Vec2::Zero(), table, q);
}

DomainCorners ParticleBasis::domain_corners(const Particles& P, Index p) const {
  const Vec2& x = P.position[p];
  switch (method_) {
    case MPMMethod::ugimp: return parallelogram_corners(x, Mat2::Identity(), P.half_size[p]);
    case MPMMethod::cpgimp:
    case MPMMethod::bspline_cpgimp:
      return parallelogram_corners(x, Mat2(P.deformation[p].diagonal().asDiagonal()), P.half_size[p]);
    case MPMMethod::cpdi:
    case MPMMethod::qcpdi: return parallelogram_corners(x, P.deformation[p], P.half_size[p]);
    case MPMMethod::cpdi2: return P.corners[p];
    default: throw std::logic_error("MPM: a method without particle domains");
  }
}

Vec2 ParticleBasis::hat_interpolate(const Vec2& x, const std::vector<Vec2>& nodal) const {
  const BSplineAxis::Values vx = grid_.x_axis().evaluate_as<1>(x.x());
  const BSplineAxis::Values vy = grid_.y_axis().evaluate_as<1>(x.y());
  Vec2 v = Vec2::Zero();
  for (int b = 0; b < 2; ++b)
    for (int a = 0; a < 2; ++a) v += vx.value[a] * vy.value[b] * nodal[grid_.index(vx.first + a, vy.first + b)];
  return v;
}

}  // namespace mfree

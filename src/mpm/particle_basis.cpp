#include "mfree/mpm/particle_basis.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "mfree/core/error.hpp"
#include "mfree/mpm/grid_transfer.hpp"

namespace mfree {

const NameTable<MPMMethodChoice>& mpm_method_names() {
  static const NameTable<MPMMethodChoice> table{
      {"classic", {MPMMethod::classic, 1}},  {"ugimp", {MPMMethod::ugimp, 1}},
      {"cpdi", {MPMMethod::cpdi, 1}},        {"bspline", {MPMMethod::bspline, 2}},
      {"bspline_cubic", {MPMMethod::bspline, 3}}, {"bspline_mls", {MPMMethod::bspline_mls, 2}}};
  return table;
}

std::string_view to_string(MPMMethod m) {
  for (const auto& [name, choice] : mpm_method_names().entries())
    if (choice.method == m) return name;
  throw std::logic_error("MPM: a method without a name");
}

int grid_padding(MPMMethod m) { return m == MPMMethod::ugimp || m == MPMMethod::cpdi ? 1 : 0; }
bool is_bspline(MPMMethod m) { return m == MPMMethod::bspline || m == MPMMethod::bspline_mls; }

namespace {

/// int_{-1}^{s} max(0, 1 - |t|) dt: the antiderivative of the unit hat.
double hat_integral(double s) {
  if (s <= -1.0) return 0.0;
  if (s <= 0.0) return 0.5 * (1.0 + s) * (1.0 + s);
  if (s < 1.0) return 1.0 - 0.5 * (1.0 - s) * (1.0 - s);
  return 1.0;
}
double hat(double s) { return std::max(0.0, 1.0 - std::abs(s)); }

/// uGIMP in one direction: averages over [x - l, x + l] of the hats of a degree-1 axis and
/// the averages of their derivatives, (N_i(x + l) - N_i(x - l)) / (2 l).
struct GimpAxis {
  int first = 0;
  std::array<double, 3> value{};
  std::array<double, 3> derivative{};
};
GimpAxis gimp_axis(const BSplineAxis& a, double x, double l) {
  const double h = a.spacing();
  const int touched = std::max(0, static_cast<int>(std::floor((x - l - a.lo()) / h)));
  const int last = std::min(a.size() - 1, static_cast<int>(std::floor((x + l - a.lo()) / h)) + 1);
  if (last - touched >= 3)
    throw NumericalError(fmt::format("uGIMP: a particle domain of half size {} is wider than a cell of size {}", l, h));
  GimpAxis g;
  // A slot of three hats, all on the axis: at its far end the slot starts one hat before the
  // first the domain touches, and that extra hat keeps zero weight (a padded axis has at least
  // 4 hats).
  g.first = std::min(touched, a.size() - 3);
  for (int i = touched; i <= last; ++i) {
    const double node = a.lo() + i * h;  // = a.node(i): a hat's Greville node is its peak, a knot
    const double sa = (x - l - node) / h, sb = (x + l - node) / h;
    g.value[i - g.first] = h / (2.0 * l) * (hat_integral(sb) - hat_integral(sa));
    g.derivative[i - g.first] = (hat(sb) - hat(sa)) / (2.0 * l);
  }
  return g;
}

Vec2 perp(const Vec2& d) { return {d.y(), -d.x()}; }

}  // namespace

ParticleBasis::ParticleBasis(MPMMethod method, const Grid& grid) : method_(method), grid_(grid) {
  const int p = grid.x_axis().degree();
  if (is_bspline(method) != (p >= 2))
    throw InputError(fmt::format("MPM: method {} does not use degree-{} functions", to_string(method), p));
  if (grid_padding(method) > 0 && grid.extent().lo.x() >= grid.box().lo.x())
    throw InputError(fmt::format("MPM: method {} needs a grid padded by one cell", to_string(method)));
  axis_ = method == MPMMethod::ugimp ? 3 : method == MPMMethod::cpdi ? 0 : p + 1;
  stride_ = method == MPMMethod::cpdi ? 16 : axis_ * axis_;
}

void ParticleBasis::resize(WeightTable& table, Index points) const { table.resize(points, stride_, axis_, grid_.nx()); }

void ParticleBasis::check_on_grid(const Vec2& x, const char* what) const {
  const Box e = grid_.extent();
  if (!(e.contains(x)))
    throw NumericalError(fmt::format("MPM: {} at ({:.6g}, {:.6g}) left the grid [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]",
                                     what, x.x(), x.y(), e.lo.x(), e.hi.x(), e.lo.y(), e.hi.y()));
}

template <int p>
void ParticleBasis::point_weights(const Vec2& x, WeightTable& table, Index q) const {
  const BSplineAxis::Values vx = grid_.x_axis().evaluate_as<p>(x.x());
  const BSplineAxis::Values vy = grid_.y_axis().evaluate_as<p>(x.y());
  table.set_tensor<p + 1>(q, grid_.index(vx.first, vy.first), vx, vy);  // N_ij = N_i N_j, eqs. (4)-(5)
}

void ParticleBasis::gimp_weights(const Vec2& x, const Vec2& half, WeightTable& table, Index q) const {
  check_on_grid(x - half, "a uGIMP particle domain");
  check_on_grid(x + half, "a uGIMP particle domain");
  const GimpAxis gx = gimp_axis(grid_.x_axis(), x.x(), half.x());
  const GimpAxis gy = gimp_axis(grid_.y_axis(), x.y(), half.y());
  table.set_tensor<3>(q, grid_.index(gx.first, gy.first), gx, gy);  // the averages factor by axis
}

void ParticleBasis::cpdi_weights(const Vec2& x, const Mat2& F, const Vec2& half, WeightTable& table, Index q) const {
  const WeightSlot out = table.slot(q);
  const Vec2 r1 = F.col(0) * half.x(), r2 = F.col(1) * half.y();
  const std::array<Vec2, 4> c{x - r1 - r2, x + r1 - r2, x + r1 + r2, x - r1 + r2};  // counter-clockwise
  const double volume = 4.0 * (r1.x() * r2.y() - r1.y() * r2.x());
  if (!(volume > 0.0))
    throw NumericalError(fmt::format("CPDI: the particle domain at ({:.6g}, {:.6g}) has area {:.3e} <= 0 (J <= 0)",
                                     x.x(), x.y(), volume));
  std::fill(out.node, out.node + stride_, 0);
  std::fill(out.S, out.S + stride_, 0.0);
  std::fill(out.G, out.G + stride_, Vec2::Zero());
  int used = 0;
  for (int k = 0; k < 4; ++k) {
    check_on_grid(c[k], "a CPDI particle corner");
    const Vec2 normal = 0.5 * perp(c[(k + 1) % 4] - c[(k + 3) % 4]);
    const BSplineAxis::Values vx = grid_.x_axis().evaluate(c[k].x());
    const BSplineAxis::Values vy = grid_.y_axis().evaluate(c[k].y());
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        const Index node = grid_.index(vx.first + a, vy.first + b);
        const double N = vx.value[a] * vy.value[b];
        int e = 0;
        while (e < used && out.node[e] != node) ++e;
        if (e == used) out.node[used++] = node;  // at most 4 corners x 4 hats = stride
        out.S[e] += 0.25 * N;
        out.G[e] += N / volume * normal;
      }
  }
}

void ParticleBasis::evaluate(const Vec2& x, const Mat2& F, const Vec2& half, WeightTable& table, Index q) const {
  switch (method_) {
    case MPMMethod::ugimp: return gimp_weights(x, half, table, q);
    case MPMMethod::cpdi: return cpdi_weights(x, F, half, table, q);
    default:
      check_on_grid(x, "a particle");
      switch (axis_) {  // once per particle, not per axis
        case 2: return point_weights<1>(x, table, q);
        case 3: return point_weights<2>(x, table, q);
        default: return point_weights<3>(x, table, q);
      }
  }
}

}  // namespace mfree

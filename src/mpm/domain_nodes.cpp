#include "mfree/mpm/domain_nodes.hpp"

#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

Vec2 perp(const Vec2& d) { return {d.y(), -d.x()}; }
double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

DomainCorners parallelogram_corners(const Vec2& x, const Mat2& F, const Vec2& half) {
  const Vec2 r1 = F.col(0) * half.x(), r2 = F.col(1) * half.y();
  return {x - r1 - r2, x + r1 - r2, x + r1 + r2, x - r1 + r2};
}

DomainNodes<4> bilinear_nodes(const DomainCorners& c, const Vec2& x, const char* method) {
  DomainNodes<4> out;
  std::array<double, 4> J;
  for (int k = 0; k < 4; ++k) {
    J[k] = 0.25 * cross(c[(k + 1) % 4] - c[k], c[(k + 3) % 4] - c[k]);
    out.volume += J[k];
  }
  // J is linear in (xi, eta): positive at the four corners, it is positive everywhere.
  for (int k = 0; k < 4; ++k)
    if (!(J[k] > 0.0))
      throw NumericalError(fmt::format(
          "{}: the domain of the particle at ({:.6g}, {:.6g}) is not a convex quadrilateral (area {:.4g}; corners "
          "({:.6g}, {:.6g}), ({:.6g}, {:.6g}), ({:.6g}, {:.6g}), ({:.6g}, {:.6g}); Jacobian {:.4g} <= 0 at corner {})",
          method, x.x(), x.y(), out.volume, c[0].x(), c[0].y(), c[1].x(), c[1].y(), c[2].x(), c[2].y(), c[3].x(),
          c[3].y(), J[k], k));
  for (int k = 0; k < 4; ++k) {
    out.point[k] = c[k];
    out.weight[k] = 1.0 / 6.0 + J[k] / (3.0 * out.volume);
    out.gradient[k] = 0.5 * perp(c[(k + 1) % 4] - c[(k + 3) % 4]);
  }
  return out;
}

DomainNodes<8> serendipity_nodes(const Vec2& x, const Mat2& F, const Vec2& half) {
  DomainNodes<8> out;
  out.volume = 4.0 * half.x() * half.y() * F.determinant();
  if (!(out.volume > 0.0))
    throw NumericalError(fmt::format("qCPDI: the particle domain at ({:.6g}, {:.6g}) has area {:.4g} <= 0 (J <= 0)",
                                     x.x(), x.y(), out.volume));
  const DomainCorners c = parallelogram_corners(x, F, half);
  for (int k = 0; k < 4; ++k) {
    const Vec2& next = c[(k + 1) % 4];
    out.point[k] = c[k];
    out.point[k + 4] = 0.5 * (c[k] + next);
    out.weight[k] = -1.0 / 12.0;
    out.weight[k + 4] = 1.0 / 3.0;
    out.gradient[k] = perp(next - c[(k + 3) % 4]) / 6.0;
    out.gradient[k + 4] = 2.0 / 3.0 * perp(next - c[k]);
  }
  return out;
}

}  // namespace mfree

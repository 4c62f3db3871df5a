#pragma once
// Random particle domains for the MPM basis tests: deformation gradients with det F above a
// floor, and convex quadrilaterals (CPDI2's domains) near a parallelogram.

#include <Eigen/LU>
#include <random>

#include "mfree/mpm/domain_nodes.hpp"

namespace mfree::testing {

/// F = I + spread * (uniform in [-1, 1] per entry), drawn again until det F >= 0.3 and both
/// F_ii >= 0.3 (so that every method's domain keeps a positive size).
inline Mat2 random_deformation(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    Mat2 F;
    F << 1 + spread * u(rng), spread * u(rng), spread * u(rng), 1 + spread * u(rng);
    if (F.determinant() >= 0.3 && F(0, 0) >= 0.3 && F(1, 1) >= 0.3) return F;
  }
}

/// The parallelogram x + F (+-l_x, +-l_y) with each corner moved by up to a third of the
/// smaller half size, drawn again until it is strictly convex.
inline DomainCorners random_quadrilateral(std::mt19937_64& rng, const Vec2& x, const Mat2& F, const Vec2& half) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double move = half.minCoeff() / 3.0;
  for (;;) {
    DomainCorners c = parallelogram_corners(x, F, half);
    for (Vec2& y : c) y += move * Vec2(u(rng), u(rng));
    bool convex = true;
    for (int k = 0; k < 4; ++k) {
      const Vec2 a = c[(k + 1) % 4] - c[k], b = c[(k + 3) % 4] - c[k];
      convex = convex && a.x() * b.y() - a.y() * b.x() > 0.0;
    }
    if (convex) return c;
  }
}

/// The area centroid of a simple polygon (shoelace formula).
inline Vec2 polygon_centroid(const DomainCorners& c) {
  double area = 0.0;
  Vec2 moment = Vec2::Zero();
  for (int k = 0; k < 4; ++k) {
    const Vec2 &a = c[k], &b = c[(k + 1) % 4];
    const double cross = a.x() * b.y() - a.y() * b.x();
    area += 0.5 * cross;
    moment += cross * (a + b) / 6.0;
  }
  return moment / area;
}

}  // namespace mfree::testing

#include "mfree/geometry/polygon_integrals.hpp"

#include <cstddef>

namespace mfree {

// The sums are taken about the first vertex r: the shoelace terms then carry coordinates of
// the ring's own size instead of its distance from the origin, which keeps the cancellation
// error small for small rings far from the origin (clipped cells, Voronoi cells).
// Translating back: int x dA = int (x - r) dA + r A.

double ring_area(const Ring& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return 0.0;
  const Vec2 r = ring[0];
  double twice_area = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec2 p = ring[i] - r;
    const Vec2 q = ring[i + 1] - r;
    twice_area += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice_area;
}

Vec2 ring_first_moment(const Ring& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return Vec2::Zero();
  const Vec2 r = ring[0];
  double twice_area = 0.0;
  Vec2 six_moment = Vec2::Zero();
  // Edges touching r have c_i = 0 in shifted coordinates, so only edges (i, i+1) with
  // 1 <= i <= n-2 contribute.
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec2 p = ring[i] - r;
    const Vec2 q = ring[i + 1] - r;
    const double c = p.x() * q.y() - q.x() * p.y();
    twice_area += c;
    six_moment += (p + q) * c;
  }
  return six_moment / 6.0 + r * (0.5 * twice_area);
}

Box ring_bounding_box(const Ring& ring) {
  Box b{ring[0], ring[0]};
  for (const Vec2& x : ring) {
    b.lo = b.lo.cwiseMin(x);
    b.hi = b.hi.cwiseMax(x);
  }
  return b;
}

}  // namespace mfree

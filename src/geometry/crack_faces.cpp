#include "mfree/geometry/crack_faces.hpp"

#include <algorithm>

namespace mfree {

namespace {

/// The unit normal (left of a -> b) of the crack segment x lies on, within `tolerance` and
/// not within it of a tip; zero when there is none.
Vec2 crack_normal_at(const Domain& domain, const Vec2& x, double tolerance) {
  for (const Crack& c : domain.cracks()) {
    if ((c.tip[0] && (x - c.points.front()).norm() <= tolerance) ||
        (c.tip[1] && (x - c.points.back()).norm() <= tolerance))
      return Vec2::Zero();
    for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
      const Vec2 &a = c.points[i], &b = c.points[i + 1];
      const Vec2 d = b - a;
      const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      if ((a + t * d - x).norm() <= tolerance) return Vec2(-d.y(), d.x()).normalized();
    }
  }
  return Vec2::Zero();
}

}  // namespace

std::vector<Vec2> split_on_cracks(const Domain& domain, const std::vector<Vec2>& points, double h,
                                  std::vector<Index>* origin) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  if (origin) origin->clear();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2 n = domain.cracks().empty() ? Vec2(Vec2::Zero())
                                           : crack_normal_at(domain, points[i], crack_tolerance * h);
    const int copies = n.isZero() ? 1 : 2;
    for (int k = 0; k < copies; ++k) {
      out.push_back(copies == 1 ? points[i] : Vec2(points[i] + (k == 0 ? 1.0 : -1.0) * crack_offset * h * n));
      if (origin) origin->push_back(static_cast<Index>(i));
    }
  }
  return out;
}

Vec2 inside_face(const BoundarySegment& segment, const Vec2& x, double h) {
  return segment.crack < 0 ? x : Vec2(x - crack_offset * h * segment.normal);
}

}  // namespace mfree

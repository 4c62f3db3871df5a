#include "mfree/geometry/crack_faces.hpp"

#include <algorithm>

#include "mfree/geometry/boundary_selection.hpp"

namespace mfree {

namespace {

/// Where a point lies on a crack: the unit normal of its segment (left of a -> b) and the
/// unit direction from the nearer end of the segment into it; zero normal when off every
/// crack (beyond `tolerance`) or at a tip.
struct OnCrack {
  Vec2 normal = Vec2::Zero();
  Vec2 inward = Vec2::Zero();
};

OnCrack crack_at(const Domain& domain, const Vec2& x, double tolerance) {
  for (const Crack& c : domain.cracks()) {
    if ((c.tip[0] && (x - c.points.front()).norm() <= tolerance) ||
        (c.tip[1] && (x - c.points.back()).norm() <= tolerance))
      return {};
    for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
      const Vec2 &a = c.points[i], &b = c.points[i + 1];
      const Vec2 d = b - a;
      const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      if ((a + t * d - x).norm() <= tolerance)
        return {Vec2(-d.y(), d.x()).normalized(), (t < 0.5 ? 1.0 : -1.0) * d.normalized()};
    }
  }
  return {};
}

}  // namespace

std::vector<Vec2> split_on_cracks(const Domain& domain, const std::vector<Vec2>& points, double h,
                                  std::vector<Index>* origin) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  if (origin) origin->clear();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const OnCrack on = domain.cracks().empty() ? OnCrack{} : crack_at(domain, points[i], crack_tolerance * h);
    const int copies = on.normal.isZero() ? 1 : 2;
    for (int k = 0; k < copies; ++k) {
      Vec2 x =
          copies == 1 ? points[i] : Vec2(points[i] + (k == 0 ? 1.0 : -1.0) * crack_offset * h * on.normal);
      // At a mouth where the crack meets the boundary at a slant, the offset across the crack
      // can leave the domain on one side: that copy steps along the crack into the domain.
      for (int step = 1; copies == 2 && step <= 64 && !domain.contains(x); step *= 2)
        x += step * crack_offset * h * on.inward;
      out.push_back(x);
      if (origin) origin->push_back(static_cast<Index>(i));
    }
  }
  return out;
}

Vec2 inside_face(const BoundarySegment& segment, const Vec2& x, double h) {
  return segment.crack < 0 ? x : Vec2(x - crack_offset * h * segment.normal);
}

bool crack_crosses(const Domain& domain, const Box& box) {
  if (domain.cracks().empty() || !domain.boundary_near(box)) return false;
  const Vec2 pad = 1e-9 * box.size();
  const Vec2 lo = box.lo + pad, hi = box.hi - pad;
  for (const int k : domain.boundary_segments_near(box)) {
    const BoundarySegment& s = domain.boundary()[k];
    if (s.crack >= 0 && !domain.cracks()[s.crack].interface() && segment_in_box(s.a, s.b, Box{lo, hi}))
      return true;
  }
  return false;
}

}  // namespace mfree

#include "mfree/geometry/crack_faces.hpp"

#include <algorithm>
#include <optional>

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
    const std::size_t n = c.points.size();
    const auto left_normal = [&](std::size_t i) {
      const Vec2 d = c.points[i + 1] - c.points[i];
      return Vec2(Vec2(-d.y(), d.x()).normalized());
    };
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const Vec2 &a = c.points[i], &b = c.points[i + 1];
      const Vec2 d = b - a;
      const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      if ((a + t * d - x).norm() > tolerance) continue;
      // At an inner vertex the copies go along the bisector of the faces' wedges (the sum of
      // the two segments' left normals): along one segment's normal, a copy at a sharp corner
      // of an inclusion would leave its face's wedge for the other side.
      const bool closed = c.closed();
      std::optional<std::size_t> other;  // the segment meeting this one at the vertex
      if (t == 0.0 && (i > 0 || closed)) other = i > 0 ? i - 1 : n - 2;
      if (t == 1.0 && (i + 2 < n || closed)) other = i + 2 < n ? i + 1 : 0;
      const Vec2 normal = other ? Vec2((left_normal(i) + left_normal(*other)).normalized()) : left_normal(i);
      return {normal, (t < 0.5 ? 1.0 : -1.0) * d.normalized()};
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

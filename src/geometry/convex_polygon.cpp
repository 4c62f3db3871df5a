#include "mfree/geometry/convex_polygon.hpp"

#include <algorithm>

namespace mfree {

ConvexPolygon clip_half_space(const ConvexPolygon& p, int axis, double value, bool below) {
  if (p.size() < 3) return {};
  const auto inside = [&](const Point<3>& x) { return below ? x[axis] <= value : x[axis] >= value; };
  ConvexPolygon out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point<3>& a = p[i];
    const Point<3>& b = p[(i + 1) % p.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      // The crossing of edge a -> b, on the plane exactly.
      Point<3> x = a + (value - a[axis]) / (b[axis] - a[axis]) * (b - a);
      x[axis] = value;
      out.push_back(x);
    }
  }
  if (out.size() < 3) out.clear();
  return out;
}

ConvexPolygon clip_to_box(ConvexPolygon p, const AlignedBox<3>& box) {
  for (int axis = 0; axis < 3 && !p.empty(); ++axis) {
    p = clip_half_space(p, axis, box.min()[axis], false);
    p = clip_half_space(p, axis, box.max()[axis], true);
  }
  return p;
}

std::vector<ConvexPolygon> split_by_box(const ConvexPolygon& p, const AlignedBox<3>& box) {
  std::vector<ConvexPolygon> pieces(1);
  ConvexPolygon rest = p;
  for (int axis = 0; axis < 3 && !rest.empty(); ++axis)
    for (const bool below : {false, true}) {
      const double value = below ? box.max()[axis] : box.min()[axis];
      // Beyond the plane strictly: a piece lying in the plane is inside.
      ConvexPolygon beyond = clip_half_space(rest, axis, value, !below);
      const bool strictly = std::any_of(beyond.begin(), beyond.end(), [&](const Point<3>& x) {
        return below ? x[axis] > value : x[axis] < value;
      });
      if (strictly && polygon_area(beyond) > 0.0) pieces.push_back(std::move(beyond));
      rest = clip_half_space(rest, axis, value, below);
    }
  if (polygon_area(rest) > 0.0) pieces.front() = std::move(rest);
  return pieces;
}

double polygon_area(const ConvexPolygon& p) {
  Point<3> twice = Point<3>::Zero();
  for (std::size_t i = 1; i + 1 < p.size(); ++i) twice += (p[i] - p[0]).cross(p[i + 1] - p[0]);
  return 0.5 * twice.norm();
}

}  // namespace mfree

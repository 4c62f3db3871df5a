#include "mfree/geometry/support_obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mfree/core/parallel.hpp"
#include "mfree/geometry/segment_grid.hpp"
#include "mfree/search/cell_list.hpp"

namespace mfree {

namespace {

constexpr double end_extension = 1e-9;  ///< of a segment's length, at ends that are not corners

void add_segment(SupportObstacles& o, Vec2 a, Vec2 b, bool extend_a, bool extend_b, bool one_sided) {
  const Vec2 d = end_extension * (b - a);
  if (extend_a) a -= d;
  if (extend_b) b += d;
  o.a.push_back(a);
  o.b.push_back(b);
  o.one_sided.push_back(one_sided);
}

Vec2 unit_or_zero(const Vec2& v) {
  const double n = v.norm();
  return n > 0.0 ? Vec2(v / n) : Vec2(Vec2::Zero());
}

/// The unit normal of edge a -> b into the domain (on its left).
Vec2 inward_normal(const Vec2& a, const Vec2& b) { return unit_or_zero(Vec2(a.y() - b.y(), b.x() - a.x())); }

/// A corner at x; with `sides`, reached only from those sides of `vertex` (SupportObstacles).
/// With `wedge` >= 0, x is that wedge's reflex vertex itself.
void add_corner(SupportObstacles& o, const Vec2& x, const Vec2& vertex = Vec2::Zero(),
                const std::array<Vec2, 2>& sides = {Vec2::Zero(), Vec2::Zero()}, int wedge = -1) {
  o.corners.push_back(x);
  o.corner_vertex.push_back(vertex);
  o.corner_sides.push_back(sides);
  o.corner_wedge.push_back(wedge);
}

/// The vertices of a polyline (closed: a ring) without those where it runs straight on
/// (turn below 1e-12 of the product of the two edges' lengths): a straight side meshed into
/// many elements is one obstacle, and no corner. The ends of an open polyline stay.
std::vector<Vec2> without_straight_vertices(const std::vector<Vec2>& p, bool closed) {
  const std::size_t n = p.size();
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (!closed && (i == 0 || i + 1 == n)) {
      out.push_back(p[i]);
      continue;
    }
    const Vec2& before = out.empty() ? p[(i + n - 1) % n] : out.back();
    const Vec2& after = p[(i + 1) % n];
    const double turn = orientation(before, p[i], after);
    if (std::abs(turn) > 1e-12 * (p[i] - before).norm() * (after - p[i]).norm()) out.push_back(p[i]);
  }
  return out;
}

/// The corners of the reflex ring vertex v (edges prev -> v -> next, the domain on their
/// left). Cracks whose mouth is at v cut its wedge into sub-wedges: a path may not pass from one
/// to the next through v (it would go from one face of the crack to the other). A sub-wedge of
/// more than 180 degrees gets a corner 1e-3 of the shorter edge inside it along its bisector,
/// reached from its side of either bounding ray; a convex one needs none (no shortest path bends
/// there). Without a crack the corner is v itself, reached from the domain's side of an edge.
void add_reflex_corners(SupportObstacles& o, const Domain& domain, const Vec2& prev, const Vec2& v,
                        const Vec2& next, double tolerance) {
  o.wedge_vertex.push_back(v);
  o.wedge_edges.push_back({unit_or_zero(prev - v), unit_or_zero(next - v)});
  std::vector<Vec2> rays;  // directions of the cracks leaving v into the domain
  for (const Crack& c : domain.cracks())
    for (int end = 0; end < 2; ++end) {
      const std::size_t at = end == 0 ? 0 : c.points.size() - 1, inner = end == 0 ? 1 : c.points.size() - 2;
      if (!c.tip[end] && (c.points[at] - v).norm() <= tolerance) rays.push_back(unit_or_zero(c.points[inner] - v));
    }
  if (rays.empty()) {
    add_corner(o, v, v, {inward_normal(prev, v), inward_normal(v, next)},
               static_cast<int>(o.wedge_vertex.size()) - 1);
    return;
  }
  // Angles counter-clockwise from the edge to next, through the domain to the edge to prev.
  const Vec2 start = unit_or_zero(next - v);
  const auto angle = [&](const Vec2& d) {
    const double a = std::atan2(start.x() * d.y() - start.y() * d.x(), start.dot(d));
    return a < 0.0 ? a + 2.0 * std::numbers::pi : a;
  };
  std::sort(rays.begin(), rays.end(), [&](const Vec2& a, const Vec2& b) { return angle(a) < angle(b); });
  rays.insert(rays.begin(), start);
  rays.push_back(unit_or_zero(prev - v));
  const double offset = 1e-3 * std::min((prev - v).norm(), (next - v).norm());
  for (std::size_t k = 0; k + 1 < rays.size(); ++k) {
    const Vec2 &d1 = rays[k], &d2 = rays[k + 1];
    const double width = angle(d2) - angle(d1);
    if (width <= std::numbers::pi) continue;
    const double half = angle(d1) + 0.5 * width;
    const Vec2 bisector(std::cos(half) * start.x() - std::sin(half) * start.y(),
                        std::sin(half) * start.x() + std::cos(half) * start.y());
    // d1's left normal and d2's right normal point into the sub-wedge.
    add_corner(o, v + offset * bisector, v, {Vec2(-d1.y(), d1.x()), Vec2(d2.y(), -d2.x())});
  }
}

}  // namespace

SupportObstacles support_obstacles(const Domain& domain, double reach) {
  SupportObstacles out;
  const Box box = domain.bounding_box();
  const double tolerance = 1e-12 * box.size().norm();

  // Whether the boundary comes back to the outer side of edge a -> b within reach: some
  // boundary segment (ring edge or crack face) whose box meets the edge's box grown by reach
  // has an end strictly on that side. Conservative: such a segment's far end may lie beyond.
  const std::vector<BoundarySegment>& segments = domain.boundary();
  const SegmentGrid grid(segments);
  const auto separates = [&](const Vec2& a, const Vec2& b) {
    const Vec2 outward = Vec2(b.y() - a.y(), a.x() - b.x()).normalized();
    bool found = false;
    grid.for_each_meeting(Box{a.cwiseMin(b).array() - reach, a.cwiseMax(b).array() + reach}, [&](int k) {
      const BoundarySegment& f = segments[k];
      found = found || outward.dot(f.a - a) > tolerance || outward.dot(f.b - a) > tolerance;
    });
    return found;
  };

  for (const Ring& given : domain.rings()) {
    const Ring r = without_straight_vertices(given, true);
    const std::size_t n = r.size();
    // turn[i] > 0: convex vertex i (left turn), < 0: reflex.
    std::vector<double> turn(n);
    for (std::size_t i = 0; i < n; ++i) turn[i] = orientation(r[(i + n - 1) % n], r[i], r[(i + 1) % n]);
    for (std::size_t i = 0; i < n; ++i) {
      // A reflex vertex is reached from the domain's side of either edge only: a path from the
      // vertex into the outside wedge (across a slot to a point on its far wall) crosses no
      // obstacle, since it touches them only at its ends.
      if (turn[i] < 0.0) add_reflex_corners(out, domain, r[(i + n - 1) % n], r[i], r[(i + 1) % n], tolerance);
      const Vec2 &a = r[i], &b = r[(i + 1) % n];
      if (separates(a, b)) add_segment(out, a, b, turn[i] > 0.0, turn[(i + 1) % n] > 0.0, true);
    }
  }
  for (const Crack& c : domain.cracks()) {
    // A closed interface (round an inclusion) has no ends: every vertex is an inner one.
    const bool closed = c.closed();
    const std::vector<Vec2> p = closed
                                    ? without_straight_vertices({c.points.begin(), c.points.end() - 1}, true)
                                    : without_straight_vertices(c.points, false);
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (!closed && ((i == 0 && c.tip[0]) || (i + 1 == n && c.tip[1])))
        add_corner(out, p[i]);  // paths go round a tip
      if (!closed && (i == 0 || i + 1 == n)) continue;
      // An inner vertex is a corner on its reflex face, a little off the crack along the
      // bisector (1e-3 of the shorter segment: far above the round-off tolerance of the
      // crossing test, so that a path from the other face to it, nearly along the bisector,
      // still crosses a segment): a path that bends there stays on that face (through the
      // vertex itself it would pass from one face to the other).
      const Vec2 &before = p[(i + n - 1) % n], &after = p[(i + 1) % n];
      const Vec2 n1 = unit_or_zero(Vec2(before.y() - p[i].y(), p[i].x() - before.x()));
      const Vec2 n2 = unit_or_zero(Vec2(p[i].y() - after.y(), after.x() - p[i].x()));
      // Only the face on which the crack turns away (the reflex one) bends paths.
      const double offset = 1e-3 * std::min((p[i] - before).norm(), (after - p[i]).norm());
      const Vec2 side = offset * unit_or_zero(n1 + n2);
      const double sign = orientation(before, p[i], after) > 0.0 ? -1.0 : 1.0;
      add_corner(out, p[i] + sign * side, p[i], {sign * n1, sign * n2});
    }
    for (std::size_t i = 0; i + 1 < n + (closed ? 1 : 0); ++i)
      add_segment(out, p[i], p[(i + 1) % n], closed || !(i == 0 && c.tip[0]),
                  closed || !(i + 2 == n && c.tip[1]), false);
  }
  return out;
}

}  // namespace mfree

namespace mfree {

SurfaceObstacles support_obstacles(const Solid& solid, double reach) {
  const std::vector<SurfaceTriangle>& surface = solid.surface();
  std::vector<Vec3> vertices;
  vertices.reserve(3 * surface.size());
  for (const SurfaceTriangle& t : surface)
    vertices.insert(vertices.end(), t.vertices.begin(), t.vertices.end());
  const CellList<3> cells(vertices, reach);
  const double beyond = 1e-9 * reach;
  std::vector<char> obstacle(surface.size(), 0);
  parallel_blocks(static_cast<Index>(surface.size()), 256, [&](Index b, Index e) {
    for (Index k = b; k < e; ++k) {
      const auto& t = surface[static_cast<std::size_t>(k)].vertices;
      const Vec3 n = surface[static_cast<std::size_t>(k)].area_normal().normalized();
      const Vec3 centroid = (t[0] + t[1] + t[2]) / 3.0;
      double spread = 0.0;
      for (const Vec3& v : t) spread = std::max(spread, (v - centroid).norm());
      bool found = false;
      cells.for_each_in_box(centroid, reach + spread, [&](Index, const Vec3& v) {
        if (found || !((v - t[0]).dot(n) > beyond)) return;
        found = (closest_point_on_triangle(v, t) - v).norm() < reach;
      });
      obstacle[static_cast<std::size_t>(k)] = found ? 1 : 0;
    }
  });
  SurfaceObstacles out;
  for (std::size_t k = 0; k < surface.size(); ++k)
    if (obstacle[k]) {
      out.triangles.push_back(surface[k].vertices);
      out.normals.push_back(surface[k].area_normal().normalized());
    }
  return out;
}

}  // namespace mfree

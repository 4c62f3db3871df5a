#include "mfree/kernels/surface_visibility.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

using Triangle = std::array<Vec3, 3>;

}  // namespace

/// By the Voronoi regions of the vertices, edges and face (Ericson, Real-Time Collision
/// Detection, 2005, section 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Triangle& t) {
  const Vec3 &a = t[0], &b = t[1], &c = t[2];
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

namespace {

/// Whether y, a point of t's plane, lies in the closed triangle t (to round-off).
bool in_triangle(const Vec3& y, const Triangle& t, const Vec3& unit_normal) {
  const double tolerance = -1e-12 * (t[1] - t[0]).squaredNorm();
  for (int e = 0; e < 3; ++e)
    if ((t[(e + 1) % 3] - t[e]).cross(y - t[e]).dot(unit_normal) < tolerance) return false;
  return true;
}

/// Where the segment p -> q passes through triangle t at a point interior to the segment, its
/// parameter in (0, 1); nothing when it touches the plane only at an end (to 1e-12 of the
/// segment's length), runs in the plane, or passes beside the triangle. The triangle is
/// closed: a segment through an edge or a vertex crosses.
std::optional<double> crossing(const Vec3& p, const Vec3& q, const Triangle& t, const Vec3& unit_normal) {
  const double dp = (p - t[0]).dot(unit_normal), dq = (q - t[0]).dot(unit_normal);
  const double on_plane = 1e-12 * (q - p).norm();
  if (!((dp > on_plane && dq < -on_plane) || (dp < -on_plane && dq > on_plane))) return std::nullopt;
  const double s = dp / (dp - dq);
  if (!in_triangle(p + s * (q - p), t, unit_normal)) return std::nullopt;
  return s;
}

std::vector<Vec3> centroids(const SurfaceObstacles& o) {
  std::vector<Vec3> c(o.triangles.size());
  for (std::size_t k = 0; k < c.size(); ++k)
    c[k] = (o.triangles[k][0] + o.triangles[k][1] + o.triangles[k][2]) / 3.0;
  return c;
}

}  // namespace

SurfaceVisibility::SurfaceVisibility(SurfaceObstacles obstacles, double reach)
    : obstacles_(std::move(obstacles)), reach_(reach) {
  if (!(reach_ > 0.0) || !std::isfinite(reach_))
    throw InputError("surface visibility: the reach must be positive and finite");
  if (obstacles_.normals.size() != obstacles_.triangles.size())
    throw InputError("surface visibility: one normal per obstacle triangle");
  const std::vector<Vec3> c = centroids(obstacles_);
  double spread = 0.0;
  for (std::size_t k = 0; k < c.size(); ++k)
    for (const Vec3& v : obstacles_.triangles[k]) spread = std::max(spread, (v - c[k]).norm());
  search_ = reach_ + spread;
  if (!c.empty()) centroids_ = CellList<3>(c, std::max(reach_, spread));
}

bool SurfaceVisibility::prepare(const Vec3& x, VisibilityScratch& s) const {
  s.triangles.clear();
  s.clearance = reach_;
  centroids_.for_each_in_box(x, search_, [&](Index k, const Vec3&) {
    const double d = (closest_point_on_triangle(x, obstacles_.triangles[k]) - x).norm();
    if (d >= reach_) return;
    s.triangles.push_back(k);
    s.clearance = std::min(s.clearance, d);
  });
  return !s.triangles.empty();
}

double SurfaceVisibility::clearance(const Vec3& p) const {
  double c = reach_;
  centroids_.for_each_in_box(p, search_, [&](Index k, const Vec3&) {
    c = std::min(c, (closest_point_on_triangle(p, obstacles_.triangles[k]) - p).norm());
  });
  return c;
}

bool SurfaceVisibility::leaves(const Vec3& end, const Vec3& other, const VisibilityScratch& s) const {
  const double on_plane = 1e-12 * (other - end).norm();
  std::vector<int> out, in;  // the triangles holding `end` the segment leaves and enters (rare: ends on walls)
  for (int k : s.triangles) {
    const Triangle& t = obstacles_.triangles[k];
    const Vec3& n = obstacles_.normals[k];
    if (!(std::abs((end - t[0]).dot(n)) <= on_plane) || !in_triangle(end, t, n)) continue;
    const double along = (other - end).dot(n);
    if (along > on_plane) out.push_back(k);
    if (along < -on_plane) in.push_back(k);
  }
  // Out through T and in through U at once (end on an edge or a vertex): the outside when the
  // edge is convex (U on T's inner side: the solid is the intersection of the half-spaces
  // there), the solid's inside at a re-entrant edge (the union).
  const auto convex = [&](int t, int u) {
    const Triangle& a = obstacles_.triangles[t];
    const double tolerance = 1e-9 * (a[1] - a[0]).norm();
    for (const Vec3& v : obstacles_.triangles[u])
      if ((v - a[0]).dot(obstacles_.normals[t]) > tolerance) return false;
    return true;
  };
  for (int t : out) {
    bool outside = true;
    for (std::size_t j = 0; j < in.size() && outside; ++j) outside = convex(t, in[j]);
    if (outside) return true;
  }
  return false;
}

bool SurfaceVisibility::visible(const Vec3& p, double p_clearance, const Vec3& x,
                                const VisibilityScratch& s) const {
  // Shorter than the clearances' sum: no obstacle within reach of the segment. At the sum
  // itself the segment may pass through one (a node and a point on either side of a wall on
  // the lattice, each as far from it as the other's distance makes up): a margin of 1e-9.
  if ((p - x).norm() < (1.0 - 1e-9) * (p_clearance + s.clearance)) return true;
  for (int k : s.triangles)
    if (crossing(p, x, obstacles_.triangles[k], obstacles_.normals[k])) return false;
  // An end on the surface from which the segment runs outside (from one wall of a gap to the
  // other, both ends on the walls).
  if (s.clearance <= 1e-12 * (p - x).norm() && leaves(x, p, s)) return false;
  return !(p_clearance <= 1e-12 * (p - x).norm() && leaves(p, x, s));
}

std::optional<SurfaceGap> find_gap(const SurfaceObstacles& obstacles, double radius) {
  const SurfaceVisibility visibility(obstacles, radius);
  const std::vector<Vec3> c = centroids(obstacles);
  VisibilityScratch s;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Vec3& n = obstacles.normals[k];
    const Vec3 end = c[k] + radius * n;
    visibility.prepare(c[k], s);
    double nearest = std::numeric_limits<double>::infinity();
    int wall = -1;
    for (int j : s.triangles) {
      if (static_cast<std::size_t>(j) == k) continue;
      const std::optional<double> t = crossing(c[k], end, obstacles.triangles[j], obstacles.normals[j]);
      if (t && *t < nearest) nearest = *t, wall = j;
    }
    if (wall < 0 || obstacles.normals[wall].dot(n) > -0.5) continue;
    // Across the gap the outside must reach at least its width every way: a hole narrower than
    // the support is not a gap (the path round it is pi / 2 times its diameter).
    const double width = nearest * radius;
    const Vec3 middle = c[k] + 0.5 * width * n;
    const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
    visibility.prepare(middle, s);
    bool open = true;
    for (int d = 0; d < 8 && open; ++d) {
      const double angle = d * std::numbers::pi / 4.0;
      const Vec3 end_d = middle + width * (std::cos(angle) * a + std::sin(angle) * b);
      for (int j : s.triangles)
        if (crossing(middle, end_d, obstacles.triangles[j], obstacles.normals[j])) {
          open = false;
          break;
        }
    }
    if (open) return SurfaceGap{c[k], c[k] + width * n, width};
  }
  return std::nullopt;
}

}  // namespace mfree

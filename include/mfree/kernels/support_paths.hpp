#pragma once
// Supports that respect the domain: the distance d(x_I, x) a node's window measures to a
// point is taken along paths inside the domain, so that a support does not reach material
// joined to its node only across a crack, a slot, a thin wall or a re-entrant corner
// (SPEC section 13). The window is then w(d / a_I) in place of w(|x - x_I| / a_I); the
// RK correction (rk_shape_functions.hpp) restores reproduction whatever the window.
//
// Rules:
//   plain       d = |x - x_I|: supports ignore the domain and reach across gaps and cracks.
//   visibility  d = |x - x_I| when the segment x_I -> x crosses no obstacle, otherwise the
//               node does not reach x (Belytschko, Lu & Gu 1994; Belytschko, Organ &
//               Krongauz 1996): the shape functions jump across the shadow lines that
//               start at crack tips and re-entrant corners.
//   geodesic    d = the length of the shortest path from x_I to x that crosses no obstacle,
//               bending at corners: continuous in x, so the window of a node beside a crack
//               tip wraps around the tip. With one bend at a crack tip it is the distance of
//               the diffraction method with exponent 1 (Organ, Fleming, Terry & Belytschko
//               1996, eq. 7: d = (s1 + s2), lambda = 1); here every re-entrant corner is a
//               bend point and paths may bend several times, as long as they stay within the
//               support. It is the distance a local problem on the embedded domain (the
//               eikonal equation |grad d| = 1 in Omega, d = 0 at x_I) would give.
//
// Obstacles are straight segments no path may cross (a path touching one at a point does
// not cross it); corners are the points where paths may bend. The domain makes them
// (geometry/support_obstacles.hpp): the boundary edges that can separate two points of the
// domain, both faces of each crack, reflex vertices and crack tips as corners. An end of an
// obstacle that is not a corner is moved out by 1e-9 of its length, so that a path along
// the boundary cannot slip past a convex vertex through the outside (the mouth of a slot).
//
// The gradient of d in x is the unit vector from the last bend point (or x_I) to x.
// In three dimensions obstacles become triangles and corners become edges (crack fronts,
// re-entrant edges); a path bends at a point of an edge, and the same two rules apply.
//
// Everything here is per point: prepare() collects the obstacles near one point into a
// scratch the caller owns (one per thread), distance() reads them.

#include <array>
#include <memory>
#include <utility>
#include <optional>
#include <string_view>
#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"

namespace mfree {

enum class SupportRule { plain, visibility, geodesic };
/// plain, visibility, geodesic: the names scenes use.
const NameTable<SupportRule>& support_rule_names();
std::string_view to_string(SupportRule rule);

/// Segments no path crosses and the corners where paths bend.
struct SupportObstacles {
  std::vector<Vec2> a, b;  ///< segment k runs from a[k] to b[k]
  /// Per segment (or empty: none), whether the domain lies on its left only (a ring edge; a
  /// crack has the domain on both sides): a path from a point on it must leave to the left.
  std::vector<char> one_sided;
  std::vector<Vec2> corners;
  /// Per corner (or empty: none guarded), the side a path must come from: a corner at a
  /// crack's inner vertex v is reached from x only when (x - v) . m > 0 for one of the two
  /// normals m (of its segments, into its reflex face), a reflex vertex of a ring when x is on
  /// the domain's side of one of its edges (m their inward normals); m zero: from anywhere.
  std::vector<Vec2> corner_vertex;
  std::vector<std::array<Vec2, 2>> corner_sides;
  /// Per corner (or empty: none), the wedge (below) of the reflex vertex the corner is, or -1
  /// for a corner off a vertex (a crack's, or one of a vertex a crack's mouth cuts).
  std::vector<int> corner_wedge;
  /// The reflex vertices of the rings, each with the unit directions along its two edges:
  /// their ends meet there unmoved (paths bend there), so a segment through such a vertex,
  /// or from it, into the outside wedge between the edges (under 180 degrees) crosses no
  /// obstacle at an interior point; it is blocked by the wedge (a chord of a faceted hole
  /// through two of its vertices, a path from a slot's corner across the slot).
  std::vector<Vec2> wedge_vertex;
  std::vector<std::array<Vec2, 2>> wedge_edges;
  [[nodiscard]] bool empty() const { return a.empty(); }
  /// Whether a path from x may bend at corner c: x on the corner's side and, where the
  /// corner's edges are known, the line from x through the corner tangent to them (both on
  /// one side of it, to 1e-9 in the sine of the angle). A shortest path bends only where each
  /// of its legs is tangent (its line entering the outside wedge at the vertex, the path
  /// could be shortened), so the test drops no shortest path; along a finely faceted concave
  /// arc it leaves two corners of hundreds. A point on the line of one of the corner's
  /// segments (to 1e-10 of its distance: a crack tip, from which a path runs along the face)
  /// reaches it too; face copies lie 1e-7 h off the line (crack_faces.hpp), far outside that
  /// tolerance.
  [[nodiscard]] bool reaches(const Vec2& x, std::size_t c) const {
    if (corner_sides.empty() || corner_sides[c][0].isZero()) return true;
    const Vec2 d = x - corner_vertex[c];
    const double on_line = -1e-10 * d.norm();
    if (!(d.dot(corner_sides[c][0]) >= on_line || d.dot(corner_sides[c][1]) >= on_line)) return false;
    if (corner_wedge.empty() || corner_wedge[c] < 0) return true;
    // Sines (times |d|) of the angles from d to each edge: opposite signs, the line separates them.
    const std::array<Vec2, 2>& e = wedge_edges[static_cast<std::size_t>(corner_wedge[c])];
    const double s0 = d.x() * e[0].y() - d.y() * e[0].x();
    const double s1 = d.x() * e[1].y() - d.y() * e[1].x();
    const double tolerance = 1e-9 * d.norm();
    return !((s0 > tolerance && s1 < -tolerance) || (s0 < -tolerance && s1 > tolerance));
  }
};

/// What prepare() collects for one point x: the obstacles and corners within the reach of
/// x, and (geodesic rule) the in-domain distance from each such corner to x.
struct PathScratch {
  std::vector<int> segments;  ///< indices of obstacles near x
  std::vector<int> corners;   ///< indices of corners near x
  std::vector<int> wedges;    ///< indices of wedges near x
  std::vector<double> to_x;   ///< per near corner: shortest path length to x (inf: none)
  std::vector<Vec2> last;     ///< per near corner: the path's last point before x
  std::vector<int> local;     ///< per corner of the domain: its place in `corners`, or -1
  std::vector<std::pair<double, int>> heap;  ///< Dijkstra's queue: (length, place)
};

class SupportPaths {
 public:
  /// `reach`: the largest support radius (length units) the paths serve.
  SupportPaths(SupportObstacles obstacles, SupportRule rule, double reach);

  [[nodiscard]] SupportRule rule() const { return rule_; }
  [[nodiscard]] const SupportObstacles& obstacles() const { return obstacles_; }

  /// Collects the obstacles within the reach of x. False when there are none (or the rule
  /// is plain): every node then measures |x - x_I|.
  bool prepare(const Vec2& x, PathScratch& s) const;

  /// d(x_I, x) under the rule, for a node x_I within the reach of x, after prepare(x, s)
  /// returned true; +inf when no admissible path shorter than the reach joins them.
  /// `gradient` gets d d / d x (a unit vector; zero where x is the path's last point).
  double distance(const Vec2& xi, const Vec2& x, const PathScratch& s, Vec2& gradient) const;

  /// Whether the segment p -> q crosses none of the obstacles collected in s and enters no
  /// wedge collected there.
  [[nodiscard]] bool visible(const Vec2& p, const Vec2& q, const PathScratch& s) const;

 private:
  template <class F>
  void for_each_bucket(const Vec2& x, F&& f) const;
  /// The obstacles and corners near x into s; false when there are no obstacles.
  bool prepare_obstacles(const Vec2& x, PathScratch& s) const;
  void find_legs();

  SupportObstacles obstacles_;
  SupportRule rule_;
  double reach_;
  double tolerance_ = 0.0;  ///< a segment end this close to an obstacle's line lies on it (length)
  // Buckets of side reach_ over the obstacles' box: segment and corner indices per bucket.
  Vec2 origin_ = Vec2::Zero();
  double side_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> segment_start_, segment_items_, corner_start_, corner_items_, wedge_start_, wedge_items_;
  // Geodesic rule: the legs between corners (CSR by corner), those shorter than the reach
  // along which a shortest path may run (each end reached from the other, no obstacle crossed).
  std::vector<int> leg_start_, leg_to_;
  std::vector<double> leg_length_;
};

/// A node whose plain support of radius `radius` reaches a point across a gap: |x - x_I| <
/// radius while the shortest path between them in the domain is more than twice as long (or
/// longer than two radii): a slot, a crack, a thin cavity narrower than the support. Corners
/// do not count (around a re-entrant corner of 90 degrees a path is at most sqrt(2) times
/// the straight distance).
struct Bridge {
  Vec2 node, point;
  double straight = 0.0;   ///< |point - node|
  double in_domain = 0.0;  ///< the shortest path in the domain, +inf beyond two radii
};

/// The first bridge (points in order) plain supports of `radius` about the nodes would make
/// to the points (the quadrature points), if any.
std::optional<Bridge> find_bridge(const std::vector<Vec2>& nodes, const std::vector<Vec2>& points,
                                  const SupportObstacles& obstacles, double radius);

}  // namespace mfree

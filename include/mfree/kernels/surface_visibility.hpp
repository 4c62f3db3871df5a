#pragma once
// Supports that respect a solid (SPEC section 13) in three dimensions: the visibility rule
// (Belytschko, Lu & Gu 1994; Belytschko, Organ & Krongauz 1996). A node reaches x only when
// the segment x_I -> x crosses no obstacle, a triangle of the solid's surface that can
// separate two points of the solid within a support (geometry/support_obstacles.hpp: the
// walls of a slot, a thin cavity, a hole, a re-entrant edge; never a face of a convex part).
// The window then measures the straight distance as for plain supports; a blocked node does
// not reach x, so the shape functions jump across the shadows that start at re-entrant edges.
//
// A segment crosses a triangle when it passes through it at a point interior to the segment:
// touching at an end (a boundary point on the surface, a node on a wall) or running in its
// plane is not crossing. An end within 1e-12 of the segment's length of a triangle's plane
// lies on it. A segment is blocked too when an end lies on an obstacle and the segment runs
// from there to its outer side (from one wall of a gap to the other); at an edge where it
// leaves through one face and enters through the other, the edge decides: convex, outside;
// re-entrant, inside.
//
// Everything here is per point: prepare() collects the obstacles near one point and its
// clearance (the distance to the nearest one) into a scratch the caller owns (one per
// thread); visible() reads them. A segment shorter than the sum of the clearances of its two
// ends (by a margin of 1e-9 of it) cannot reach an obstacle and is visible without a test.

#include <array>
#include <optional>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/search/cell_list.hpp"

namespace mfree {

/// Triangles no support reaches across, with their outward normals (unit).
struct SurfaceObstacles {
  std::vector<std::array<Vec3, 3>> triangles;
  std::vector<Vec3> normals;
  [[nodiscard]] bool empty() const { return triangles.empty(); }
};

/// The point of the triangle t nearest to p.
Vec3 closest_point_on_triangle(const Vec3& p, const std::array<Vec3, 3>& t);

/// What prepare() collects for one point x.
struct VisibilityScratch {
  std::vector<int> triangles;  ///< obstacles within the reach of x
  double clearance = 0.0;      ///< distance from x to the nearest of them (reach when none)
};

class SurfaceVisibility {
 public:
  /// `reach`: the largest support radius (length units) the tests serve.
  SurfaceVisibility(SurfaceObstacles obstacles, double reach);

  [[nodiscard]] const SurfaceObstacles& obstacles() const { return obstacles_; }
  [[nodiscard]] double reach() const { return reach_; }

  /// Collects the obstacles within the reach of x and its clearance. False when x is at
  /// least the reach away from every obstacle: every segment from x within the reach is
  /// visible.
  bool prepare(const Vec3& x, VisibilityScratch& s) const;

  /// The distance from p to the nearest obstacle, at most the reach.
  [[nodiscard]] double clearance(const Vec3& p) const;

  /// Whether the segment p -> x crosses none of the obstacles prepare(x, s) collected;
  /// `p_clearance`: p's clearance, or 0 when not known.
  [[nodiscard]] bool visible(const Vec3& p, double p_clearance, const Vec3& x,
                             const VisibilityScratch& s) const;

 private:
  /// Whether the segment leaves the solid at `end`, a point on the surface, towards `other`.
  [[nodiscard]] bool leaves(const Vec3& end, const Vec3& other, const VisibilityScratch& s) const;

  SurfaceObstacles obstacles_;
  double reach_;
  double search_ = 0.0;  ///< reach plus the largest distance from a triangle's centroid to its vertices
  CellList<3> centroids_;
};

/// A gap plain supports of radius `radius` reach across: the outside of the solid narrower
/// than the radius between two walls that face each other, from the centroid `from` of an
/// obstacle along its outward normal to the wall it meets at `to`, which faces back within
/// 60 degrees, the outside reaching at least that width from the middle in eight directions
/// across (a slot or a thin cavity away from its end, a V-notch sharper than 60 degrees: there
/// the shortest path in the solid between the walls is more than twice their distance; not a
/// hole, round which the path is pi / 2 times its diameter, nor the root of a slot).
struct SurfaceGap {
  Vec3 from, to;
  double width = 0.0;  ///< |to - from|
};

/// The first gap (obstacles in order) of the surface, if any.
std::optional<SurfaceGap> find_gap(const SurfaceObstacles& obstacles, double radius);

}  // namespace mfree

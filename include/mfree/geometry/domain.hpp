#pragma once
// The problem domain Omega: a polygon with holes in the plane.
//
// Rings: the outer boundary first, counter-clockwise; then each hole, clockwise. With this
// orientation the domain lies to the left of every boundary edge, and the outward unit
// normal of an edge a -> b is (t.y, -t.x) with t = (b - a) / |b - a|.
//
// Domains are built in (rectangle), read from a gmsh file (gmsh_domain.hpp: .geo, .msh, CAD)
// or from a WKT file (meshes/*.wkt), e.g.
//   POLYGON((0 0, 2 0, 2 1, 0 1, 0 0), (0.5 0.25, 0.5 0.75, 1 0.75, 1 0.25, 0.5 0.25))
// WKT is what GIS tools, Shapely, QGIS and CAD exporters write. Ring orientation in the file
// is free; mfree normalises it. The closing vertex repeating the first one is optional.
//
// CGAL does the geometry (inside tests, Boolean clipping); its headers stay in domain.cpp.

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

/// A closed polygonal ring, vertices in order, last vertex not repeated.
using Ring = std::vector<Vec2>;

/// One straight piece of the boundary, with its outward unit normal.
struct BoundarySegment {
  Vec2 a;         ///< start vertex
  Vec2 b;         ///< end vertex (domain on the left of a -> b)
  Vec2 normal;    ///< outward unit normal
  double length;  ///< |b - a|
  int ring;       ///< 0: outer boundary, k >= 1: hole k
  int edge;       ///< index of the edge in its ring (from vertex edge to vertex edge + 1)
  int part;       ///< named boundary part (Domain::part_names()), -1: none
};

class Domain {
 public:
  /// The rectangle [lo.x, hi.x] x [lo.y, hi.y]; throws InputError unless lo < hi. Its edges
  /// are the named parts "bottom", "right", "top" and "left".
  static Domain rectangle(Vec2 lo, Vec2 hi);
  /// A polygon with holes from its rings (any orientation, outer ring first) and, per ring
  /// and edge (edge i from vertex i to vertex i + 1), the index of its named part in
  /// `part_names` or -1. Validated like WKT input; `source` names it in messages.
  static Domain from_rings(std::vector<Ring> rings, std::vector<std::vector<int>> edge_parts,
                           std::vector<std::string> part_names, const std::string& source);
  /// Parses one WKT POLYGON; `source` names the text in error messages (a file name).
  /// Throws InputError on malformed text, self-intersecting or degenerate rings.
  static Domain from_wkt(std::string_view wkt, const std::string& source = "<wkt>");
  /// Reads a domain file by its extension (case aside): .wkt as WKT (from_wkt), the gmsh
  /// extensions (.geo, .msh, .step, .stp, .brep, .iges, .igs) with read_gmsh_domain
  /// (gmsh_domain.hpp), which also names the boundary parts. A missing or unreadable file, or
  /// another extension (the message lists the accepted ones), is an InputError naming the path.
  static Domain from_file(const std::filesystem::path& path);

  Domain(const Domain&);
  Domain(Domain&&) noexcept;
  Domain& operator=(const Domain&);
  Domain& operator=(Domain&&) noexcept;
  ~Domain();

  /// True for points inside Omega or on its boundary (Omega is taken closed).
  [[nodiscard]] bool contains(const Vec2& x) const;
  /// |Omega|.
  [[nodiscard]] double area() const;
  /// The first moment, integral of x over Omega (so centroid = first_moment() / area()).
  [[nodiscard]] Vec2 first_moment() const;
  [[nodiscard]] Box bounding_box() const;
  /// Outer ring (counter-clockwise) then holes (clockwise).
  [[nodiscard]] const std::vector<Ring>& rings() const;
  /// Every boundary edge with its outward normal, ring by ring in ring order.
  [[nodiscard]] const std::vector<BoundarySegment>& boundary() const;
  /// Names of the boundary parts (BoundarySegment::part indexes them); may be empty.
  [[nodiscard]] const std::vector<std::string>& part_names() const;
  /// The part of the box inside Omega, as rings oriented like rings(): counter-clockwise
  /// outer rings and clockwise holes, so Green's-theorem integrals over all returned rings
  /// add up to integrals over box ∩ Omega. Empty when they do not overlap.
  [[nodiscard]] std::vector<Ring> clip(const Box& box) const;

 private:
  struct Impl;
  explicit Domain(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace mfree

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
// Cracks come as line strings beside the polygon, in a collection:
//   GEOMETRYCOLLECTION(POLYGON((0 0, 2 0, 2 1, 0 1)), LINESTRING(0.8 0.5, 1.2 0.5))
// named crack1, crack2, ... in their order (a MULTILINESTRING counts each line).
// Several polygons (a MULTIPOLYGON, or POLYGONs in the collection) are the regions of one
// domain, named region1, region2, ... unless RegionOptions names them (from_regions).
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
  int ring;       ///< 0: outer boundary, k >= 1: hole k, -1: a crack face
  int edge;       ///< index of the edge in its ring or crack (from vertex edge to vertex edge + 1)
  int part;       ///< named boundary part (Domain::part_names()), -1: none
  int crack = -1;  ///< the crack (Domain::cracks()) whose face this is, -1: a ring edge
};

/// A crack: a polyline inside the domain whose two faces are boundary (traction-free unless
/// a condition names the crack). Each end is a tip inside the domain or lies on the boundary
/// (an edge crack's mouth). Its faces are the part named `name`.
struct Crack {
  /// Vertices in order, at least 2; an interface round an inclusion closes on itself: its
  /// last point repeats its first (at least 3 distinct points), and it has no ends.
  std::vector<Vec2> points;
  std::string name;
  bool tip[2] = {false, false};  ///< whether points.front() / points.back() is a tip
  /// An interface between two regions (Domain::regions()) is a crack whose faces are tied,
  /// not free: the region on the left of the polyline (points in order; the face a -> b's
  /// material) and the one on its right. -1 for a crack.
  int left = -1, right = -1;
  [[nodiscard]] bool interface() const { return left >= 0; }
  [[nodiscard]] bool closed() const { return points.size() > 3 && points.front() == points.back(); }
};

/// A named region of a domain made of several (a material, or a part of an assembly).
struct Region {
  std::string name;
  std::vector<Ring> rings;  ///< oriented like Domain::rings()
};

/// How a domain of several polygons is built (from_regions).
struct RegionOptions {
  std::vector<std::string> names;  ///< the regions' names in order; empty: region1, region2, ...
  /// true: the edges two regions share become interfaces, cracks whose faces are tied
  /// (supports end there, nodes on them split, the strain may jump); false: they stay inside
  /// the domain and the approximation is smooth across them.
  bool interfaces = true;
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
  static Domain from_wkt(std::string_view wkt, const std::string& source = "<wkt>",
                         const RegionOptions& regions = {});
  /// The union of regions: polygons with holes (rings as from_rings takes them) that share
  /// edges, or pieces of edges, and overlap nowhere; their union must be one polygon with
  /// holes. Where two regions share edges the domain gets an interface (a Crack with left
  /// and right set) named "<left>/<right>", unless options.interfaces is false. An interface
  /// runs from boundary to boundary or closes on itself (round an inclusion); one that meets
  /// another is refused. `edge_parts`, when given, holds per region, ring and edge (as given)
  /// the index of its part in `part_names` or -1; an edge of the union takes the part of the
  /// region edge it lies along. Throws InputError naming `source` and the regions otherwise.
  static Domain from_regions(std::vector<std::vector<Ring>> polygons, const RegionOptions& options,
                             const std::string& source,
                             std::vector<std::vector<std::vector<int>>> edge_parts = {},
                             std::vector<std::string> part_names = {});
  /// This domain with cracks: polylines (each at least 2 distinct points) inside the closed
  /// domain, whose vertices other than the ends lie in its interior, crossing no boundary
  /// edge, no other crack and themselves nowhere; an end on the boundary is a mouth, one in
  /// the interior a tip. `names` (one per crack, not a part name already) name their faces.
  /// `sides`, when given, makes each line an interface between regions: (left, right) per
  /// line (Crack::left, right); an interface may close on itself (its last point its first,
  /// every point in the interior), a crack may not (it would cut its inside loose).
  /// Throws InputError naming `source` and the crack otherwise.
  [[nodiscard]] Domain with_cracks(std::vector<std::vector<Vec2>> lines, std::vector<std::string> names,
                                   const std::string& source,
                                   const std::vector<std::pair<int, int>>& sides = {}) const;
  /// Reads a domain file by its extension (case aside): .wkt as WKT (from_wkt), the gmsh
  /// extensions (.geo, .msh, .step, .stp, .brep, .iges, .igs) with read_gmsh_domain
  /// (gmsh_domain.hpp), which also names the boundary parts and takes the regions from the
  /// physical surfaces (regions.names must be empty; regions.interfaces applies). A missing or
  /// unreadable file, or another extension (the message lists the accepted ones), is an
  /// InputError naming the path.
  static Domain from_file(const std::filesystem::path& path, const RegionOptions& regions = {});

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
  /// Whether a boundary segment (ring edge, crack or interface face) may meet the box: false
  /// means the box lies wholly inside or wholly outside one region (a conservative test).
  [[nodiscard]] bool boundary_near(const Box& box) const;
  /// Indices into boundary() of the segments whose boxes meet the box's (from the domain's
  /// segment grid: a few per query, however many segments the domain has).
  [[nodiscard]] std::vector<int> boundary_segments_near(const Box& box) const;
  /// The cracks, in the order given, and the interfaces between regions.
  [[nodiscard]] const std::vector<Crack>& cracks() const;
  /// The regions of a domain built from several; empty for one polygon.
  [[nodiscard]] const std::vector<Region>& regions() const;
  /// The region holding x (on an edge two regions share: the first); 0 for a domain
  /// without regions; -1 outside every region.
  [[nodiscard]] int region_at(const Vec2& x) const;
  /// region_at(x), or for a point outside every region (a point of the boundary, off its
  /// edge by round-off) the region whose rings pass nearest, with that distance.
  [[nodiscard]] std::pair<int, double> nearest_region(const Vec2& x) const;
  /// Every boundary edge with its outward normal, ring by ring in ring order, then the faces
  /// of each crack: per crack segment a -> b, the face a -> b (the material on its left;
  /// normal to the right) and then the face b -> a.
  [[nodiscard]] const std::vector<BoundarySegment>& boundary() const;
  /// Names of the boundary parts (BoundarySegment::part indexes them); may be empty.
  [[nodiscard]] const std::vector<std::string>& part_names() const;
  /// The part of the box inside Omega, as rings oriented like rings(): counter-clockwise
  /// outer rings and clockwise holes, so Green's-theorem integrals over all returned rings
  /// add up to integrals over box ∩ Omega. Empty when they do not overlap. With region >= 0:
  /// the part of the box inside that region (regions()).
  [[nodiscard]] std::vector<Ring> clip(const Box& box, int region = -1) const;

 private:
  struct Impl;
  explicit Domain(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace mfree

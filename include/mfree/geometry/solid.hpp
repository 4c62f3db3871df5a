#pragma once
// The three-dimensional domain Omega: a solid.
//
// The interface the dimension-generic parts take from a domain (clouds, the background
// lattice, the quadrature), the same as the plane Domain's: the bounding box, the inside test
// of the closed solid and the measure (volume). Its boundary is a surface of flat triangles,
// each oriented outward ((b - a) x (c - a) points out of the solid) and in one named part;
// the conditions of a problem select pieces of it (geometry/boundary_selection.hpp).
//
// A solid is either an axis-aligned box [lo, hi] (length units), inside which every cell of a
// lattice fitted to it is whole, its surface two triangles per face in the parts x_min,
// x_max, y_min, y_max, z_min, z_max; or a mesh of tetrahedra Omega_h (gmsh's, from .geo,
// .msh, STEP/BREP/IGES: geometry/gmsh_solid.hpp) with the triangles of its boundary, which is
// the solid for the inside test, the measure and the cut cells of the background lattice:
// a curved surface enters as the flat triangles of its mesh.

#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

class TetrahedralMesh;

/// An axis-aligned box in dim dimensions: min() and max() corners, sizes(), volume().
template <int dim>
using AlignedBox = Eigen::AlignedBox<double, dim>;

/// A flat triangle of a solid's surface, oriented outward, in part `part` (index into
/// Solid::parts()).
struct SurfaceTriangle {
  std::array<Point<3>, 3> vertices;
  int part = 0;
  /// (b - a) x (c - a): the outward normal times twice the area.
  [[nodiscard]] Point<3> area_normal() const {
    return (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]);
  }
};

/// A flat triangle of a face two regions share (an interface), oriented out of region `from`
/// into region `to` (from < to).
struct InterfaceTriangle {
  std::array<Point<3>, 3> vertices;
  int from = 0, to = 1;
  /// (b - a) x (c - a): the normal from `from` into `to` times twice the area.
  [[nodiscard]] Point<3> area_normal() const {
    return (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]);
  }
};

class Solid {
 public:
  static constexpr int dim = 3;

  /// The box [lo, hi]; InputError unless lo < hi in every coordinate (all finite).
  static Solid box(const Point<3>& lo, const Point<3>& hi);

  /// The solid Omega_h filled by `mesh`, bounded by `surface` (outward triangles, each in one
  /// of `parts`, or in none: part -1), of the named `regions` (the mesh's region indices count
  /// them; empty: one region). Throws InputError naming `source` when the surface is empty, a
  /// triangle's part or a tetrahedron's region is out of range, or the surface does not
  /// enclose the mesh's volume (sum of (x . n) dA / 3 over the surface against the volume,
  /// 1e-9 relative: a surface missing triangles or turned inward), or a triangle has the solid
  /// on its outer side too (volumes touching without a conforming mesh). With `tied` the faces
  /// two regions' tetrahedra share are the solid's interfaces(), where the supports end and
  /// Nitsche's method ties the sides; otherwise the regions are bonded inside one set of
  /// functions and interfaces() is empty.
  static Solid from_mesh(TetrahedralMesh mesh, std::vector<SurfaceTriangle> surface,
                         std::vector<std::string> parts, const std::string& source,
                         std::vector<std::string> regions = {}, bool tied = true);

  [[nodiscard]] const AlignedBox<3>& bounding_box() const { return box_; }
  /// Whether x lies in the closed solid.
  [[nodiscard]] bool contains(const Point<3>& x) const;
  /// |Omega| (length units cubed).
  [[nodiscard]] double measure() const;
  /// The tetrahedra filling the solid; null for a box.
  [[nodiscard]] const TetrahedralMesh* mesh() const { return mesh_.get(); }
  /// The boundary: outward triangles.
  [[nodiscard]] const std::vector<SurfaceTriangle>& surface() const { return surface_; }
  /// The names of the surface's parts, in the order SurfaceTriangle::part counts them.
  [[nodiscard]] const std::vector<std::string>& parts() const { return parts_; }
  /// The names of the solid's regions (gmsh's physical volumes), in the order region_at()
  /// counts them; empty: one region (a box, or a part without physical volumes).
  [[nodiscard]] const std::vector<std::string>& regions() const { return regions_; }
  /// The region of x (0 for a solid of one region); on a face between two regions, either;
  /// -1 outside the solid.
  [[nodiscard]] int region_at(const Point<3>& x) const;
  /// The faces between regions that are tied (from_mesh), each once; empty for one region or
  /// bonded regions.
  [[nodiscard]] const std::vector<InterfaceTriangle>& interfaces() const { return interfaces_; }

 private:
  Solid(const AlignedBox<3>& box, std::vector<SurfaceTriangle> surface, std::vector<std::string> parts,
        std::shared_ptr<const TetrahedralMesh> mesh = nullptr, std::vector<std::string> regions = {})
      : box_(box),
        surface_(std::move(surface)),
        parts_(std::move(parts)),
        regions_(std::move(regions)),
        mesh_(std::move(mesh)) {}
  AlignedBox<3> box_;
  std::vector<SurfaceTriangle> surface_;
  std::vector<std::string> parts_;
  std::vector<std::string> regions_;
  std::shared_ptr<const TetrahedralMesh> mesh_;
  std::vector<InterfaceTriangle> interfaces_;
};

}  // namespace mfree

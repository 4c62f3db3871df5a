#pragma once
// The three-dimensional domain Omega: a solid.
//
// The interface the dimension-generic parts take from a domain (clouds, the background
// lattice, the quadrature), the same as the plane Domain's: the bounding box, the inside test
// of the closed solid and the measure (volume). Its boundary is a surface of flat triangles,
// each oriented outward ((b - a) x (c - a) points out of the solid) and in one named part;
// the conditions of a problem select pieces of it (geometry/boundary_selection.hpp).
//
// For now a solid is an axis-aligned box [lo, hi] (length units), inside which every cell of
// a lattice fitted to it is whole, its surface two triangles per face in the parts x_min,
// x_max, y_min, y_max, z_min, z_max; solids from gmsh (.geo, .msh, STEP/BREP/IGES through
// OpenCASCADE) with curved surfaces and cut cells take the same interface.

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

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

class Solid {
 public:
  static constexpr int dim = 3;

  /// The box [lo, hi]; InputError unless lo < hi in every coordinate (all finite).
  static Solid box(const Point<3>& lo, const Point<3>& hi);

  [[nodiscard]] const AlignedBox<3>& bounding_box() const { return box_; }
  /// Whether x lies in the closed solid.
  [[nodiscard]] bool contains(const Point<3>& x) const { return box_.contains(x); }
  /// |Omega| (length units cubed).
  [[nodiscard]] double measure() const { return box_.volume(); }
  /// The boundary: outward triangles.
  [[nodiscard]] const std::vector<SurfaceTriangle>& surface() const { return surface_; }
  /// The names of the surface's parts, in the order SurfaceTriangle::part counts them.
  [[nodiscard]] const std::vector<std::string>& parts() const { return parts_; }

 private:
  Solid(const AlignedBox<3>& box, std::vector<SurfaceTriangle> surface, std::vector<std::string> parts)
      : box_(box), surface_(std::move(surface)), parts_(std::move(parts)) {}
  AlignedBox<3> box_;
  std::vector<SurfaceTriangle> surface_;
  std::vector<std::string> parts_;
};

}  // namespace mfree

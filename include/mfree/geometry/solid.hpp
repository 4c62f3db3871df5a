#pragma once
// The three-dimensional domain Omega: a solid.
//
// The interface the dimension-generic parts take from a domain (clouds, the background
// lattice, the quadrature), the same as the plane Domain's: the bounding box, the inside test
// of the closed solid and the measure (volume).
//
// For now a solid is an axis-aligned box [lo, hi] (length units), inside which every cell of
// a lattice fitted to it is whole; solids from gmsh (.geo, .msh, STEP/BREP/IGES through
// OpenCASCADE) with curved surfaces and cut cells take the same interface.

#include <Eigen/Geometry>

#include "mfree/core/types.hpp"

namespace mfree {

/// An axis-aligned box in dim dimensions: min() and max() corners, sizes(), volume().
template <int dim>
using AlignedBox = Eigen::AlignedBox<double, dim>;

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

 private:
  explicit Solid(const AlignedBox<3>& box) : box_(box) {}
  AlignedBox<3> box_;
};

}  // namespace mfree

#pragma once
// The three-dimensional domain Omega: a solid.
//
// The interface the dimension-generic parts take from a domain (clouds, the background
// lattice, the quadrature), the same as the plane Domain's: the bounding box, the inside test
// of the closed solid, the measure (volume), and whether an axis-aligned cell lies wholly
// inside (such a cell takes the lattice's Newton–Cotes weights, any other is cut).
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
  /// Whether the closed cell [lo, hi] lies wholly in the closed solid.
  [[nodiscard]] bool contains_cell(const Point<3>& lo, const Point<3>& hi) const {
    return box_.contains(AlignedBox<3>(lo, hi));
  }
  /// |Omega| (length units cubed).
  [[nodiscard]] double measure() const { return box_.volume(); }

 private:
  explicit Solid(const AlignedBox<3>& box) : box_(box) {}
  AlignedBox<3> box_;
};

}  // namespace mfree

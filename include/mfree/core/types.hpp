#pragma once
// Basic types shared by every part of mfree.
//
// Coordinates are in the problem's own length unit; mfree never assumes one.
// Points of the dimension-generic parts are Point<dim> (dim = 2 or 3, explicitly
// instantiated in the .cpp files); the plane parts use Vec2 = Point<2>. Indices of points
// into clouds are 32-bit: a cloud holds at most 2^31 - 1 points, far above what fits the
// memory of the machines we target.

#include <Eigen/Core>
#include <cstdint>

namespace mfree {

template <int dim>
using Point = Eigen::Matrix<double, dim, 1>;
/// A second-order tensor (dim x dim): deformation gradients, stresses.
template <int dim>
using Tensor2 = Eigen::Matrix<double, dim, dim>;

using Vec2 = Point<2>;
using Vec3 = Point<3>;
using Mat2 = Tensor2<2>;
using Index = std::int32_t;

/// Axis-aligned box [lo.x, hi.x] x [lo.y, hi.y].
struct Box {
  Vec2 lo;
  Vec2 hi;
  [[nodiscard]] Vec2 size() const { return hi - lo; }
  [[nodiscard]] double area() const { return (hi - lo).prod(); }
  [[nodiscard]] bool contains(const Vec2& x) const {
    return x.x() >= lo.x() && x.x() <= hi.x() && x.y() >= lo.y() && x.y() <= hi.y();
  }
};

/// Twice the signed area of (a, b, c): > 0 when c lies left of a -> b (floating point, not
/// an exact predicate; callers compare it against tolerances).
inline double orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

}  // namespace mfree

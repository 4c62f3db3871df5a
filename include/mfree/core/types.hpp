#pragma once
// Basic types shared by every part of mfree.
//
// Coordinates are in the problem's own length unit; mfree never assumes one.
// Points are 2D (x, y). Indices of points into clouds are 32-bit: a cloud holds at
// most 2^31 - 1 points, far above what fits the memory of the machines we target.

#include <Eigen/Core>
#include <cstdint>

namespace mfree {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
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

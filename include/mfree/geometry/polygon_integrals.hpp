#pragma once
// Integrals over the interior of a polygonal ring by Green's theorem.
//
// For a ring x_0 .. x_{n-1} (closed implicitly by x_n = x_0) write
//   c_i = x_i y_{i+1} - x_{i+1} y_i.
// Then (Green's theorem with a polynomial integrand, exact for straight edges)
//   A        = 1/2 sum_i c_i                      (shoelace)
//   int x dA = 1/6 sum_i (x_i + x_{i+1}) c_i
//   int y dA = 1/6 sum_i (y_i + y_{i+1}) c_i.
// Both are signed: positive for counter-clockwise rings, negative for clockwise ones, so
// summing over an outer ring (CCW) and its holes (CW) integrates over the region between.

#include "mfree/core/types.hpp"
#include "mfree/geometry/domain.hpp"

namespace mfree {

/// Smallest box holding every vertex of a non-empty ring.
[[nodiscard]] Box ring_bounding_box(const Ring& ring);

/// Signed area enclosed by the ring (positive when counter-clockwise).
[[nodiscard]] double ring_area(const Ring& ring);

/// Signed integral of x over the ring's interior (positive orientation as ring_area).
[[nodiscard]] Vec2 ring_first_moment(const Ring& ring);

}  // namespace mfree

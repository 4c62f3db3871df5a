#pragma once
// Points on a tied interface of a solid (Solid::interfaces()) belong to both of its sides, as
// points on a plane crack or interface do (geometry/crack_faces.hpp): clouds give each side
// its own copy, moved off the face along its normal by crack_offset times the spacing, so
// that each copy lies in its region, whose points alone its support reaches (RKSettings::
// region_of).

#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/solid.hpp"

namespace mfree {

/// The points with each one within crack_tolerance * h of an interface triangle replaced by
/// its two copies (interface_copy), the one in the triangle's `from` region first.
std::vector<Point<3>> split_on_interfaces(const Solid& solid, const std::vector<Point<3>>& points, double h);

/// The copy of x, a point of interface triangle t, in `region` (t.from with sign -1, t.to
/// with +1): x moved crack_offset h along sign n; where that leaves the region (x on the rim,
/// where the interface meets the surface), also crack_offset h towards t's centroid. Throws
/// Error naming x when neither lies in the region.
Point<3> interface_copy(const Solid& solid, const InterfaceTriangle& t, const Point<3>& x, double sign,
                        int region, double h);

}  // namespace mfree

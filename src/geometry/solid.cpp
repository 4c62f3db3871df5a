#include "mfree/geometry/solid.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mfree/core/error.hpp"

namespace mfree {

Solid Solid::box(const Point<3>& lo, const Point<3>& hi) {
  if (!lo.allFinite() || !hi.allFinite() || !(lo.array() < hi.array()).all())
    throw InputError(
        fmt::format("solid box: the corners ({}) and ({}) do not span a box (each coordinate of the "
                    "first below the second, all finite)",
                    fmt::join(lo.begin(), lo.end(), ", "), fmt::join(hi.begin(), hi.end(), ", ")));
  return Solid(AlignedBox<3>(lo, hi));
}

}  // namespace mfree

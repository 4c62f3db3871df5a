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
  const AlignedBox<3> box(lo, hi);
  // Face `side` (0: min, 1: max) normal to `axis`: its corners in the order (u, v) = (0, 0),
  // (1, 0), (1, 1), (0, 1) along the next two axes, turned so that the triangles face out.
  std::vector<SurfaceTriangle> surface;
  std::vector<std::string> parts;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int part = static_cast<int>(parts.size());
      parts.push_back(fmt::format("{}_{}", "xyz"[axis], side == 0 ? "min" : "max"));
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      std::array<Point<3>, 4> c;
      for (int k = 0; k < 4; ++k) {
        c[k][axis] = side == 0 ? lo[axis] : hi[axis];
        c[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
        c[k][v] = k >= 2 ? hi[v] : lo[v];
      }
      // e_u x e_v = e_axis: counter-clockwise in (u, v) faces +axis, the max side.
      if (side == 0) std::swap(c[1], c[3]);
      surface.push_back({{c[0], c[1], c[2]}, part});
      surface.push_back({{c[0], c[2], c[3]}, part});
    }
  return Solid(box, std::move(surface), std::move(parts));
}

}  // namespace mfree

#include "mfree/geometry/interface_faces.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <utility>

#include "mfree/core/error.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/kernels/surface_visibility.hpp"
#include "mfree/search/cell_list.hpp"

namespace mfree {

std::vector<Point<3>> split_on_interfaces(const Solid& solid, const std::vector<Point<3>>& points, double h) {
  const std::vector<InterfaceTriangle>& faces = solid.interfaces();
  if (faces.empty() || points.empty()) return points;
  const double tolerance = crack_tolerance * h;
  // The first interface triangle each point lies on; -1: none.
  std::vector<int> face(points.size(), -1);
  const CellList<3> cells(points, h);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& v = faces[f].vertices;
    const Point<3> centroid = (v[0] + v[1] + v[2]) / 3.0;
    double spread = 0.0;
    for (const Point<3>& p : v) spread = std::max(spread, (p - centroid).norm());
    cells.for_each_in_box(centroid, spread + tolerance, [&](Index i, const Point<3>& p) {
      int& fi = face[static_cast<std::size_t>(i)];
      if (fi < 0 && (closest_point_on_triangle(p, v) - p).norm() <= tolerance) fi = static_cast<int>(f);
    });
  }
  std::vector<Point<3>> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (face[i] < 0) {
      out.push_back(points[i]);
      continue;
    }
    const InterfaceTriangle& t = faces[static_cast<std::size_t>(face[i])];
    for (const auto& [sign, region] : {std::pair{-1.0, t.from}, std::pair{1.0, t.to}})
      out.push_back(interface_copy(solid, t, points[i], sign, region, h));
  }
  return out;
}

Point<3> interface_copy(const Solid& solid, const InterfaceTriangle& t, const Point<3>& x, double sign,
                        int region, double h) {
  const Point<3> off = sign * crack_offset * h * t.area_normal().normalized();
  if (solid.region_at(x + off) == region) return x + off;
  // On the rim, where the interface meets the surface: a step towards the triangle's centroid too.
  const Point<3> centroid = (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0;
  const Point<3> inward = x + off + crack_offset * h * (centroid - x).normalized();
  if (solid.region_at(inward) == region) return inward;
  throw Error(fmt::format("interface point ({:.6g}): no point {:.3g} off it lies in region {} of the solid",
                          fmt::join(x.begin(), x.end(), ", "), crack_offset * h, region));
}

}  // namespace mfree

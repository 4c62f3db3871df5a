#pragma once
// Gauss points on the boundary segments of the domain: each segment is cut at the ends of
// the boundary parts that the conditions select (so that every piece lies in one part or in
// none), each such interval into pieces no longer than `max_length`, each piece carrying
// `gauss_points` Gauss–Legendre points. Exact for polynomials of degree 2 gauss_points - 1
// along straight segments, so sums of x n and 1 n over the whole boundary vanish/close to
// round-off (divergence theorem). The points of a crack face lie a tiny offset (1e-7 of
// max_length) into the material of that face (geometry/crack_faces.hpp), so that the data
// and the shape functions there belong to that face.

#include <vector>

#include "mfree/geometry/boundary_selection.hpp"

namespace mfree {

struct BoundaryQuadrature {
  std::vector<Vec2> points;
  std::vector<Vec2> normals;    ///< outward unit normals
  std::vector<Vec2> tangents;   ///< unit tangents, domain on their left (normal = tangent turned clockwise)
  std::vector<double> weights;  ///< length weights
  std::vector<Index> segment;   ///< index into Domain::boundary()
  [[nodiscard]] Index size() const { return static_cast<Index>(points.size()); }
};

/// Segments are cut at the ends of the pieces of `parts`.
BoundaryQuadrature boundary_quadrature(const Domain& domain, double max_length, int gauss_points,
                                       const std::vector<BoundarySelection>& parts = {});

}  // namespace mfree

#pragma once
// Gauss points on the boundary segments of the domain: each segment is cut at the ends of
// the boundary parts that the conditions select (so that every piece lies in one part or in
// none), each such interval into pieces no longer than `max_length`, each piece carrying
// `gauss_points` Gauss–Legendre points. Exact for polynomials of degree 2 gauss_points - 1
// along straight segments, so sums of x n and 1 n over the whole boundary vanish/close to
// round-off (divergence theorem). The points lie on the faces; on a crack face the shape
// functions are sampled a tiny offset (1e-7 of max_length) into its material
// (geometry/crack_faces.hpp), so that they are the functions of that face, and taken back to
// the face by boundary_functions(). The two faces of an interface between regions carry the
// same points (twin says which), for the terms that tie them.

#include <vector>

#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/geometry/boundary_selection.hpp"

namespace mfree {

struct BoundaryQuadrature {
  std::vector<Vec2> points;
  std::vector<Vec2> normals;    ///< outward unit normals
  std::vector<Vec2> tangents;   ///< unit tangents, domain on their left (normal = tangent turned clockwise)
  std::vector<double> weights;  ///< length weights
  std::vector<Index> segment;   ///< index into Domain::boundary()
  /// Per point on an interface face, the same point on the other face; -1 elsewhere.
  std::vector<Index> twin;
  /// Per point, where the shape functions are sampled: on a crack face a little into its
  /// material (crack_offset of max_length against the outward normal), elsewhere the point.
  std::vector<Vec2> samples;
  [[nodiscard]] Index size() const { return static_cast<Index>(points.size()); }
};

/// Segments are cut at the ends of the pieces of `parts`.
BoundaryQuadrature boundary_quadrature(const Domain& domain, double max_length, int gauss_points,
                                       const std::vector<BoundarySelection>& parts = {});

/// The trial functions and their gradients at the boundary points: sampled at `samples`, the
/// values taken to the face, phi_I + grad phi_I . (x - sample) (first order: exact for the
/// linear fields the RK functions reproduce, so a field continuous across an interface has no
/// jump there, and the data of a condition on a crack face meet u^h where they are given).
GalerkinQuadrature<2> boundary_functions(const RKShapeFunctions<2>& trial, const BoundaryQuadrature& bq);

}  // namespace mfree

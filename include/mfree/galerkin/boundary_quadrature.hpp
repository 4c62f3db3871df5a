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
//
// On a solid the same on its surface's flat triangles, cut at the boxes of the parts (below),
// and on both faces of its tied interfaces (Solid::interfaces()).
// boundary_part() matches a point to the first part that holds it: the one place the
// conditions of a problem meet the boundary.

#include <vector>

#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/geometry/boundary_selection.hpp"

namespace mfree {

template <int dim>
struct BoundaryQuadrature {
  std::vector<Point<dim>> points;
  std::vector<Point<dim>> normals;  ///< outward unit normals
  std::vector<double> weights;      ///< length (area) weights
  /// Per point, its boundary segment (index into Domain::boundary()) or surface triangle
  /// (Solid::surface()); on a solid's interface triangle k, surface().size() + k.
  std::vector<Index> segment;
  /// Per point, where the shape functions are sampled: on a crack face a little into its
  /// material (crack_offset of max_length against the outward normal), elsewhere the point.
  std::vector<Point<dim>> samples;
  /// Plane only: unit tangents, domain on their left (normal = tangent turned clockwise).
  std::vector<Point<dim>> tangents;
  /// Per point on an interface face, the same point on the other face; -1 elsewhere (empty
  /// when the domain has no interface; in a solid the `from` face's point comes first).
  std::vector<Index> twin;
  [[nodiscard]] Index size() const { return static_cast<Index>(points.size()); }
};

/// Segments are cut at the ends of the pieces of `parts`.
BoundaryQuadrature<2> boundary_quadrature(const Domain& domain, double max_length, int gauss_points,
                                          const std::vector<BoundarySelection<2>>& parts = {});
/// A solid's surface: each triangle cut by the boxes of the pieces of `parts` into convex
/// polygons each inside or outside every box, each polygon fanned into triangles, each of
/// those cut into m x m similar triangles with edges no longer than `max_length`, each of which
/// carries the collapsed (Duffy) product rule of gauss_points x gauss_points Gauss points
/// (exact for polynomials of total degree 2 gauss_points - 2 on flat triangles). The
/// interface triangles are cut the same way (no part selects them).
BoundaryQuadrature<3> boundary_quadrature(const Solid& solid, double max_length, int gauss_points,
                                          const std::vector<BoundarySelection<3>>& parts = {});

/// The first of `parts` that holds point x of boundary segment (surface triangle) `segment`;
/// -1: none. A point on a piece's end counts as in it.
int boundary_part(const Domain& domain, const std::vector<BoundarySelection<2>>& parts, Index segment,
                  const Vec2& x);
int boundary_part(const Solid& solid, const std::vector<BoundarySelection<3>>& parts, Index triangle,
                  const Point<3>& x);

/// The trial functions and their gradients at the boundary points: sampled at `samples`, the
/// values taken to the face, phi_I + grad phi_I . (x - sample) (first order: exact for the
/// linear fields the RK functions reproduce, so a field continuous across an interface has no
/// jump there, and the data of a condition on a crack face meet u^h where they are given).
template <int dim>
GalerkinQuadrature<dim> boundary_functions(const RKShapeFunctions<dim>& trial,
                                           const BoundaryQuadrature<dim>& bq);

}  // namespace mfree

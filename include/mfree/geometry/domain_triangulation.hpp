#pragma once
// A triangulation of the domain through a set of points, for contour plots of fields known
// at those points (e.g. displacements and stresses at the DOF nodes, written with
// io/vtk_output.hpp). The triangles only serve plotting; mfree's methods need no mesh.
//
// The triangulation is the constrained Delaunay triangulation of the points and the
// domain's boundary vertices, with every boundary segment as a constraint, restricted to
// the domain: holes and re-entrant notches stay empty, and the triangle areas add up to
// |Omega| up to round-off. Cracks are constraints too: no triangle spans a crack, whose
// faces carry the copies of the points on it (geometry/crack_faces.hpp), so a warped plot
// shows the crack open.
//
// Points may lie on the boundary. A point a little outside it — up to 1e-9 times the
// diagonal of the domain's bounding box, as lattice nodes meant to lie on a boundary do
// after round-off (clouds/point_cloud.hpp) — is moved onto the nearest boundary point (or a
// few ulps inside, where rounding leaves that point outside), so the triangles cover exactly
// the domain and the point remains a vertex of the plot.
//
// CGAL does the work; its headers stay in domain_triangulation.cpp.

#include <array>
#include <optional>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/domain.hpp"

namespace mfree {

struct Triangulation {
  /// Vertices: points[0 .. input_points) are the given points in their order (so fields
  /// computed at them map 1:1; those a round-off outside the domain moved into it, see
  /// above), then the boundary vertices that coincide with no given point, in ring order
  /// (domain.rings()), then the cracks' vertices: each (but a tip) twice, the triangles of
  /// each face using their own copy.
  std::vector<Vec2> points;
  /// Where each point's fields are sampled: the point itself, but a copy of a crack's vertex
  /// moved a little into its face (split_on_cracks with the shorter crack segment there as the
  /// spacing): at the vertex itself the functions of both faces meet (a ring of wrong stress
  /// round an inclusion).
  std::vector<Vec2> samples;
  /// Indices into points, counter-clockwise, each triangle of positive area.
  std::vector<std::array<Index, 3>> triangles;
  /// How many of `points` were given.
  Index input_points = 0;
};

/// Triangulates the domain through the given points (see above). A given point repeated
/// exactly is one vertex: triangles use one of its indices and never the others.
/// Throws InputError naming the index of the first point that is not finite or lies outside
/// the domain (beyond the tolerance above).
Triangulation triangulate_domain(const Domain& domain, const std::vector<Vec2>& points);

/// The triangles (counter-clockwise, positive area) of the region that the rings bound: the
/// faces of the constrained triangulation of their edges inside an odd number of them. For
/// pieces the polygon partition cannot take: a ring with a hole, or rings that touch
/// themselves or each other at a vertex (Domain::clip of a region with a hole whose vertex
/// lies on the box's side). Empty (no value) when rounding made two edges cross.
std::optional<std::vector<std::array<Vec2, 3>>> triangulate_rings(const std::vector<Ring>& rings);

}  // namespace mfree

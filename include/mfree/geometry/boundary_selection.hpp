#pragma once
// Parts of a domain's boundary picked by a scene's [[boundary]] selectors: pieces of the
// boundary segments (Domain::boundary()), each a parameter interval [t0, t1] of one segment
// a -> b (the points a + t (b - a)).
//
// Selectors:
//   part    the segments of a named part (gmsh physical curves; a rectangle's bottom, right,
//           top, left)
//   ring    every segment of ring k (0: the outer boundary, k >= 1: hole k)
//   edges   edges i of ring k, numbered as in the input: edge i runs from vertex i to vertex
//           i + 1 of the ring as written (WKT) or built
//   box     the parts of the segments inside a closed axis-aligned box: a segment is clipped
//           to the box, so a segment half inside counts half
// The faces of an interface between regions (Crack::interface()) are tied to each other:
// a box passes them by and naming one is an error.
// A selection may be empty; the caller decides that this is an error (it is, in scenes).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/solid.hpp"

namespace mfree {

/// A piece of the boundary of a dim-dimensional domain (specialised below).
template <int dim>
struct BoundaryPiece;

/// A piece of a plane boundary segment.
template <>
struct BoundaryPiece<2> {
  Index segment = 0;  ///< index into Domain::boundary()
  double t0 = 0.0;    ///< 0 <= t0 < t1 <= 1
  double t1 = 1.0;
};

/// A piece of a solid's surface triangle: the part of it inside `clip`, or all of it.
template <>
struct BoundaryPiece<3> {
  Index triangle = 0;                 ///< index into Solid::surface()
  std::optional<AlignedBox<3>> clip;  ///< none: the whole triangle
};

/// Pieces of the boundary, in segment (triangle) order, no two overlapping.
template <int dim>
using BoundarySelection = std::vector<BoundaryPiece<dim>>;

/// Total length of the pieces.
double selection_length(const Domain& domain, const BoundarySelection<2>& s);

/// The segments of the part named `name`; throws InputError when the domain has no part of
/// that name (the message lists the names it has).
BoundarySelection<2> select_part(const Domain& domain, const std::string& name);
/// Every segment of ring k; throws InputError when there is no ring k.
BoundarySelection<2> select_ring(const Domain& domain, int ring);
/// Edges `edges` of ring k; throws InputError for a ring or edge that does not exist.
BoundarySelection<2> select_edges(const Domain& domain, int ring, const std::vector<int>& edges);
/// The parameters [t0, t1] of the part of segment a -> b inside the closed box (Liang–Barsky
/// clipping), when that part has a positive length.
std::optional<std::array<double, 2>> segment_in_box(const Vec2& a, const Vec2& b, const Box& box);
/// The parts of the segments inside the closed box (segment_in_box).
BoundarySelection<2> select_box(const Domain& domain, const Box& box);

/// A solid's surface (Solid::surface()): the selectors part and box; a box keeps the part of
/// each triangle inside it, when that has a positive area.
BoundarySelection<3> select_part(const Solid& solid, const std::string& name);
BoundarySelection<3> select_box(const Solid& solid, const AlignedBox<3>& box);
/// Total area of the pieces.
double selection_area(const Solid& solid, const BoundarySelection<3>& s);
/// The area two selections share (pieces of one triangle, clipped by both boxes).
double overlap_area(const Solid& solid, const BoundarySelection<3>& a, const BoundarySelection<3>& b);
/// The piece of its triangle as a polygon.
std::vector<Point<3>> piece_polygon(const Solid& solid, const BoundaryPiece<3>& piece);

/// A short stretch of a selection round a corner: a piece cut inside its segment at one end
/// whose other end meets a selected piece of the next segment at a turn (a box drawn round one
/// edge clips the edges it crosses).
struct CornerSliver {
  BoundaryPiece<2> piece;
  Vec2 corner;        ///< where it meets the longer piece
  double length = 0;  ///< of the sliver
  double turn = 0;    ///< angle between the two pieces' directions [degrees]
};
/// The slivers of s: pieces as above that turn by more than `min_turn` degrees and are
/// shorter than `fraction` times the piece they meet.
std::vector<CornerSliver> corner_slivers(const Domain& domain, const BoundarySelection<2>& s,
                                         double min_turn = 20.0, double fraction = 0.1);

/// Length of the boundary that two selections share.
double overlap_length(const Domain& domain, const BoundarySelection<2>& a, const BoundarySelection<2>& b);

}  // namespace mfree

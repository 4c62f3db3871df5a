#pragma once
// Point clouds on a domain (a plane Domain or a Solid): DOF nodes and quadrature points.
//
// Every generator is seeded and reproducible: the same settings give the same points,
// bit for bit, on every run and thread count.
//
//   lattice    regular lattice of spacing h, fitted to the bounding box of the domain
//              (the spacing per axis is adjusted so an integer number of steps spans it);
//              vertex lattice (points on the box edges) or cell-centred lattice.
//   perturbed  the lattice, each point moved by a uniform random offset in
//              [-f h/2, f h/2]^dim (f: perturbation, a fraction of the spacing); a move that
//              leaves the domain is redrawn (up to 16 times, then the point stays put), so
//              points on the boundary stay in the closed domain.
//   random     round(|Omega| / h^dim) points uniformly distributed in the domain.
//
// Only points inside the closed domain are kept (lattice points up to round-off: a point
// meant to lie on the boundary may land a few ulps outside it).

#include <cstdint>
#include <functional>
#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/solid.hpp"

namespace mfree {

enum class CloudKind { lattice, perturbed, random };

struct CloudSettings {
  CloudKind kind = CloudKind::lattice;
  double spacing = 0.0;        ///< nominal spacing h > 0 (length units)
  double perturbation = 0.0;   ///< f in [0, 1], perturbed clouds only
  std::uint64_t seed = 1;      ///< random clouds and perturbations
  bool cell_centred = false;   ///< lattice points at cell centres instead of vertices
};

/// The points of a cloud inside the domain. Throws InputError for a bad spacing or
/// perturbation, or when no point falls inside the domain.
std::vector<Vec2> make_cloud(const Domain& domain, const CloudSettings& settings);
std::vector<Point<3>> make_cloud(const Solid& solid, const CloudSettings& settings);

/// A quadrature cloud for a DOF cloud: about `ratio` points per node (ratio >= 1), of the
/// same kind, spacing h / ratio^(1/dim), cell-centred, seeded differently from the nodes.
std::vector<Vec2> make_quadrature_cloud(const Domain& domain, const CloudSettings& nodes, double ratio);
std::vector<Point<3>> make_quadrature_cloud(const Solid& solid, const CloudSettings& nodes, double ratio);

/// Support radii for a cloud of spacing h in a solid: a_I = factor h, and (factor + 1/2) h
/// for the nodes near a point of the surface whose neighbours within factor h lie too flat for
/// an RK basis of degree `order` (1 or 2). Where the surface runs nearly parallel to a lattice
/// plane (the poles of a sphere) the solid reaches past the last plane of nodes by up to h, and
/// a point in that cap can find within factor h nodes of one plane only (linear RK, factor 2),
/// or of two (quadratic, factor 3): its moment matrix is singular (seen on Lamé's sphere at
/// h = 0.05). The surface, and both sides of each tied interface (Solid::interfaces(), where
/// supports end as at the surface), is sampled at spacing h / 4 or finer; a sample is flat when its
/// neighbours' extent along their thinnest direction (the covariance's least eigenvector) is
/// below 0.75 order h (one plane of a lattice, or two for quadratic RK). The nodes within
/// (factor + 1/2) h of a flat sample then reach it, and the next plane down lies within that:
/// depth at most (order + 1) h, offset at most h / sqrt(2), so sqrt((order + 1)^2 + 1/2) h =
/// 2.12 h or 3.08 h. Faces on a lattice plane (boxes, planes of symmetry) are not flat in this
/// sense and keep factor h. Returns an empty vector when every radius is factor h.
/// `unseen`, when given, removes from a sample's neighbours (indices into `nodes`) those its
/// supports do not reach (the visibility rule: the wall of a gap sees the nodes on its own
/// side only; tied regions: the nodes of the sample's region only).
std::vector<double> surface_support_radii(
    const Solid& solid, const std::vector<Point<3>>& nodes, double h, double factor, int order,
    const std::function<void(const Point<3>& sample, std::vector<Index>& near)>& unseen = {});

/// lattice, perturbed, random: the names scenes use.
const NameTable<CloudKind>& cloud_kind_names();
std::string_view to_string(CloudKind kind);

}  // namespace mfree

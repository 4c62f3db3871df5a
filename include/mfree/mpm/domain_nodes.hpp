#pragma once
// The nodes through which the CPDIs integrate over a particle domain (SPEC section 11): the
// domain is one isoparametric element with nodes y_k and shape functions M_k, a grid hat N_i
// is replaced by its interpolant sum_k N_i(y_k) M_k, and so
//
//   S_ip = sum_k w_k N_i(y_k),   G_ip = (1 / V) sum_k N_i(y_k) g_k,
//   w_k = (1 / V) int_{Omega_p} M_k dA,   g_k = int_{Omega_p} grad M_k dA = oint M_k n ds,
//
// the last by the divergence theorem. Corners are counter-clockwise, and
// perp(d) = (d_y, -d_x) turns a counter-clockwise edge into its outward normal times length.
//
//   bilinear_nodes (lCPDI, CPDI2; Sadeghirad, Brannon, Guilkey 2013): the 4 corners c_k and
//     the bilinear M_k of the quadrilateral. The map's Jacobian is linear in (xi, eta); at
//     corner k it is J_k = (c_{k+1} - c_k) x (c_{k-1} - c_k) / 4, the area is V = sum_k J_k
//     and int M_k dA = int_{[-1,1]^2} M_k J dxi deta = V / 6 + J_k / 3, so
//       w_k = 1/6 + J_k / (3 V)   (1/4 for a parallelogram),
//       g_k = perp(c_{k+1} - c_{k-1}) / 2   (M_k is linear along the edges).
//     Some J_k <= 0 (a domain not convex, degenerate or inverted) is a NumericalError.
//   serendipity_nodes (qCPDI; Sadeghirad, Brannon, Burghardt 2011): the parallelogram
//     x + F (+-l_x, +-l_y) with the 8-node serendipity element, nodes 0-3 its corners, 4-7 the
//     midsides of edges c_0 c_1, c_1 c_2, c_2 c_3, c_3 c_0. The map is affine (J = V / 4), so
//     w_k = (1/4) int_{[-1,1]^2} M_k: -1/12 at each corner and 1/3 at each midside; along an
//     edge M_k is the quadratic Lagrange function (Simpson's weights 1/6, 2/3, 1/6), so
//       g_k = perp(c_{k+1} - c_{k-1}) / 6 at corner k, 2 perp(c_{k+1} - c_k) / 3 at midside k.
//     V = 4 l_x l_y det F <= 0 is a NumericalError.
//
// Both elements reproduce linear fields, so sum_k w_k = 1, sum_k w_k y_k is the domain's area
// centroid, sum_k g_k = 0 and sum_k y_k g_k^T = V I. Errors name the method and the particle
// position x.

#include <array>

#include "mfree/core/types.hpp"
#include "mfree/mpm/particles.hpp"

namespace mfree {

/// The nodes of a particle domain's element.
template <int n>
struct DomainNodes {
  std::array<Vec2, n> point;     ///< y_k [m]
  std::array<double, n> weight;  ///< w_k = (1 / V) int M_k, dimensionless
  std::array<Vec2, n> gradient;  ///< g_k = int grad M_k [m]
  double volume = 0.0;           ///< V [m^2 per unit thickness]
};

/// The bilinear element on corners c of the particle at x (see above); method names it in
/// errors.
DomainNodes<4> bilinear_nodes(const DomainCorners& c, const Vec2& x, const char* method);

/// The serendipity element on the parallelogram x + F (+-l_x, +-l_y) (see above).
DomainNodes<8> serendipity_nodes(const Vec2& x, const Mat2& F, const Vec2& half);

/// The corners x + F (+-l_x, +-l_y), counter-clockwise from (-l_x, -l_y): the parallelogram
/// of lCPDI and qCPDI, and the reference domain CPDI2's corners start from (F = I).
DomainCorners parallelogram_corners(const Vec2& x, const Mat2& F, const Vec2& half);

}  // namespace mfree

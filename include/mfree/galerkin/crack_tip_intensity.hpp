#pragma once
// Stress intensity factors at every crack tip of a domain from a small-strain solution
// u^h = sum phi_I d_I: the interaction integral (interaction_integral.hpp) over an annulus
// about each tip, sampled with 4 x 4 Gauss points on cells of h / 2 (a point on the crack
// split to both faces, quadrature/gauss_cells.hpp), the smooth weight q.
//
// The annulus: the tip's room R is 0.9 of the distance to the nearest of the end of its
// straight last crack segment, another crack and the domain's boundary (the domain form needs
// straight traction-free faces and no other boundary inside it); the outer radius is
// r1 = max(4 h, R / 2), at most R (h the nodal spacing), and the inner one r1 / 2. Once
// 4 h < R / 2 the annulus no longer shrinks with h: at a fixed number of spacings from the
// tip the relative error of u^h does not fall, and K converged as h^0.4 to h^0.9
// (verification/crack-plate). The radius used is reported with the factors.

#include <string>
#include <vector>

#include "mfree/galerkin/exact_elasticity.hpp"
#include "mfree/galerkin/interaction_integral.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"

namespace mfree {

struct TipIntensity {
  std::string crack;   ///< the crack's name
  int end = 0;         ///< 0: its first point, 1: its last
  CrackTipFrame frame; ///< tip and direction of extension
  double outer_radius = 0.0;  ///< r1 of the annulus used (length)
  StressIntensity k;          ///< NaN when loaded_by is set
  /// The condition on the crack's faces, when one holds there (a slip face used as a
  /// symmetry hold): the domain form needs traction-free faces, so the tip has no K.
  std::string loaded_by;
};

/// K_I, K_II and J at every tip (in crack order, first end before last) for coefficients d of
/// the trial functions; `h` the nodal spacing. Throws InputError when a tip has no room for
/// an annulus of one spacing. The law is the tip's region's (the annulus stops short of other
/// cracks and interfaces, so it lies in that region). `face_conditions`: per crack, the name
/// of a condition on its faces, empty when they are traction free (or an empty list: all
/// free); such a crack's tips are listed with loaded_by set and no K.
std::vector<TipIntensity> crack_tip_intensities(const Domain& domain, const RKShapeFunctions<2>& trial,
                                                const Eigen::VectorXd& d, const LawAt& law_at, double h,
                                                const std::vector<std::string>& face_conditions = {});

}  // namespace mfree

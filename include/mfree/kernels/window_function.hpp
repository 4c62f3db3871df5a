#pragma once
// Window (weight) functions of the reproducing-kernel construction, in the normalised
// distance r = |x - x_I| / a, with support r < 1 (a: support radius, length units).
//
// Both are non-negative, C1 at least, and have w'(0) = 0, so the gradient of a circular
// window is well defined at its own node.

#include <algorithm>
#include <cmath>
#include <string_view>

#include "mfree/core/name_table.hpp"

namespace mfree {

enum class Window {
  cubic_bspline,     ///< SPEC section 1: C2 cubic B-spline, w(0) = 2/3
  quadratic_spline,  ///< seed 000 eq. (17), stretched from 3/2 to 1: C1, w(0) = 3/4
};

/// Value w(r) and derivative dw/dr of a window at r >= 0.
struct WindowValue {
  double w;
  double dw;
};

/// Cubic B-spline (SPEC section 1):
///   2/3 - 4r^2 + 4r^3 (r <= 1/2),  4/3 - 4r + 4r^2 - 4/3 r^3 (1/2 < r <= 1),  0 beyond.
/// Both pieces are formed and one is selected, without a branch: r is effectively random
/// from neighbour to neighbour, and the mispredicted branches of the piecewise form were a
/// large share of a kernel evaluation.
inline WindowValue cubic_bspline(double r) {
  const double inner_w = 2.0 / 3.0 - 4.0 * r * r + 4.0 * r * r * r, inner_dw = -8.0 * r + 12.0 * r * r;
  const double s = std::max(1.0 - r, 0.0);  // 4/3 (1 - r)^3 expands to the SPEC polynomial
  const double outer_w = 4.0 / 3.0 * s * s * s, outer_dw = -4.0 * s * s;
  const bool inner = r <= 0.5;
  return {inner ? inner_w : outer_w, inner ? inner_dw : outer_dw};
}

/// Quadratic spline of seed 000 eq. (17), written in rho = 3r/2 so that its support
/// |rho| < 3/2 becomes r < 1: 3/4 - rho^2 (rho <= 1/2), (3/2 - rho)^2 / 2 (rho <= 3/2).
/// The seed's kernel with r_x = (x - x_p) / (2 l_x) is this one with a = 3 l_x. Branchless,
/// as cubic_bspline().
inline WindowValue quadratic_spline(double r) {
  const double rho = 1.5 * r;
  const double s = std::max(1.5 - rho, 0.0);
  const bool inner = rho <= 0.5;
  return {inner ? 0.75 - rho * rho : 0.5 * s * s, inner ? -2.0 * rho * 1.5 : -s * 1.5};
}

inline WindowValue evaluate_window(Window kind, double r) {
  return kind == Window::cubic_bspline ? cubic_bspline(r) : quadratic_spline(r);
}

/// cubic_bspline, quadratic_spline: the names scenes use.
const NameTable<Window>& window_names();
std::string_view to_string(Window kind);

}  // namespace mfree

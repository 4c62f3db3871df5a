#pragma once
// Refinement studies without an exact solution (SPEC section 8): at each level the probe's
// value u_k, its change |u_k - u_{k-1}| from the level before, the observed rate p of that
// change over the last three levels, p = log(|u_{k-1} - u_{k-2}| / |u_k - u_{k-1}|) /
// log(h_{k-2} / h_{k-1}), and the Richardson-extrapolated value of each component,
// u + (u - u_{k-1}) / ((h_{k-1} / h_k)^p - 1).

#include <string>
#include <utility>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree {

/// The last level's columns, formatted ("-" where not defined yet: fewer than two or three
/// levels, or a change that does not shrink).
struct ProbeLevel {
  std::string change = "-";
  std::string rate = "-";
  std::string extrapolated_x = "-";
  std::string extrapolated_y = "-";
  std::string extrapolated_z = "-";  ///< in 3D
};

/// levels: (h, u at the probe), coarse to fine; the columns of the last one (dim 2 or 3).
template <int dim>
ProbeLevel probe_level(const std::vector<std::pair<double, Point<dim>>>& levels);

}  // namespace mfree

#include "mfree/core/step_count.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mfree/core/error.hpp"

namespace mfree {

int step_count(double end_time, double dt, std::string_view what) {
  const double n = std::ceil(end_time / dt * (1.0 - 1e-12));
  if (!std::isfinite(n) || !(n <= max_time_steps))
    throw InputError(
        fmt::format("{}: end_time {:.6g} s in steps of at most {:.6g} s takes {:.4g} steps, more than "
                    "the {:.0e} a run may take (check the units of end_time and time_step)",
                    what, end_time, dt, n, max_time_steps));
  return std::max(1, static_cast<int>(n));
}

}  // namespace mfree

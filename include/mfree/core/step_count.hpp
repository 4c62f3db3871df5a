#pragma once
// The number of equal time steps that cover a run, computed in floating point so that no
// end time or step size can overflow it: n = ceil(end_time / dt) (within 1e-12 relative, so
// a step that divides the end time exactly is not split), refused above max_time_steps.

#include <string_view>

namespace mfree {

/// The most time steps a run may take (far above any run that fits a day on this machine;
/// more is taken to be a mistake of units).
inline constexpr double max_time_steps = 1e9;

/// n >= 1 with end_time / n <= dt (to 1e-12 relative). InputError, naming `what` (the run), the end time, the
/// step and the count, for a count above max_time_steps or a non-finite one.
int step_count(double end_time, double dt, std::string_view what);

}  // namespace mfree

#pragma once
// Memory checks before large allocations: a run that cannot fit this machine is refused at
// the start, saying how much it needs and how much there is, instead of dying in an
// allocation (or in the swap) part of the way through.

#include <string_view>

namespace mfree {

/// Bytes the machine can still give: MemAvailable of /proc/meminfo; infinity when unknown.
double available_memory();

/// InputError when `bytes` (an estimate, or a lower bound, of what `what` allocates) exceed
/// available_memory(); the message gives both in GiB. Also for a non-finite estimate.
void check_memory(double bytes, std::string_view what);

}  // namespace mfree

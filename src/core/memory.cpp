#include "mfree/core/memory.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "mfree/core/error.hpp"

namespace mfree {

double available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  double value = 0.0;
  while (in >> key >> value >> unit)
    if (key == "MemAvailable:") return value * 1024.0;  // kB
  return std::numeric_limits<double>::infinity();
}

void check_memory(double bytes, std::string_view what) {
  const double available = available_memory();
  if (std::isfinite(bytes) && bytes <= available) return;
  constexpr double gib = 1024.0 * 1024.0 * 1024.0;
  throw InputError(
      fmt::format("{} needs about {:.3g} GiB of memory; this machine has {:.3g} GiB available "
                  "(coarsen the problem)",
                  what, bytes / gib, available / gib));
}

}  // namespace mfree

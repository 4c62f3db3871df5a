#include "mfree/core/memory.hpp"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "mfree/core/error.hpp"

namespace mfree {

namespace fs = std::filesystem;

namespace {

constexpr double unlimited = std::numeric_limits<double>::infinity();

/// The first number in a file: a byte count, or infinity for "max", a missing file or a value
/// beyond 2^60 (cgroup v1 writes its "no limit" as a number near 2^63).
double bytes_in(const fs::path& file) {
  std::ifstream in(file);
  std::string word;
  if (!(in >> word) || word == "max") return unlimited;
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  return (end == word.c_str() || value > std::ldexp(1.0, 60)) ? unlimited : value;
}

MemoryRoom machine_room() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  double value = 0.0;
  while (in >> key >> value >> unit)
    if (key == "MemAvailable:") return {value * 1024.0, "this machine's available memory"};  // kB
  return {unlimited, ""};
}

MemoryRoom address_space_room() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return {unlimited, ""};
  std::ifstream in("/proc/self/statm");
  double pages = 0.0;  // the first field: the size of the address space in pages
  in >> pages;
  const double mapped = pages * static_cast<double>(::sysconf(_SC_PAGESIZE));
  return {
      std::max(0.0, static_cast<double>(limit.rlim_cur) - mapped),
      fmt::format("the address-space limit of {:.3g} GiB (ulimit -v)", limit.rlim_cur / std::ldexp(1.0, 30))};
}

}  // namespace

MemoryRoom cgroup_room(const fs::path& root, std::string_view proc_self_cgroup) {
  MemoryRoom least{unlimited, ""};
  std::istringstream lines{std::string(proc_self_cgroup)};
  for (std::string line; std::getline(lines, line);) {
    // "ID:CONTROLLERS:PATH": v2 has ID 0 and no controllers, v1's memory group names "memory".
    const auto first = line.find(':');
    const auto second = first == std::string::npos ? first : line.find(':', first + 1);
    if (second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const fs::path path = fs::path(line.substr(second + 1)).relative_path();
    const bool v2 = line.compare(0, first, "0") == 0 && controllers.empty();
    if (!v2 && controllers.find("memory") == std::string::npos) continue;
    const fs::path hierarchy = v2 ? root : root / "memory";
    const char* max = v2 ? "memory.max" : "memory.limit_in_bytes";
    const char* used = v2 ? "memory.current" : "memory.usage_in_bytes";
    // The group and its ancestors; inside a container the path may not exist under the
    // mount, whose top is then the container's own group.
    for (fs::path group = path;; group = group.parent_path()) {
      const fs::path folder = hierarchy / group;
      const double limit = bytes_in(folder / max);
      if (std::isfinite(limit)) {
        const double current = bytes_in(folder / used);
        const double room = std::max(0.0, limit - (std::isfinite(current) ? current : 0.0));
        if (room < least.bytes)
          least = {room, fmt::format("the memory limit of {:.3g} GiB of control group {}",
                                     limit / std::ldexp(1.0, 30), folder.string())};
      }
      if (group.empty()) break;
    }
  }
  return least;
}

MemoryRoom available_memory() {
  std::ifstream in("/proc/self/cgroup");
  const std::string groups((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  MemoryRoom least = machine_room();
  for (const MemoryRoom& room : {address_space_room(), cgroup_room("/sys/fs/cgroup", groups)})
    if (room.bytes < least.bytes) least = room;
  return least;
}

void check_memory(double bytes, std::string_view what) {
  constexpr double gib = 1024.0 * 1024.0 * 1024.0;
  if (!std::isfinite(bytes))
    throw InputError(fmt::format("{} needs more memory than can be counted (coarsen the problem)", what));
  const MemoryRoom room = available_memory();
  if (bytes <= room.bytes) return;
  throw InputError(
      fmt::format("{} needs about {:.3g} GiB of memory; {:.3g} GiB are available under {} "
                  "(coarsen the problem)",
                  what, bytes / gib, room.bytes / gib, room.limit));
}

}  // namespace mfree

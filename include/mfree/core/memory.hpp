#pragma once
// Memory checks before large allocations: a run that cannot fit is refused at the start,
// saying how much it needs, how much there is and which limit binds, instead of dying in an
// allocation (or in the swap) part of the way through.
//
// What this process may still allocate is the least of (bytes):
//   - the machine's MemAvailable (/proc/meminfo);
//   - its address-space limit (RLIMIT_AS, `ulimit -v`) less the address space it has mapped
//     (/proc/self/statm);
//   - for each control group it is in (cgroup v2 memory.max less memory.current, cgroup v1
//     memory.limit_in_bytes less memory.usage_in_bytes), and each ancestor of that group,
//     the room left under the group's limit (a container's or a batch job's memory).

#include <filesystem>
#include <string>
#include <string_view>

namespace mfree {

/// Bytes that may still be allocated and the limit that gives them, for messages.
struct MemoryRoom {
  double bytes;       ///< infinity when no limit is known
  std::string limit;  ///< e.g. "this machine's available memory"
};

/// The least of the three rooms above.
MemoryRoom available_memory();

/// The room under the memory limits of the control groups listed in `proc_self_cgroup` (the
/// text of /proc/self/cgroup) and their ancestors, in the hierarchy mounted at `root`
/// (/sys/fs/cgroup); a group whose files are absent is skipped. Infinity when none limits.
MemoryRoom cgroup_room(const std::filesystem::path& root, std::string_view proc_self_cgroup);

/// InputError when `bytes` (an estimate, or a lower bound, of what `what` allocates) exceed
/// available_memory(); the message gives both in GiB and names the limit. Also for a
/// non-finite estimate.
void check_memory(double bytes, std::string_view what);

}  // namespace mfree

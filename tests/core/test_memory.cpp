#include <sys/resource.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <string>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"

namespace fs = std::filesystem;
using mfree::testing::message_of;
using mfree::testing::ScratchFolder;

namespace {

void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

}  // namespace

TEST_CASE("memory: the room under control-group limits is the least over the group and its ancestors",
          "[core][memory]") {
  ScratchFolder root("cgroups");
  const double gib = std::ldexp(1.0, 30);
  // cgroup v2: a job's group under a user slice; the slice limits harder than the job.
  write(root.path / "user.slice/memory.max", std::to_string(static_cast<long long>(8 * gib)) + "\n");
  write(root.path / "user.slice/memory.current", std::to_string(static_cast<long long>(7 * gib)) + "\n");
  write(root.path / "user.slice/job/memory.max", std::to_string(static_cast<long long>(6 * gib)) + "\n");
  write(root.path / "user.slice/job/memory.current", std::to_string(static_cast<long long>(2 * gib)) + "\n");
  write(root.path / "memory.max", "max\n");
  const mfree::MemoryRoom v2 = mfree::cgroup_room(root.path, "0::/user.slice/job\n");
  CHECK(v2.bytes == 1 * gib);
  CHECK_THAT(v2.limit, Catch::Contains("8 GiB") && Catch::Contains("user.slice"));

  // cgroup v1: the memory controller's hierarchy; "no limit" is written as a number near 2^63.
  write(root.path / "memory/batch/memory.limit_in_bytes", std::to_string(static_cast<long long>(3 * gib)));
  write(root.path / "memory/batch/memory.usage_in_bytes", std::to_string(static_cast<long long>(gib / 2)));
  write(root.path / "memory/memory.limit_in_bytes", "9223372036854771712");
  const mfree::MemoryRoom v1 = mfree::cgroup_room(root.path, "5:cpu:/\n4:memory:/batch\n");
  CHECK(v1.bytes == 2.5 * gib);

  // A group whose path is not under the mount (inside a container) is looked up from its top.
  write(root.path / "memory/memory.limit_in_bytes", std::to_string(static_cast<long long>(gib)));
  write(root.path / "memory/memory.usage_in_bytes", std::to_string(static_cast<long long>(gib / 4)));
  CHECK(mfree::cgroup_room(root.path, "4:memory:/elsewhere/abc\n").bytes == 0.75 * gib);
  // No limit anywhere.
  CHECK(std::isinf(mfree::cgroup_room(root.path / "none", "0::/\n").bytes));
  CHECK(std::isinf(mfree::cgroup_room(root.path, "garbage\n").bytes));
}

TEST_CASE("memory: the address-space limit bounds the room; a need past it is refused naming it",
          "[core][memory]") {
  const double gib = std::ldexp(1.0, 30);
  rlimit before{};
  REQUIRE(::getrlimit(RLIMIT_AS, &before) == 0);
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0;
  statm >> pages;
  const double mapped = pages * static_cast<double>(::sysconf(_SC_PAGESIZE));
  rlimit limit = before;
  limit.rlim_cur = static_cast<rlim_t>(mapped + gib);  // one GiB more than is mapped now
  if (before.rlim_max != RLIM_INFINITY) limit.rlim_cur = std::min(limit.rlim_cur, before.rlim_max);
  REQUIRE(::setrlimit(RLIMIT_AS, &limit) == 0);
  const mfree::MemoryRoom room = mfree::available_memory();
  const std::string refused =
      message_of([] { mfree::check_memory(2.0 * std::ldexp(1.0, 30), "a test cloud"); });
  ::setrlimit(RLIMIT_AS, &before);
  CHECK(room.bytes <= gib);
  CHECK(room.bytes > 0.9 * gib);  // what Catch2 mapped meanwhile is far below 100 MiB
  CHECK_THAT(room.limit, Catch::Contains("ulimit -v"));
  CHECK_THAT(refused, Catch::Contains("a test cloud needs about 2 GiB") && Catch::Contains("ulimit -v"));
  CHECK_THROWS_AS(mfree::check_memory(std::nan(""), "x"), mfree::InputError);
}

// Parallel loops: an exception thrown in several blocks reaches the caller as that of the
// lowest failing index, whatever the threads' timing.

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

#include "mfree/core/parallel.hpp"

using namespace mfree;

namespace {

/// The message of the exception f throws ("" if none).
template <class F>
std::string thrown_by(F&& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("parallel loops: the failure at the lowest index wins, on every run", "[core]") {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(std::max(2, threads));
  // Points 7, 3001 and 9000 fail; point 7 only once another has failed (or after a second),
  // so that a loop keeping the first exception in time would report 3001 or 9000.
  std::atomic<bool> other{false};
  const auto check = [&](Index p) {
    if (p == 3001 || p == 9000) {
      other = true;
      throw std::runtime_error(std::to_string(p));
    }
    if (p != 7) return;
    const auto start = std::chrono::steady_clock::now();
    while (!other && std::chrono::steady_clock::now() - start < std::chrono::seconds(1))
      std::this_thread::yield();
    throw std::runtime_error("7");
  };
  for (int run = 0; run < 3; ++run) {
    other = false;
    const std::string blocks = thrown_by([&] {
      parallel_blocks(10000, 16, [&](Index begin, Index end) {
        for (Index p = begin; p < end; ++p) check(p);
      });
    });
    CHECK(blocks == "7");
    other = false;
    const std::string ranges = thrown_by([&] {
      parallel_ranges(10000, [&](int, Index begin, Index end) {
        for (Index p = begin; p < end; ++p) check(p);
      });
    });
    CHECK(ranges == "7");  // the first range's, though the others failed before it
  }
  omp_set_num_threads(threads);
}

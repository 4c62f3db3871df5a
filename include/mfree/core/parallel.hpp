#pragma once
// Parallel loops over point ranges (OpenMP).
//
// Per-point kernels stay free of threading: a caller hands a range body to
// parallel_blocks(), which splits [0, n) into blocks and runs each block on one thread.
// A body may allocate its scratch once per block. An exception thrown inside a block is
// carried out of the parallel region and rethrown on the calling thread: that of the lowest
// block (parallel_blocks) or range (parallel_ranges), whatever the threads' timing. A body
// that throws at the first failing point of its block thus reports the lowest failing index
// of all, as a serial loop would, the same in every run.

#include <atomic>
#include <exception>

#include <omp.h>

#include "mfree/core/types.hpp"

namespace mfree {

/// Number of threads parallel loops use (OpenMP's, set by OMP_NUM_THREADS).
int thread_count();

/// Runs body(begin, end) over consecutive blocks of [0, n) of at most `block` items.
template <class Body>
void parallel_blocks(Index n, Index block, Body&& body) {
  if (n <= 0) return;
  const Index nblocks = (n + block - 1) / block;
  std::exception_ptr error;
  // The lowest block that failed so far (nblocks: none); blocks above it are skipped, those
  // below still run, as one of them may fail at a lower index.
  std::atomic<Index> failed{nblocks};
#pragma omp parallel for schedule(dynamic, 1)
  for (Index b = 0; b < nblocks; ++b) {
    if (b > failed.load(std::memory_order_relaxed)) continue;
    try {
      const Index begin = b * block;
      const Index end = begin + block < n ? begin + block : n;
      body(begin, end);
    } catch (...) {
#pragma omp critical(mfree_parallel_error)
      if (b < failed.load(std::memory_order_relaxed)) {
        error = std::current_exception();
        failed.store(b, std::memory_order_relaxed);
      }
    }
  }
  if (error) std::rethrow_exception(error);
}

/// Splits [0, n) into one contiguous range per thread and runs body(thread, begin, end),
/// thread in [0, thread_count()). With a fixed thread count the split is fixed, so
/// per-thread partial sums combined in thread order give reproducible results.
template <class Body>
void parallel_ranges(Index n, Body&& body) {
  std::exception_ptr error;
  int failed = -1;  // the lowest thread (range) that failed
#pragma omp parallel
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const Index begin = static_cast<Index>(static_cast<std::int64_t>(n) * t / nt);
    const Index end = static_cast<Index>(static_cast<std::int64_t>(n) * (t + 1) / nt);
    try {
      body(t, begin, end);
    } catch (...) {
#pragma omp critical(mfree_parallel_error)
      if (failed < 0 || t < failed) {
        error = std::current_exception();
        failed = t;
      }
    }
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace mfree

#pragma once
// Work in a child process under a wall-time and a memory limit: for libraries that may crash,
// loop forever or allocate without bound on bad input (libgmsh), so that neither takes this
// process down with them.
//
// The child is a fork of this process (no exec): it runs the work, sends the bytes it returns
// through a pipe and ends with _exit (no exit handlers of this process run there). It starts
// with default signal dispositions and an empty signal mask, whatever this process set, holds
// no file descriptor of this process but 0, 1 and 2, is killed (SIGKILL) when the thread
// that started it ends, so it never outlives this process, and only reads and computes: a
// seccomp filter makes starting a program and changing a file (opening one for writing,
// creating, truncating, renaming, linking, removing, making a folder) fail with EPERM there
// and in whatever it forks.
//
// This process polls the pipe until the child closes it, and meanwhile watches the clock and,
// every 20 ms, the child's memory: its resident anonymous memory (/proc/PID/statm: resident
// minus shared pages) beyond what it had when it started, which is what it inherited from this
// process by the fork (the pages of this process it maps, copy-on-write). Past either limit
// the child is killed (SIGKILL) and reaped. An address-space limit (RLIMIT_AS) in the child is
// not used: AddressSanitizer's reserved shadow memory is terabytes of address space. Without
// /proc the memory is not watched.

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace mfree {

/// Limits of a child process (run_in_child).
struct ChildLimits {
  std::chrono::milliseconds wall_time;  // from the fork to the end of its output
  std::size_t memory_bytes;             // resident anonymous memory beyond what it inherited
};

/// How a child process ended.
struct ChildOutcome {
  enum class End {
    exited,         // by _exit: `code` is its exit status, `output` what it sent
    signalled,      // by a signal not sent by run_in_child: `code` is the signal
    out_of_time,    // killed by run_in_child at the wall-time limit
    out_of_memory,  // killed by run_in_child past the memory limit
  };
  End end;
  int code;
  std::string output;       // the bytes received (all of them when `exited` with status 0)
  std::size_t peak_memory;  // the most memory seen in use (as limited), in bytes
  std::chrono::milliseconds elapsed;
};

/// Runs `work` in a child process under `limits` (see above) and returns how it ended. `work`
/// runs in the child only; an exception escaping it ends the child with exit status 2 (so it
/// should catch its own and report them in its output). Throws Error, naming `what`, when the
/// child cannot be started or the pipe fails.
[[nodiscard]] ChildOutcome run_in_child(const std::function<std::string()>& work, const ChildLimits& limits,
                                        std::string_view what);

}  // namespace mfree

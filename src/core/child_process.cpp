#include "mfree/core/child_process.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <omp.h>
#include <poll.h>
#include <pthread.h>
#include <seccomp.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstring>
#include <limits>
#include <system_error>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

using Clock = std::chrono::steady_clock;

/// The memory is looked at this often (and the pipe polled at least this often).
constexpr std::chrono::milliseconds watch_period{20};

/// No figure: /proc/PID/statm could not be read.
constexpr std::size_t unknown = std::numeric_limits<std::size_t>::max();

/// Resident anonymous memory of a process in bytes, from /proc/PID/statm (in pages: size,
/// resident, shared = file-backed and shmem resident, ...): (resident - shared) pages.
std::size_t anonymous_resident(const char* statm) {
  const int fd = ::open(statm, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return unknown;
  char text[128];
  const ssize_t n = ::read(fd, text, sizeof text);
  ::close(fd);
  if (n <= 0) return unknown;
  // std::from_chars, not sscanf: the child must not wait for a lock (of the C library, or of a
  // sanitizer's interceptor) that another thread of this process held at the fork.
  std::size_t fields[3] = {0, 0, 0};  // size, resident, shared
  const char* at = text;
  for (std::size_t& field : fields) {
    while (at < text + n && *at == ' ') ++at;
    const std::from_chars_result r = std::from_chars(at, text + n, field);
    if (r.ec != std::errc()) return unknown;
    at = r.ptr;
  }
  const std::size_t resident = fields[1], shared = fields[2];
  const long page = ::sysconf(_SC_PAGESIZE);
  return resident >= shared ? (resident - shared) * static_cast<std::size_t>(page) : 0;
}

/// Writes all of `bytes` to fd; false on an error.
bool write_all(int fd, const void* bytes, std::size_t size) {
  const char* at = static_cast<const char*>(bytes);
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, at + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

/// The child reads and computes, nothing else (a seccomp filter, which also sets
/// no_new_privs; the calls below fail with EPERM there and in whatever it forks): it starts no
/// program (execve, execveat) and changes no file: it opens none for writing, creates,
/// truncates, renames, links or removes none, and makes no folder. libgmsh runs a .geo file's
/// SystemCall through the shell and carries out its Printf > "file", Save, CreateDir,
/// RenameFile and DeleteFile: a file a scene names must do none of that. The pipe and the
/// standard streams, open before, stay writable.
void confine() {
  const scmp_filter_ctx filter = ::seccomp_init(SCMP_ACT_ALLOW);
  bool ok = filter != nullptr;
  const auto deny = [&](int call, auto... comparisons) {
    ok = ok &&
         ::seccomp_rule_add(filter, SCMP_ACT_ERRNO(EPERM), call, sizeof...(comparisons), comparisons...) == 0;
  };
  for (const int call :
       {SCMP_SYS(execve), SCMP_SYS(execveat), SCMP_SYS(creat), SCMP_SYS(openat2), SCMP_SYS(truncate),
        SCMP_SYS(rename), SCMP_SYS(renameat), SCMP_SYS(renameat2), SCMP_SYS(link), SCMP_SYS(linkat),
        SCMP_SYS(symlink), SCMP_SYS(symlinkat), SCMP_SYS(unlink), SCMP_SYS(unlinkat), SCMP_SYS(rmdir),
        SCMP_SYS(mkdir), SCMP_SYS(mkdirat), SCMP_SYS(mknod), SCMP_SYS(mknodat)})
    deny(call);
  // open(path, flags) and openat(folder, path, flags) with any flag that writes.
  for (const scmp_datum_t flag : {O_WRONLY, O_RDWR, O_CREAT, O_TRUNC, O_APPEND}) {
    deny(SCMP_SYS(open), scmp_arg_cmp{1, SCMP_CMP_MASKED_EQ, flag, flag});  // flags & flag == flag
    deny(SCMP_SYS(openat), scmp_arg_cmp{2, SCMP_CMP_MASKED_EQ, flag, flag});
  }
  ok = ok && ::seccomp_load(filter) == 0;
  if (filter != nullptr) ::seccomp_release(filter);
  if (!ok) ::_exit(3);
}

/// The child's settings before it works: killed with the thread that forked it (or at once if
/// that already ended, `parent` no longer being its parent), default dispositions of every
/// signal (sanitizer and fuzzer handlers of this process would report a crash as their own),
/// an empty signal mask, no file descriptors but 0, 1, 2 and `keep`, and confine() above.
void prepare_child(pid_t parent, int keep) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  ::sigemptyset(&default_action.sa_mask);
  // SIGKILL and SIGSTOP cannot be changed; the C library's own real-time signals refuse (EINVAL).
  for (int signal = 1; signal < NSIG; ++signal) {
    if (signal != SIGKILL && signal != SIGSTOP) ::sigaction(signal, &default_action, nullptr);
  }
  sigset_t none;
  ::sigemptyset(&none);
  ::pthread_sigmask(SIG_SETMASK, &none, nullptr);
  if (keep > 3) ::close_range(3, static_cast<unsigned>(keep - 1), 0);
  ::close_range(static_cast<unsigned>(keep + 1), ~0U, 0);
  // LLVM's OpenMP runtime (clang builds; it serves libgmsh's GOMP calls there too) starts
  // anew in a forked child: it registers itself in a file of /dev/shm, removing a stale one
  // of the same process id first. That happens here, before confine() forbids both (the
  // child would abort, or retry for ever on a stale file).
  (void)omp_get_max_threads();
  confine();
}

/// The child: its starting memory (the baseline of the limit), then the work's bytes.
[[noreturn]] void child(const std::function<std::string()>& work, pid_t parent, int out) {
  prepare_child(parent, out);
  const std::size_t inherited = anonymous_resident("/proc/self/statm");
  if (!write_all(out, &inherited, sizeof inherited)) ::_exit(2);
  std::string bytes;
  try {
    bytes = work();
  } catch (...) {
    ::_exit(2);
  }
  ::_exit(write_all(out, bytes.data(), bytes.size()) ? 0 : 2);
}

/// waitpid that goes on through interruptions; the status.
int reap(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

/// The parent's side: reads the child's output, killing it at a limit.
class Watch {
 public:
  Watch(pid_t pid, int in, const ChildLimits& limits)
      : pid_(pid), in_(in), limits_(limits), statm_(fmt::format("/proc/{}/statm", pid)) {}

  /// Reads until the end of the output or a limit; the outcome, the child reaped.
  ChildOutcome run(std::string_view what) {
    const Clock::time_point start = Clock::now();
    const Clock::time_point deadline = start + limits_.wall_time;
    Clock::time_point next_look = start;
    for (;;) {
      const Clock::time_point now = Clock::now();
      if (now >= deadline) return kill(ChildOutcome::End::out_of_time, start);
      if (now >= next_look) {
        if (over_memory()) return kill(ChildOutcome::End::out_of_memory, start);
        next_look = now + watch_period;
      }
      const auto wait = std::chrono::ceil<std::chrono::milliseconds>(std::min(deadline, next_look) - now);
      pollfd p{in_, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(wait.count()));
      if (ready < 0 && errno == EINTR) continue;
      if (ready < 0) fail(what, "poll");
      if (ready == 0) continue;
      char buffer[1 << 16];
      const ssize_t n = ::read(in_, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) fail(what, "read");
      if (n == 0) break;
      received_.append(buffer, static_cast<std::size_t>(n));
    }
    const int status = reap(pid_);
    ChildOutcome out{ChildOutcome::End::exited, 0, output(), peak_, elapsed(start)};
    if (WIFSIGNALED(status)) {
      out.end = ChildOutcome::End::signalled;
      out.code = WTERMSIG(status);
    } else {
      out.code = WEXITSTATUS(status);
    }
    return out;
  }

 private:
  /// Whether the child's memory beyond its start exceeds the limit (false while unknown).
  bool over_memory() {
    if (received_.size() < sizeof(std::size_t)) return false;  // its start is not known yet
    std::size_t inherited;
    std::memcpy(&inherited, received_.data(), sizeof inherited);
    const std::size_t now = anonymous_resident(statm_.c_str());
    if (inherited == unknown || now == unknown) return false;
    const std::size_t used = now > inherited ? now - inherited : 0;
    peak_ = std::max(peak_, used);
    return used > limits_.memory_bytes;
  }

  ChildOutcome kill(ChildOutcome::End end, Clock::time_point start) {
    ::kill(pid_, SIGKILL);
    (void)reap(pid_);
    return ChildOutcome{end, SIGKILL, output(), peak_, elapsed(start)};
  }

  [[noreturn]] void fail(std::string_view what, const char* call) {
    const int error = errno;
    ::kill(pid_, SIGKILL);
    (void)reap(pid_);
    throw Error(fmt::format("{}: reading the output of its child process failed ({}: {})", what, call,
                            std::strerror(error)));
  }

  std::string output() const {
    return received_.size() > sizeof(std::size_t) ? received_.substr(sizeof(std::size_t)) : std::string();
  }

  static std::chrono::milliseconds elapsed(Clock::time_point start) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start);
  }

  pid_t pid_;
  int in_;
  ChildLimits limits_;
  std::string statm_;
  std::string received_;  // the child's starting memory (sizeof(size_t) bytes), then its output
  std::size_t peak_ = 0;
};

}  // namespace

ChildOutcome run_in_child(const std::function<std::string()>& work, const ChildLimits& limits,
                          std::string_view what) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw Error(fmt::format("{}: cannot start a child process: {}", what, std::strerror(errno)));
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error(fmt::format("{}: cannot start a child process: {}", what, std::strerror(error)));
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(work, parent, fds[1]);
  }
  ::close(fds[1]);
  try {
    ChildOutcome out = Watch(pid, fds[0], limits).run(what);
    ::close(fds[0]);
    return out;
  } catch (...) {
    ::close(fds[0]);
    throw;
  }
}

}  // namespace mfree

#include "mfree/io/interrupt.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>

#include "mfree/core/error.hpp"
#include "mfree/io/staged_folder.hpp"

namespace mfree {

namespace {

/// The pipe from the signal handler (which may only do async-signal-safe work) to the thread
/// that stops the run. Process-wide, as signal dispositions are.
int signal_pipe[2] = {-1, -1};

extern "C" void forward_signal(int number) {
  const int saved = errno;
  const auto byte = static_cast<unsigned char>(number);
  (void)!::write(signal_pipe[1], &byte, 1);
  errno = saved;
}

/// Removes the staging folders, reports, and ends the process by `number` itself.
[[noreturn]] void stop_by(int number) {
  for (const std::filesystem::path& target : abandon_staging_folders()) {
    std::string message = fmt::format("mfree: stopped by SIG{}: the results in {} are as they were",
                                      ::sigabbrev_np(number), target.string());
    std::filesystem::path checkpoints = target;
    checkpoints += ".checkpoints";
    std::error_code ec;
    if (std::filesystem::is_directory(checkpoints, ec))
      message += fmt::format("; the checkpoints in {} stay (--restart {} continues the run)",
                             checkpoints.string(), checkpoints.string());
    std::fputs((message + "\n").c_str(), stderr);
  }
  std::fflush(stderr);
  std::signal(number, SIG_DFL);
  ::raise(number);
  std::_Exit(128 + number);  // reached only if the default action did not end the process
}

}  // namespace

void remove_staging_folders_on_signals() {
  if (::pipe2(signal_pipe, O_CLOEXEC) != 0)
    throw Error(fmt::format("cannot prepare for signals: {}", std::strerror(errno)));
  for (const int number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction now {};
    if (::sigaction(number, nullptr, &now) != 0 || now.sa_handler == SIG_IGN) continue;
    struct sigaction take {};
    take.sa_handler = forward_signal;
    take.sa_flags = SA_RESTART;
    sigemptyset(&take.sa_mask);
    ::sigaction(number, &take, nullptr);
  }
  std::thread([] {
    unsigned char number = 0;
    while (::read(signal_pipe[0], &number, 1) != 1) {
    }
    stop_by(number);
  }).detach();
}

}  // namespace mfree

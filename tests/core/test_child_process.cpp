#include <poll.h>
#include <pthread.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "../test_support.hpp"
#include "mfree/core/child_process.hpp"

using mfree::ChildLimits;
using mfree::ChildOutcome;
using mfree::run_in_child;
using namespace std::chrono_literals;

namespace {

constexpr std::size_t mib = 1024 * 1024;

/// Touches `bytes` of fresh memory in 1 MiB steps, one step per 1 ms, and keeps it.
std::vector<char> grow(std::size_t bytes) {
  std::vector<char> memory;
  memory.reserve(bytes);
  for (std::size_t step = 0; step < bytes / mib; ++step) {
    memory.resize(memory.size() + mib, static_cast<char>(step | 1));
    std::this_thread::sleep_for(1ms);
  }
  return memory;
}

/// Whether the process is gone: no /proc entry, or a zombie (dead, not yet reaped).
bool is_dead(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string pid_field, name, state;
  if (!(stat >> pid_field >> name >> state)) return true;
  return state == "Z" || state == "X";
}

}  // namespace

TEST_CASE("child process: its output and exit status", "[core]") {
  const ChildOutcome out =
      run_in_child([] { return std::string("boundary\0mesh", 13); }, {5s, 64 * mib}, "test");
  CHECK(out.end == ChildOutcome::End::exited);
  CHECK(out.code == 0);
  CHECK(out.output == std::string("boundary\0mesh", 13));

  // An exception escaping the work ends the child with exit status 2, its output empty.
  const ChildOutcome thrown =
      run_in_child([]() -> std::string { throw std::runtime_error("x"); }, {5s, 64 * mib}, "test");
  CHECK(thrown.end == ChildOutcome::End::exited);
  CHECK(thrown.code == 2);
  CHECK(thrown.output.empty());
}

TEST_CASE("child process: it starts no program and changes no file", "[core]") {
  // In the child, std::system runs no shell, and a file cannot be created, opened for
  // writing, renamed or removed, nor a folder made; it still reads, and writes its pipe.
  const mfree::testing::ScratchFolder folder("child_confined");
  const std::filesystem::path touched = folder.path / "touched", existing = folder.path / "existing";
  std::ofstream(existing) << "kept";
  const ChildOutcome out = run_in_child(
      [&] {
        std::string seen;
        seen += std::system(("touch " + touched.string()).c_str()) == 0 ? "ran " : "";
        seen += std::ofstream(touched) ? "created " : "";
        seen += std::ofstream(existing, std::ios::app) ? "appended " : "";
        std::error_code ec;
        std::filesystem::rename(existing, touched, ec);
        seen += ec ? "" : "renamed ";
        std::filesystem::remove(existing, ec);
        seen += ec ? "" : "removed ";
        std::filesystem::create_directory(folder.path / "made", ec);
        seen += ec ? "" : "made ";
        std::ifstream in(existing);
        std::string text;
        in >> text;
        return seen + "read " + text;
      },
      {5s, 64 * mib}, "test");
  CHECK(out.end == ChildOutcome::End::exited);
  CHECK(out.output == "read kept");
  CHECK(folder.entries() == std::vector<std::string>{"existing"});
  // Here, outside the child, the same command runs.
  CHECK(std::system(("touch " + touched.string()).c_str()) == 0);
  CHECK(std::filesystem::exists(touched));
}

TEST_CASE("child process: killed at the wall-time limit", "[core]") {
  const ChildOutcome out = run_in_child(
      [] {
        std::this_thread::sleep_for(30s);
        return std::string("late");
      },
      {300ms, 64 * mib}, "test");
  CHECK(out.end == ChildOutcome::End::out_of_time);
  CHECK(out.output.empty());
  CHECK(out.elapsed >= 300ms);
  CHECK(out.elapsed < 800ms);
}

TEST_CASE("child process: killed past the memory limit, which counts only what it adds", "[core]") {
  // The child touches 1 MiB per ms up to 512 MiB; the limit, 32 MiB, is seen within a look
  // (20 ms) of being passed.
  const ChildOutcome out = run_in_child(
      [] {
        const std::vector<char> memory = grow(512 * mib);
        return std::string(1, memory.back());
      },
      {10s, 32 * mib}, "test");
  CHECK(out.end == ChildOutcome::End::out_of_memory);
  CHECK(out.peak_memory > 32 * mib);
  CHECK(out.peak_memory < 256 * mib);
  CHECK(out.elapsed < 1s);

  // This process holds 256 MiB (the child inherits them by the fork); the child adds 16 MiB
  // and stays 200 ms (10 looks) under a limit of 64 MiB.
  const std::vector<char> held = grow(256 * mib);
  const ChildOutcome small = run_in_child(
      [] {
        const std::vector<char> memory = grow(16 * mib);
        std::this_thread::sleep_for(200ms);
        return std::string(1, memory.back());
      },
      {10s, 64 * mib}, "test");
  CHECK(held.size() == 256 * mib);
  CHECK(small.end == ChildOutcome::End::exited);
  CHECK(small.code == 0);
  CHECK(small.peak_memory >= 16 * mib);
  CHECK(small.peak_memory < 64 * mib);
}

TEST_CASE("child process: default signal dispositions and an empty mask; a signal ends it", "[core]") {
  // This thread blocks SIGTERM and this process ignores SIGUSR1: the child does neither.
  sigset_t term, old_mask;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  REQUIRE(pthread_sigmask(SIG_BLOCK, &term, &old_mask) == 0);
  struct sigaction ignore {
  }, old_usr1{};
  ignore.sa_handler = SIG_IGN;
  REQUIRE(sigaction(SIGUSR1, &ignore, &old_usr1) == 0);

  const ChildOutcome settings = run_in_child(
      [] {
        sigset_t mask;
        pthread_sigmask(SIG_SETMASK, nullptr, &mask);
        struct sigaction usr1 {};
        sigaction(SIGUSR1, nullptr, &usr1);
        return std::string(sigismember(&mask, SIGTERM) ? "blocked" : "unblocked") +
               (usr1.sa_handler == SIG_DFL ? " default" : " changed");
      },
      {5s, 64 * mib}, "test");
  CHECK(settings.output == "unblocked default");

  // SIGUSR1, ignored here, ends the child: reported as the signal, not as a limit.
  const ChildOutcome signalled = run_in_child(
      [] {
        raise(SIGUSR1);
        return std::string("survived");
      },
      {5s, 64 * mib}, "test");
  CHECK(signalled.end == ChildOutcome::End::signalled);
  CHECK(signalled.code == SIGUSR1);
  CHECK(signalled.output.empty());

  sigaction(SIGUSR1, &old_usr1, nullptr);
  pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
}

TEST_CASE("child process: it does not outlive the process that started it", "[core]") {
  // An intermediate process starts a child that writes its process id to its standard output
  // (a pipe to this process: the child may write no file) and sleeps 30 s; the intermediate
  // is killed, and the child must die with it.
  int ids[2];
  REQUIRE(pipe(ids) == 0);
  const pid_t intermediate = fork();
  REQUIRE(intermediate >= 0);
  if (intermediate == 0) {
    dup2(ids[1], 1);
    close(ids[0]);
    close(ids[1]);
    (void)run_in_child(
        [] {
          const std::string id = std::to_string(getpid()) + "\n";
          (void)!write(1, id.data(), id.size());
          std::this_thread::sleep_for(30s);
          return std::string();
        },
        {60s, 64 * mib}, "test");
    _exit(0);
  }
  close(ids[1]);
  pollfd ready{ids[0], POLLIN, 0};
  char text[32] = {};
  const bool sent = poll(&ready, 1, 2000) == 1 && read(ids[0], text, sizeof text - 1) > 0;
  close(ids[0]);
  const pid_t child = sent ? static_cast<pid_t>(std::atol(text)) : 0;
  REQUIRE(child > 0);
  CHECK_FALSE(is_dead(child));
  kill(intermediate, SIGKILL);
  int status = 0;
  REQUIRE(waitpid(intermediate, &status, 0) == intermediate);
  bool dead = false;
  for (int i = 0; i < 100 && !dead; ++i, std::this_thread::sleep_for(10ms)) dead = is_dead(child);
  CHECK(dead);
}

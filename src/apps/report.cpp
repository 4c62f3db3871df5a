#include "mfree/apps/report.hpp"

#include <fmt/format.h>
#include <iostream>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <vector>

extern char** environ;

namespace mfree {

void print_stages(const StageTimer& t) {
  for (std::size_t i = 0; i < t.stages().size(); ++i)
    std::cout << fmt::format("  {:<24} {:9.4f} s  {:>8} call(s)\n", t.stages()[i].first, t.stages()[i].second,
                             t.calls()[i]);
  std::cout << fmt::format("  {:<24} {:9.4f} s\n", "total", t.total());
}

void plot(const std::string& script, const std::filesystem::path& csv, const std::filesystem::path& folder) {
  std::cout.flush();
  // An argument vector, no shell: nothing of a scene (the folder's name) is ever parsed as
  // a command.
  std::vector<std::string> args{"/usr/bin/python3", std::string(MFREE_SOURCE_DIR) + "/verification/" + script,
                                csv.string(), folder.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  int status = 0;
  const bool ran = posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) == 0 &&
                   waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!ran) std::cerr << "mfree: plotting failed (needs /usr/bin/python3 with matplotlib); the CSV is complete\n";
}

}  // namespace mfree

#include "mfree/apps/report.hpp"

#include <cstdlib>
#include <fmt/format.h>
#include <iostream>

namespace mfree {

void print_stages(const StageTimer& t) {
  for (std::size_t i = 0; i < t.stages().size(); ++i)
    std::cout << fmt::format("  {:<24} {:9.4f} s  {:>8} call(s)\n", t.stages()[i].first, t.stages()[i].second,
                             t.calls()[i]);
  std::cout << fmt::format("  {:<24} {:9.4f} s\n", "total", t.total());
}

void plot(const std::string& script, const std::filesystem::path& csv, const std::filesystem::path& folder) {
  std::cout.flush();
  const std::string cmd = fmt::format("/usr/bin/python3 '{}/verification/{}' '{}' '{}'", MFREE_SOURCE_DIR, script,
                                      csv.string(), folder.string());
  if (std::system(cmd.c_str()) != 0)
    std::cerr << "mfree: plotting failed (needs /usr/bin/python3 with matplotlib); the CSV is complete\n";
}

}  // namespace mfree

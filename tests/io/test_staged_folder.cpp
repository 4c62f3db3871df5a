#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/staged_folder.hpp"

using namespace mfree;
using mfree::testing::ScratchFolder;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<std::string> sorted(std::vector<std::string> v) {
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

TEST_CASE("staged output: a run's folder is replaced whole on success, untouched on failure", "[io]") {
  ScratchFolder scratch("staged");
  const fs::path out = scratch.path / "results";
  {
    StagedFolder first(out);
    CHECK_FALSE(fs::exists(out));  // nothing visible until the run succeeds
    write_file_atomically(first.path() / "summary.json", "{}\n");
    write_file_atomically(first.path() / "errors.csv", "old\n");
    first.commit();
  }
  CHECK(scratch.entries() == std::vector<std::string>{"results"});
  // A failed rerun: its partial files are removed, the earlier results stay as they were.
  {
    StagedFolder failed(out);
    write_file_atomically(failed.path() / "frame_0000.vtu", "partial\n");
    CHECK(fs::exists(failed.path()));
    CHECK(failed.path().filename().string().front() == '.');  // hidden beside the results
  }
  CHECK(read(out / "errors.csv") == "old\n");
  CHECK_FALSE(fs::exists(out / "frame_0000.vtu"));
  // A successful rerun that writes no errors.csv leaves none behind from before.
  {
    StagedFolder second(out);
    write_file_atomically(second.path() / "summary.json", "{\"new\": 1}\n");
    second.commit();
  }
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(out)) names.push_back(e.path().filename().string());
  CHECK(sorted(names) == std::vector<std::string>{".mfree-output", "summary.json"});
  std::vector<std::string> beside;
  for (const auto& e : fs::directory_iterator(scratch.path)) beside.push_back(e.path().filename().string());
  CHECK(beside == std::vector<std::string>{"results"});
}

TEST_CASE("staged output: a folder mfree did not write is never replaced; a killed run's leftovers go", "[io]") {
  ScratchFolder scratch("staged_refuse");
  const fs::path mine = scratch.path / "thesis";
  fs::create_directories(mine);
  std::ofstream(mine / "chapter1.tex") << "text\n";
  CHECK_THROWS_WITH(StagedFolder(mine), Catch::Contains("was not written by mfree"));
  CHECK(read(mine / "chapter1.tex") == "text\n");
  std::ofstream(scratch.path / "file") << "x\n";
  CHECK_THROWS_WITH(StagedFolder(scratch.path / "file"), Catch::Contains("is not a folder"));
  // The staging folder of a process that no longer exists (pid 2^22 + 1 is above Linux's
  // largest) is removed by the next run into the same folder.
  const fs::path abandoned = scratch.path / ".results.partial-4194305";
  fs::create_directories(abandoned);
  // One whose number is no process id (too long for one, or negative) was not made by a run:
  // it stays, and the run goes on.
  const fs::path foreign = scratch.path / ".results.partial-99999999999999999999999";
  const fs::path negative = scratch.path / ".results.partial--5";
  fs::create_directories(foreign);
  fs::create_directories(negative);
  { StagedFolder next(scratch.path / "results"); }
  CHECK_FALSE(fs::exists(abandoned));
  CHECK(fs::exists(foreign));
  CHECK(fs::exists(negative));
}

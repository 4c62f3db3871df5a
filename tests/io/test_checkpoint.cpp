#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/types.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/checkpoint.hpp"

using namespace mfree;
using mfree::testing::ScratchFolder;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

TEST_CASE("checkpoints: a state comes back bit for bit, with the output written so far", "[io]") {
  ScratchFolder scratch("checkpoint");
  const fs::path out = scratch.path / "run", staging = scratch.path / "staging";
  write_file_atomically(staging / "energy.csv", "step 3\n");
  CheckpointState s;
  const std::vector<double> values{1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(), 1e300};
  const std::vector<Mat2> deformation{(Mat2() << 1.0, 0.1, -0.2, 0.9).finished(), Mat2::Identity() * std::sqrt(2.0)};
  s.put("values", values);
  s.put("time", 0.125);
  s.put_values("F", deformation);
  s.put_ints("body", {0, 1, 1});
  const Checkpoints writer(out, 3, 42, {});
  writer.write(3, s, staging);
  write_file_atomically(staging / "energy.csv", "step 6\n");  // replaced after the checkpoint
  writer.write(6, s, staging);
  writer.write(9, s, staging);
  // The last two are kept.
  CHECK_FALSE(fs::exists(writer.folder() / "step_0000000003"));
  CHECK(fs::exists(writer.folder() / "step_0000000006" / "state.bin"));
  CHECK(fs::exists(writer.folder() / "step_0000000009" / "state.bin"));

  const Checkpoints reader(out, 0, 42, writer.folder());
  REQUIRE(reader.resume() != nullptr);
  CHECK(reader.resume_step() == 9);
  const CheckpointState& r = *reader.resume();
  const std::vector<double>& back = r.get("values", values.size());
  for (std::size_t k = 0; k < values.size(); ++k) CHECK(mfree::testing::same_bits(back[k], values[k]));
  CHECK(std::signbit(back[1]));
  CHECK(r.scalar("time") == 0.125);
  const std::vector<Mat2> f = r.values<Mat2>("F");
  REQUIRE(f.size() == 2);
  CHECK(f[0] == deformation[0]);
  CHECK(f[1] == deformation[1]);
  CHECK(r.ints("body") == std::vector<int>{0, 1, 1});
  CHECK_THROWS_AS(r.get("missing"), InputError);
  CHECK_THROWS_AS(r.get("values", 3), InputError);

  // The output as it was at the checkpoint, linked into a new staging folder.
  const fs::path next = scratch.path / "next";
  reader.restore_output(next);
  CHECK(read(next / "energy.csv") == "step 6\n");
  CHECK(read(writer.folder() / "step_0000000006" / "output" / "energy.csv") == "step 6\n");
  reader.remove();
  CHECK_FALSE(fs::exists(writer.folder()));
}

TEST_CASE("checkpoints: another scene's, a damaged one and an empty folder are refused", "[io]") {
  ScratchFolder scratch("checkpoint_bad");
  const fs::path out = scratch.path / "run", staging = scratch.path / "staging";
  fs::create_directories(staging);
  CheckpointState s;
  s.put("time", 1.0);
  const Checkpoints writer(out, 1, 7, {});
  writer.write(1, s, staging);
  const fs::path folder = writer.folder();
  REQUIRE_THROWS_WITH(Checkpoints(out, 0, 8, folder), Catch::Contains("written by a run of another scene"));
  REQUIRE_THROWS_WITH(Checkpoints(out, 0, 7, scratch.path / "none"), Catch::Contains("no such folder of checkpoints"));
  REQUIRE_THROWS_WITH(Checkpoints(out, 0, 7, staging), Catch::Contains("holds no checkpoint"));
  REQUIRE_THROWS_AS(Checkpoints(out, -1, 7, {}), InputError);
  // One flipped bit in the state: the checksum catches it.
  const fs::path state = folder / "step_0000000001" / "state.bin";
  std::string bytes = read(state);
  bytes[bytes.size() / 2] ^= 0x10;
  write_file_atomically(state, bytes);
  REQUIRE_THROWS_WITH(Checkpoints(out, 0, 7, folder), Catch::Contains("damaged"));
  // Truncated: refused as well, never read past its end.
  write_file_atomically(state, bytes.substr(0, 20));
  REQUIRE_THROWS_AS(Checkpoints(out, 0, 7, folder), InputError);
  // A fresh run with checkpoints removes the ones an earlier run left.
  const Checkpoints fresh(out, 5, 7, {});
  CHECK_FALSE(fs::exists(folder / "step_0000000001"));
}

TEST_CASE("checkpoints: a scene's fingerprint changes with its text and its overrides", "[io]") {
  ScratchFolder scratch("checkpoint_fingerprint");
  const fs::path scene = scratch.path / "scene.toml";
  write_file_atomically(scene, "[mpm]\ncells = 8\n");
  const auto a = scene_fingerprint(scene, {});
  CHECK(scene_fingerprint(scene, {}) == a);
  CHECK(scene_fingerprint(scene, {"mpm.cells=16"}) != a);
  write_file_atomically(scene, "[mpm]\ncells = 9\n");
  CHECK(scene_fingerprint(scene, {}) != a);
}

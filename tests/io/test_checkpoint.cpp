#include <fmt/format.h>

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
using mfree::testing::message_of;
using mfree::testing::ScratchFolder;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

template <class T>
void append(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// A checkpoint made by hand: state.bin (with the fingerprint and the hash that fit) holding
/// `step` and `arrays`, in folder/step_NAMED with an output folder; returns state.bin's path.
fs::path hand_made(const fs::path& folder, long long named, long long step,
                   const std::vector<std::pair<std::string, std::vector<double>>>& arrays,
                   std::uint64_t fingerprint) {
  std::string body;
  append(body, static_cast<std::int64_t>(step));
  append(body, static_cast<std::uint64_t>(arrays.size()));
  for (const auto& [name, values] : arrays) {
    append(body, static_cast<std::uint64_t>(name.size()));
    body += name;
    append(body, static_cast<std::uint64_t>(values.size()));
    for (const double v : values) append(body, v);
  }
  const fs::path step_folder = folder / fmt::format("step_{:010d}", named);
  fs::create_directories(step_folder / "output");
  write_file_atomically(step_folder / "state.bin", checkpoint_file(fingerprint, body));
  return step_folder / "state.bin";
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

TEST_CASE(
    "checkpoints: a value that is not finite is refused in any array, naming the file, the array and the "
    "index",
    "[io]") {
  ScratchFolder scratch("checkpoint_not_finite");
  const fs::path out = scratch.path / "run", folder = scratch.path / "ck";
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  // The same arrays with finite values are read (the checksum and fingerprint fit).
  hand_made(folder, 4, 4, {{"time", {0.5}}, {"values", {1.0, 2.0, 3.0}}}, 7);
  CHECK(Checkpoints(out, 0, 7, folder).resume()->get("values", 3)[2] == 3.0);
  fs::remove_all(folder);
  const fs::path state = hand_made(folder, 4, 4, {{"time", {0.5}}, {"values", {1.0, 2.0, nan}}}, 7);
  CHECK(
      message_of<InputError>([&] { Checkpoints(out, 0, 7, folder); }) ==
      fmt::format(
          "checkpoint {}: array 'values': value 2 is nan, not a finite number; the checkpoint does not fit "
          "this run (another version of mfree?) or is damaged: restart from an earlier checkpoint or without "
          "--restart",
          state.string()));
  fs::remove_all(folder);
  hand_made(folder, 4, 4, {{"time", {-inf}}}, 7);
  CHECK_THAT(message_of<InputError>([&] { Checkpoints(out, 0, 7, folder); }),
             Catch::Contains("state.bin: array 'time': value 0 is -inf, not a finite number"));

  // The writer refuses them too, and leaves no checkpoint.
  const fs::path staging = scratch.path / "staging";
  fs::create_directories(staging);
  CheckpointState s;
  s.put("values", std::vector<double>{1.0, inf});
  const Checkpoints writer(out, 1, 7, {});
  CHECK_THAT(
      message_of<NumericalError>([&] { writer.write(3, s, staging); }),
      Catch::Contains("checkpoint of step 3 in ") && Catch::Contains("array 'values': value 1 is inf"));
  CHECK_FALSE(fs::exists(writer.folder() / "step_0000000003"));
}

TEST_CASE("checkpoints: a step other than its folder's name is refused", "[io]") {
  ScratchFolder scratch("checkpoint_step_name");
  const fs::path out = scratch.path / "run", folder = scratch.path / "ck";
  hand_made(folder, 6, 6, {{"time", {0.5}}}, 7);
  CHECK(Checkpoints(out, 0, 7, folder).resume_step() == 6);
  fs::remove_all(folder);
  const fs::path state = hand_made(folder, 7, 6, {{"time", {0.5}}}, 7);
  CHECK_THAT(message_of<InputError>([&] { Checkpoints(out, 0, 7, folder); }),
             Catch::StartsWith(fmt::format("checkpoint {}: holds step 6, but its folder is named for step 7",
                                           state.string())));
  fs::remove_all(folder);
  hand_made(folder, 0, -3, {{"time", {0.5}}}, 7);
  CHECK_THAT(message_of<InputError>([&] { Checkpoints(out, 0, 7, folder); }),
             Catch::Contains("holds step -3, but its folder is named for step 0"));
}

TEST_CASE("checkpoints: the checks of a restore name the first value out of range, its index and the range",
          "[io]") {
  CheckpointState s;
  s.source = "ck/step_0000000002/state.bin";
  const double inf = std::numeric_limits<double>::infinity();
  const auto refusal = [&](const std::string& array, const std::string& what) {
    return fmt::format(
        "checkpoint ck/step_0000000002/state.bin: array '{}': {}; the checkpoint does not fit this run "
        "(another version of mfree?) or is damaged: restart from an earlier checkpoint or without --restart",
        array, what);
  };
  s.put("mass", std::vector<double>{1.0, 2.0, 0.0, -1.0});
  CHECK(s.within("mass", -1.0, 2.0, "within [-1, 2]", 4).size() == 4);
  CHECK(message_of<InputError>([&] { (void)s.within("mass", 1e-300, inf, "positive"); }) ==
        refusal("mass", "value 2 is 0, not positive"));
  CHECK(message_of<InputError>([&] { (void)s.get("mass", 5); }) ==
        refusal("mass", "it holds 4 values, and this run needs 5"));
  CHECK(message_of<InputError>([&] { (void)s.get("volume"); }) == refusal("volume", "it is missing"));

  s.put_ints("material", {0, 1, 1});
  CHECK(s.integers("material", 0, 1, "a material", 3) == std::vector<long long>{0, 1, 1});
  CHECK(message_of<InputError>([&] { (void)s.integers("material", 0, 0, "the only material (0)"); }) ==
        refusal("material", "value 1 is 1, not the only material (0)"));
  s.put("material", std::vector<double>{0.0, 0.5});
  CHECK(message_of<InputError>([&] { (void)s.integers("material", 0, 1, "a material index"); }) ==
        refusal("material", "value 1 is 0.5, not a material index"));
  s.put("material", std::vector<double>{1e10});
  CHECK(message_of<InputError>([&] { (void)s.ints("material"); }) ==
        refusal("material", "value 0 is 10000000000, not an int"));

  s.put("frames.time", std::vector<double>{0.0, 0.5, 0.25});
  CHECK(message_of<InputError>([&] { (void)s.times("frames.time", 1.0, 3); }) ==
        refusal("frames.time", "value 2 is 0.25, before the one before it (0.5)"));
  s.put("frames.time", std::vector<double>{0.0, 0.5, 1.5});
  CHECK(message_of<InputError>([&] { (void)s.times("frames.time", 1.0, 3); }) ==
        refusal("frames.time", "value 2 is 1.5, not a time of the run so far (0 to 1 s)"));
  CHECK(message_of<InputError>([&] { (void)s.times("frames.time", 2.0, 2); }) ==
        refusal("frames.time", "it holds 3 times, more than the 2 the run can have so far"));
  CHECK(s.times("frames.time", 2.0, 3).size() == 3);
}

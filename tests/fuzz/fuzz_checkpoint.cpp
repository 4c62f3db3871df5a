// libFuzzer target: a run restored from a checkpoint (io/checkpoint.hpp), as `mfree run
// --restart` restores it. The input's first byte picks one of the four small scenes
// tests/apps/checkpoint_*.toml (byte % 4: MPM; MPM with CPDI2, J2 and two bodies; central
// differences; Newmark with J2); the rest is a checkpoint's body, the bytes of its state.bin
// between the fingerprint and the hash (the step, the number of arrays, the arrays). The
// target wraps the body in the magic, the scene's fingerprint and the hash that fits
// (checkpoint_file()), in a step folder named for the step it holds (one step off when bit 7
// of the first byte is set), so that every input passes the checksum and reaches the checks
// of the restore; the scene then runs from it to its end (output in a scratch folder). An
// mfree::Error is a clean refusal; anything else escapes and is a finding.
//
// MFREE_FUZZ_VERBOSE in the environment prints what became of each input (restored and run,
// or the refusal). With MFREE_FUZZ_CHECKPOINT_SEEDS=FOLDER it writes seeds instead and
// exits: every scene runs with checkpoints every 1, 3 and 4 steps, and the body of each
// checkpoint a run keeps (its last two), behind its scene's byte, goes to FOLDER (.ci/fuzz
// seeds the corpus so).
#include <fmt/format.h>
#include <omp.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <vector>

#include "fuzz_support.hpp"
#include "mfree/apps/mpm_app.hpp"
#include "mfree/apps/solid_app.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/elasticity_scene.hpp"
#include "mfree/io/mpm_scene.hpp"

namespace fs = std::filesystem;

namespace {

/// One of the scenes: MPM or dynamics, read once, its output in the scratch folder.
struct Scene {
  std::string name;
  std::optional<mfree::MPMScene> mpm;
  std::optional<mfree::ElasticityScene> solid;
  std::uint64_t fingerprint = 0;

  /// Runs the scene from the checkpoint folder `restart` (none: from the start), writing
  /// checkpoints every `every` steps (0: none).
  void run(const fs::path& restart, int every) const {
    const fs::path out = output();
    const mfree::Checkpoints checkpoints(out, every, fingerprint, restart);
    if (mpm)
      (void)mfree::simulate_mpm(*mpm, mpm->settings, true, &checkpoints);
    else
      (void)mfree::simulate(*solid, solid->dynamics->settings, true, &checkpoints);
  }
  [[nodiscard]] fs::path output() const { return mfree::fuzz::scratch() / name; }
};

const std::array<Scene, 4>& scenes() {
  static const std::array<Scene, 4> all = [] {
    std::array<Scene, 4> s;
    const char* names[] = {"mpm", "mpm_cpdi2_j2", "dynamics", "dynamics_j2"};
    for (std::size_t k = 0; k < s.size(); ++k) {
      const fs::path file =
          fs::path(MFREE_SOURCE_DIR) / "tests/apps" / ("checkpoint_" + std::string(names[k]) + ".toml");
      s[k].name = names[k];
      s[k].fingerprint = mfree::scene_fingerprint(file, {});
      fs::create_directories(s[k].output());
      if (k < 2) {
        s[k].mpm = mfree::read_mpm_scene(file, false);
        s[k].mpm->folder = s[k].output();
      } else {
        s[k].solid = mfree::read_elasticity_scene(file, false);
        s[k].solid->output.folder = s[k].output();
      }
    }
    return s;
  }();
  return all;
}

/// Seeds: the body of the checkpoints the scenes keep with checkpoints every 1, 3, 4 steps.
void write_seeds(const fs::path& folder) {
  fs::create_directories(folder);
  int written = 0;
  for (std::size_t k = 0; k < scenes().size(); ++k)
    for (const int every : {1, 3, 4}) {
      const Scene& scene = scenes()[k];
      const fs::path checkpoints = scene.output().string() + ".checkpoints";
      fs::remove_all(checkpoints);
      // The writer keeps the last two checkpoints of each run.
      scene.run({}, every);
      for (const fs::directory_entry& e : fs::directory_iterator(checkpoints)) {
        std::ifstream in(e.path() / "state.bin", std::ios::binary);
        const std::string bytes{std::istreambuf_iterator<char>(in), {}};
        const std::string body =
            bytes.substr(16, bytes.size() - 24);  // after magic and fingerprint, before the hash
        mfree::write_file_atomically(
            folder / fmt::format("{}-every{}-{}", scene.name, every, e.path().filename().string()),
            std::string(1, static_cast<char>(k)) + body);
        ++written;
      }
      fs::remove_all(checkpoints);
    }
  std::cout << fmt::format("fuzz_checkpoint: wrote {} seeds into {}\n", written, folder.string());
}

}  // namespace

/// MFREE_FUZZ_VERBOSE set: each input's outcome on standard error (to see what seeds reach).
const bool verbose = std::getenv("MFREE_FUZZ_VERBOSE") != nullptr;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  omp_set_num_threads(1);  // the scenes are tiny: threads would only wait for each other
  if (const char* seeds = std::getenv("MFREE_FUZZ_CHECKPOINT_SEEDS")) {
    write_seeds(seeds);
    std::exit(0);
  }
  std::cout.setstate(std::ios::badbit);  // the runs' progress: not wanted in the fuzzer's log
  (void)scenes();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const Scene& scene = scenes()[data[0] % 4];
  const std::string_view body = mfree::fuzz::text(data + 1, size - 1);
  std::int64_t step = -1;
  if (body.size() >= sizeof step) std::memcpy(&step, body.data(), sizeof step);
  const long long named = step >= 0 ? step : 0;
  const long long folder_step = (data[0] & 0x80) && named < INT64_MAX ? named + 1 : named;
  const fs::path restart = mfree::fuzz::scratch() / "restart";
  fs::remove_all(restart);
  const fs::path folder = restart / fmt::format("step_{:010d}", folder_step);
  fs::create_directories(folder / "output");
  std::ofstream(folder / "state.bin", std::ios::binary) << mfree::checkpoint_file(scene.fingerprint, body);
  try {
    scene.run(restart, 0);
    if (verbose) std::cerr << "fuzz_checkpoint: restored and ran to the end\n";
  } catch (const mfree::Error& e) {
    if (verbose) std::cerr << "fuzz_checkpoint: refused: " << e.what() << '\n';
  }
  return 0;
}

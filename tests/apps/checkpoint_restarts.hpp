#pragma once
// The fixture of the restart tests (test_mpm_app.cpp, test_solid_app.cpp): a run with
// checkpoints every 3 steps, its newest checkpoint, and runs restored from that checkpoint
// with one array changed, each written with a fitting checksum.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/checkpoint.hpp"

namespace mfree::testing {

class CheckpointRestarts {
 public:
  /// run(folder, checkpoints): a run of the scene with output folder `folder`, writing or
  /// resuming from `checkpoints`.
  using Run = std::function<void(const std::filesystem::path&, const Checkpoints*)>;

  /// Runs the scene with checkpoints into SCRATCH/run and keeps the newest.
  CheckpointRestarts(const std::string& scratch_name, std::uint64_t fingerprint, Run run)
      : scratch(scratch_name), fingerprint_(fingerprint), run_(std::move(run)) {
    const std::filesystem::path folder = scratch.path / "run";
    std::filesystem::create_directories(folder);
    {
      const Checkpoints writer(folder, 3, fingerprint_, {});
      run_(folder, &writer);
    }
    const Checkpoints reader(folder, 0, fingerprint_, folder.string() + ".checkpoints");
    state = *reader.resume();
    step = reader.resume_step();
  }

  /// The state with array `name` replaced by `values`.
  [[nodiscard]] CheckpointState with(const std::string& name, std::vector<double> values) const {
    CheckpointState s = state;
    s.put(name, std::move(values));
    return s;
  }
  /// Restores a run of the scene from `s`, written (checksum and all) as the checkpoint of
  /// step `at`: "restored" when it runs to its end, else the InputError's message.
  [[nodiscard]] std::string restore(const CheckpointState& s, long long at) const {
    const std::filesystem::path out = scratch.path / "broken";
    std::filesystem::create_directories(out);
    Checkpoints(out, 1, fingerprint_, {}).write(at, s, out);
    const Checkpoints reader(out, 0, fingerprint_, out.string() + ".checkpoints");
    try {
      run_(scratch.path / "run", &reader);
    } catch (const InputError& e) {
      return e.what();
    }
    return "restored";
  }
  /// restore(with(name, values), step).
  [[nodiscard]] std::string restore(const std::string& name, std::vector<double> values) const {
    return restore(with(name, std::move(values)), step);
  }
  [[nodiscard]] std::vector<double> get(const std::string& name) const { return state.get(name); }

  ScratchFolder scratch;
  CheckpointState state;
  long long step = 0;

 private:
  std::uint64_t fingerprint_;
  Run run_;
};

}  // namespace mfree::testing

#pragma once
// Checkpoints of long runs (total-Lagrangian dynamics, MPM), so that a killed run continues
// where it was instead of starting again.
//
// A run with `[output] checkpoint_every = N` writes, after every N-th step (not the last),
//
//   FOLDER.checkpoints/step_NNNNNNNNNN/state.bin   the run's state (below)
//   FOLDER.checkpoints/step_NNNNNNNNNN/output/     the output folder as it is at that step
//
// beside the output FOLDER. The output is kept as hard links: every output file is written
// to a temporary name and renamed into place (atomic_file.hpp), so a link keeps the content
// it had when the run replaces the file later (a copy where the file system has no links).
// A checkpoint is written into a hidden folder and renamed into place, so it is whole or
// absent; the last two are kept. `mfree run SCENE --restart FOLDER.checkpoints` reads the
// newest, refuses it unless it was written by the same scene and overrides (a fingerprint of
// their text), fills the new run's staging folder with its output and continues from its
// step: the results are those of a run that was never interrupted, bit for bit (same build,
// same thread count). A run that ends, with results or with an error, removes its
// checkpoints (apps/report.hpp); only a killed run keeps them.
//
// state.bin holds named arrays of doubles (integers up to 2^53 are exact): the magic
// "MFREECK1", the fingerprint, the step, the number of arrays, then per array its name, its
// length and its values (little-endian, as the machine stores them), and last an FNV-1a hash
// of everything before it.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mfree {

/// The state of a run at one step: named arrays of doubles.
class CheckpointState {
 public:
  void put(const std::string& name, std::vector<double> values);
  void put(const std::string& name, double value) { put(name, std::vector<double>{value}); }
  /// Fixed-size Eigen values (Vec2, Mat2, ...), stored as their coefficients.
  template <class T>
  void put_values(const std::string& name, const std::vector<T>& values) {
    constexpr int n = T::SizeAtCompileTime;
    std::vector<double> flat(values.size() * n);
    for (std::size_t k = 0; k < values.size(); ++k)
      Eigen::Map<T>(flat.data() + k * n) = values[k];
    put(name, std::move(flat));
  }
  void put_ints(const std::string& name, const std::vector<int>& values);

  /// The array `name`; InputError when it is missing or (size given) not that long.
  [[nodiscard]] const std::vector<double>& get(const std::string& name, std::optional<std::size_t> size = {}) const;
  [[nodiscard]] double scalar(const std::string& name) const { return get(name, 1)[0]; }
  template <class T>
  [[nodiscard]] std::vector<T> values(const std::string& name) const {
    constexpr int n = T::SizeAtCompileTime;
    const std::vector<double>& flat = get(name);
    if (flat.size() % n != 0) fail(name, "its length is not a multiple of the value size");
    std::vector<T> out(flat.size() / n);
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = Eigen::Map<const T>(flat.data() + k * n);
    return out;
  }
  [[nodiscard]] std::vector<int> ints(const std::string& name) const;
  [[nodiscard]] bool has(const std::string& name) const { return arrays_.count(name) > 0; }

  [[nodiscard]] const std::map<std::string, std::vector<double>>& arrays() const { return arrays_; }
  /// Where the state came from, for messages.
  std::filesystem::path source;

 private:
  [[noreturn]] void fail(const std::string& name, const std::string& what) const;
  std::map<std::string, std::vector<double>> arrays_;
};

/// FNV-1a hash of a scene's text and its overrides: what a restart must match.
std::uint64_t scene_fingerprint(const std::filesystem::path& scene, const std::vector<std::string>& overrides);

/// The checkpoints of one run: where they go, how often, and the one to start from.
class Checkpoints {
 public:
  /// every: steps between checkpoints (0: none). restart: a checkpoint folder to continue
  /// from (empty: start at step 0). InputError when restart names no folder of checkpoints,
  /// none of them is readable, or the newest was written by another scene.
  Checkpoints(std::filesystem::path output_folder, int every, std::uint64_t fingerprint,
              const std::filesystem::path& restart);

  /// FOLDER.checkpoints beside the output folder.
  [[nodiscard]] const std::filesystem::path& folder() const { return folder_; }
  [[nodiscard]] int every() const { return every_; }
  /// True after step `step` of `steps` when a checkpoint is due.
  [[nodiscard]] bool due(long long step, long long steps) const {
    return every_ > 0 && step < steps && step % every_ == 0;
  }
  /// The state to continue from (restart), with its step; nullptr for a fresh start.
  [[nodiscard]] const CheckpointState* resume() const { return resume_ ? &*resume_ : nullptr; }
  [[nodiscard]] long long resume_step() const { return resume_step_; }
  /// Links the restart checkpoint's output into `staging` (the new run's output folder).
  void restore_output(const std::filesystem::path& staging) const;

  /// Writes the checkpoint of `step`: `state` and the files of `staging` (see above); keeps
  /// the last two. Error when the file system refuses.
  void write(long long step, const CheckpointState& state, const std::filesystem::path& staging) const;
  /// Removes the checkpoint folder (after the run succeeded).
  void remove() const;

 private:
  std::filesystem::path folder_;
  int every_ = 0;
  std::uint64_t fingerprint_ = 0;
  std::optional<CheckpointState> resume_;
  std::filesystem::path resume_folder_;
  long long resume_step_ = 0;
};

}  // namespace mfree

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
//
// A checksum and a fingerprint that match say the file is the one a run of this scene wrote,
// not that its content is sound (a program or a hand may have written it, checksum and all).
// So nothing in it is used unchecked: the reader refuses a file whose step differs from its
// folder's name and any value that is not finite (NaN, inf) in any array, and every restore
// checks each array it takes (CheckpointState's within(), integers()) against the run it
// continues: its length against the scene's particles, DOFs, bodies; indices against the
// scene's lists; signs the physics needs; steps and times within the run. Every refusal is an
// InputError naming the file, the array, and the index and value at fault. The writer
// refuses a non-finite value (NumericalError), so a run never writes a checkpoint it would
// refuse.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

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
  /// get(name, size), each value in [lo, hi]; InputError naming the first that is not, its
  /// index and value, and `range` (what [lo, hi] is: "positive", "a time of this run", ...).
  [[nodiscard]] const std::vector<double>& within(const std::string& name, double lo, double hi,
                                                  const std::string& range,
                                                  std::optional<std::size_t> size = {}) const;
  /// get(name, size), each value a whole number in [lo, hi] (indices, counts); InputError as
  /// within().
  [[nodiscard]] std::vector<long long> integers(const std::string& name, long long lo, long long hi,
                                                const std::string& range,
                                                std::optional<std::size_t> size = {}) const;
  /// A series of times [s]: at most `most` values, each in [0, end] and none before the one
  /// before it; InputError as within().
  [[nodiscard]] const std::vector<double>& times(const std::string& name, double end, std::size_t most) const;
  /// InputError: array `name` of this checkpoint is refused for `what` (see the top).
  [[noreturn]] void refuse(const std::string& name, const std::string& what) const;
  [[nodiscard]] double scalar(const std::string& name) const { return get(name, 1)[0]; }
  /// The array `name` as fixed-size Eigen values (`count` of them when given).
  template <class T>
  [[nodiscard]] std::vector<T> values(const std::string& name, std::optional<std::size_t> count = {}) const {
    constexpr int n = T::SizeAtCompileTime;
    const std::vector<double>& flat =
        get(name, count ? std::optional<std::size_t>(*count * n) : std::nullopt);
    if (flat.size() % n != 0) refuse(name, "its length is not a multiple of " + std::to_string(n));
    std::vector<T> out(flat.size() / n);
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = Eigen::Map<const T>(flat.data() + k * n);
    return out;
  }
  /// The values of `name` as int: integers() over the range of int.
  [[nodiscard]] std::vector<int> ints(const std::string& name, std::optional<std::size_t> size = {}) const;
  [[nodiscard]] bool has(const std::string& name) const { return arrays_.count(name) > 0; }

  [[nodiscard]] const std::map<std::string, std::vector<double>>& arrays() const { return arrays_; }
  /// Where the state came from, for messages.
  std::filesystem::path source;

 private:
  std::map<std::string, std::vector<double>> arrays_;
};

/// The bytes of a state.bin around its body (the step, the number of arrays and the arrays, as
/// above): the magic, the fingerprint, the body, and the hash of all of them.
std::string checkpoint_file(std::uint64_t fingerprint, std::string_view body);

/// FNV-1a hash of a scene's text and its overrides: what a restart must match.
std::uint64_t scene_fingerprint(const std::filesystem::path& scene, const std::vector<std::string>& overrides);

/// The checkpoints of one run: where they go, how often, and the one to start from.
class Checkpoints {
 public:
  /// every: steps between checkpoints (0: none). restart: a checkpoint folder to continue
  /// from (empty: start at step 0). InputError when restart names no folder of checkpoints,
  /// none of them is readable, the newest was written by another scene, holds another step
  /// than its folder names or a value that is not finite.
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
  /// the last two. Error when the file system refuses; NumericalError, naming the array and
  /// the index, for a value that is not finite (nothing written).
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

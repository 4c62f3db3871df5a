#pragma once
// A run's output folder, replaced as a whole. The run writes into a hidden staging folder
// beside it, ".NAME.partial-PID"; commit() swaps the staging folder into place (one atomic
// exchange when the folder exists, a rename when it does not) and removes the old results.
// A run that fails leaves the previous results as they were and removes its staging folder;
// a killed run's staging folder stays hidden and is removed by the next run into the same
// folder (when its process is gone).
//
// An existing folder is replaced only when mfree wrote it (it holds the marker file
// .mfree-output, or a run's summary.json or a study's table) or it is empty: a scene naming
// a folder of the user's is an InputError, never a deletion.
//
// A run stopped by a signal (io/interrupt.hpp) removes its staging folders through
// abandon_staging_folders(): every StagedFolder alive registers its staging folder until it
// is committed or destroyed.

#include <filesystem>
#include <vector>

namespace mfree {

class StagedFolder {
 public:
  /// Prepares the staging folder for `target`. InputError when `target` exists and is not
  /// an mfree output folder (or not a folder); Error when the staging folder cannot be made.
  explicit StagedFolder(std::filesystem::path target);
  ~StagedFolder();  ///< removes the staging folder unless committed
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  /// Where the run writes.
  [[nodiscard]] const std::filesystem::path& path() const { return staging_; }
  /// Where the results end up.
  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  /// Puts the staged results in place of the target's. Error when the file system refuses.
  void commit();

 private:
  void remove_staging();
  std::filesystem::path target_, staging_;
  bool committed_ = false;
};

/// Removes the staging folder of every StagedFolder alive and returns their targets. No
/// StagedFolder is made, committed or removed after it: the caller ends the process.
std::vector<std::filesystem::path> abandon_staging_folders();

}  // namespace mfree

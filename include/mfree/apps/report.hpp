#pragma once
// What the command-line runs print and draw at their end.

#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <string>

#include "mfree/core/stage_timer.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/staged_folder.hpp"

namespace mfree {

/// The stage table: seconds per stage and the total, on standard output.
void print_stages(const StageTimer& timer);

/// Runs verification/SCRIPT (matplotlib, the system python3) on a CSV to draw its PNG plots
/// into `folder`; a failure is reported on standard error and leaves the CSV as it is.
void plot(const std::string& script, const std::filesystem::path& csv, const std::filesystem::path& folder);

/// Runs `run` (returning an exit code) with `folder` pointing at a staging folder that
/// replaces the original `folder` when the run returns (io/staged_folder.hpp): a run that
/// throws leaves the previous results as they were.
template <class Run>
int in_staged_folder(std::filesystem::path& folder, Run&& run) {
  const std::filesystem::path target = folder;
  StagedFolder staged(target);
  folder = staged.path();
  const int code = run();
  staged.commit();
  folder = target;
  std::cout << fmt::format("results in {}\n", target.string());
  return code;
}

/// The same for a run with checkpoints: they are removed when the run ends, with its results
/// or with an error (a restart would meet the same error again); only a killed run keeps them.
template <class Run>
int in_staged_folder(std::filesystem::path& folder, const Checkpoints& checkpoints, Run&& run) {
  try {
    const int code = in_staged_folder(folder, run);
    checkpoints.remove();
    return code;
  } catch (...) {
    checkpoints.remove();
    throw;
  }
}

}  // namespace mfree

#pragma once
// What the command-line runs print and draw at their end.

#include <filesystem>
#include <string>

#include "mfree/core/stage_timer.hpp"

namespace mfree {

/// The stage table: seconds per stage and the total, on standard output.
void print_stages(const StageTimer& timer);

/// Runs verification/SCRIPT (matplotlib, the system python3) on a CSV to draw its PNG plots
/// into `folder`; a failure is reported on standard error and leaves the CSV as it is.
void plot(const std::string& script, const std::filesystem::path& csv, const std::filesystem::path& folder);

}  // namespace mfree

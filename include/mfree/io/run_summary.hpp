#pragma once
// summary.json: what one `mfree run` did, for scripts (verification/report reads it).
//
//   { "kind": "linear_statics" | "newton" | "dynamics" | "mpm" | "material_point_path", "scene": FILE,
//     "threads": N, "stages": [{"name", "seconds", "calls"}, ...], "total_seconds": s,
//     ...the run's own numbers (SI units, as printed) }
//
// A non-finite number is written as null: a summary never holds a NaN.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mfree/core/stage_timer.hpp"

namespace mfree {

class RunSummary {
 public:
  RunSummary(const std::string& kind, const std::filesystem::path& scene);

  void number(const std::string& key, double value);
  void text(const std::string& key, const std::string& value);
  void numbers(const std::string& key, const std::vector<double>& values);
  /// An array of flat objects, e.g. the errors at every error time.
  using Record = std::vector<std::pair<std::string, double>>;
  void records(const std::string& key, const std::vector<Record>& values);
  /// A flat object, e.g. a force and its moment.
  void object(const std::string& key, const Record& value);
  /// An object of named flat objects, {"name": {...}, ...}, e.g. the reactions per part.
  void objects(const std::string& key, const std::vector<std::pair<std::string, Record>>& values);
  /// Stage names, seconds and calls of the run, and their total.
  void stages(const StageTimer& timer);

  /// Writes folder/summary.json atomically.
  void write(const std::filesystem::path& folder) const;

 private:
  std::vector<std::pair<std::string, std::string>> entries_;  ///< key, JSON text
};

}  // namespace mfree

#include "mfree/io/run_summary.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mfree/core/parallel.hpp"
#include "mfree/io/atomic_file.hpp"

namespace mfree {

namespace {

std::string json_number(double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : "null"; }

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<int>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string json_object(const RunSummary::Record& r) {
  std::string out = "{";
  for (std::size_t i = 0; i < r.size(); ++i)
    out += fmt::format("{}{}: {}", i ? ", " : "", json_string(r[i].first), json_number(r[i].second));
  return out + "}";
}

}  // namespace

RunSummary::RunSummary(const std::string& kind, const std::filesystem::path& scene) {
  text("kind", kind);
  text("scene", scene.string());
  number("threads", thread_count());
}

void RunSummary::number(const std::string& key, double value) { entries_.emplace_back(key, json_number(value)); }

void RunSummary::text(const std::string& key, const std::string& value) { entries_.emplace_back(key, json_string(value)); }

void RunSummary::numbers(const std::string& key, const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + json_number(values[i]);
  entries_.emplace_back(key, out + "]");
}

void RunSummary::records(const std::string& key, const std::vector<Record>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ",\n    " : "\n    ") + json_object(values[i]);
  entries_.emplace_back(key, out + (values.empty() ? "]" : "\n  ]"));
}

void RunSummary::object(const std::string& key, const Record& value) {
  entries_.emplace_back(key, json_object(value));
}

void RunSummary::objects(const std::string& key, const std::vector<std::pair<std::string, Record>>& values) {
  std::string out = "{";
  for (std::size_t i = 0; i < values.size(); ++i)
    out += fmt::format("{}\n    {}: {}", i ? "," : "", json_string(values[i].first),
                       json_object(values[i].second));
  entries_.emplace_back(key, out + (values.empty() ? "}" : "\n  }"));
}

void RunSummary::stages(const StageTimer& timer) {
  std::string out = "[";
  for (std::size_t i = 0; i < timer.stages().size(); ++i)
    out += fmt::format("{}\n    {{\"name\": {}, \"seconds\": {}, \"calls\": {}}}", i ? "," : "",
                       json_string(timer.stages()[i].first), json_number(timer.stages()[i].second), timer.calls()[i]);
  entries_.emplace_back("stages", out + "\n  ]");
  number("total_seconds", timer.total());
}

void RunSummary::write(const std::filesystem::path& folder) const {
  std::string out = "{";
  for (std::size_t i = 0; i < entries_.size(); ++i)
    out += fmt::format("{}\n  {}: {}", i ? "," : "", json_string(entries_[i].first), entries_[i].second);
  write_file_atomically(folder / "summary.json", out + "\n}\n");
}

}  // namespace mfree

#pragma once
// Wall-clock time of the named stages of a run, in the order they first ran, and how many
// times each ran (a stage computed once per run shows 1 however many steps reuse it);
// optionally reports each stage as it finishes (progress of long runs).

#include <chrono>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mfree {

class StageTimer {
 public:
  /// Report every finished stage on `log` (nullptr: silent).
  void report_to(std::ostream* log) { log_ = log; }

  /// Runs f() and adds its wall time to stage `name`; returns what f returns.
  template <class F>
  decltype(auto) time(const std::string& name, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    struct Record {
      StageTimer& timer;
      const std::string& name;
      std::chrono::steady_clock::time_point t0;
      ~Record() { timer.add(name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()); }
    } record{*this, name, t0};
    return f();
  }
  void add(const std::string& name, double seconds) {
    if (log_) {
      std::ostringstream line;
      line << "  ... " << name << " done in " << std::fixed << std::setprecision(3) << seconds << " s\n";
      *log_ << line.str() << std::flush;
    }
    for (std::size_t i = 0; i < stages_.size(); ++i)
      if (stages_[i].first == name) {
        stages_[i].second += seconds;
        ++calls_[i];
        return;
      }
    stages_.emplace_back(name, seconds);
    calls_.push_back(1);
  }
  [[nodiscard]] const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }
  /// calls()[i]: how many times stages()[i] ran.
  [[nodiscard]] const std::vector<long>& calls() const { return calls_; }
  [[nodiscard]] double total() const {
    double t = 0.0;
    for (const auto& [n, s] : stages_) t += s;
    return t;
  }
  /// total() without the stage `name` (a measurement that is not part of the run's work).
  [[nodiscard]] double total_without(const std::string& name) const {
    double t = 0.0;
    for (const auto& [n, s] : stages_)
      if (n != name) t += s;
    return t;
  }

 private:
  std::vector<std::pair<std::string, double>> stages_;
  std::vector<long> calls_;
  std::ostream* log_ = nullptr;
};

}  // namespace mfree

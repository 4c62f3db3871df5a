#pragma once
// The reactions of a Galerkin run (galerkin/reactions.hpp) as the run reports them, in the
// plane (dim = 2) and in solids (dim = 3):
//
//   console        reaction_lines(): a line per essential part (force R, moment M about the
//                  origin), the applied loads F, (dynamics) the inertia M a, and the balance
//                  sum R + F (- M a) with its relative size |.| / |F| (imbalance, Reactions)
//   reactions.csv  ReactionTable: columns step, load_factor (statics) or time (dynamics),
//                  part, rx, ry, moment (plane) or rx, ry, rz, mx, my, mz (solid); per record
//                  a row per essential part by its name, then "applied", (dynamics)
//                  "inertia", and "balance"
//   summary.json   summarise_reactions(): "reactions": {part: {force_x, force_y, moment}} (a
//                  solid: force_x .. force_z, moment_x .. moment_z), "applied": {...},
//                  ("inertia": {...},) "imbalance", "moment_imbalance"
//
// In the plane forces and moments are per unit thickness; units those of the scene.
// Explicitly instantiated for dim = 2 and 3.

#include <string>
#include <vector>

#include "mfree/galerkin/reactions.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/run_summary.hpp"

namespace mfree {

/// The console block: a heading and one line per part, the loads and the balance, each
/// line indented by `indent`.
template <int dim>
std::string reaction_lines(const Reactions<dim>& r, const std::string& indent = "  ");

/// The last reactions of a run into its summary.
template <int dim>
void summarise_reactions(RunSummary& summary, const Reactions<dim>& r);

/// The reactions of a run's steps, for reactions.csv.
template <int dim>
class ReactionTable {
 public:
  /// column: "load_factor" (statics) or "time" (dynamics); parts: the essential parts' names
  /// (essential_parts()); inertia: records hold the inertia (dynamics).
  ReactionTable(std::string column, std::vector<std::string> parts, bool inertia);

  /// Adds the record of step `step` at load factor or time `at`; r of the table's parts.
  void add(int step, double at, const Reactions<dim>& r);
  [[nodiscard]] std::size_t size() const { return records_.size(); }
  [[nodiscard]] std::string csv() const;

  /// Checkpoints: the records as numbers ("reactions"), and the records of a run resumed at
  /// `step` and `time` (InputError, naming the value, when they do not fit: whole records,
  /// steps increasing up to `step`, at values 0 to `time`).
  void save(CheckpointState& state) const;
  void restore(const CheckpointState& state, long long step, double time);

 private:
  struct Record {
    int step = 0;
    double at = 0.0;
    std::vector<Resultant<dim>> parts;
    Resultant<dim> applied, inertia;
  };
  /// Numbers of a resultant: the force and the moment (1 in the plane, 3 in space).
  static constexpr std::size_t resultant_size = dim == 2 ? 3 : 6;
  [[nodiscard]] std::size_t width() const {
    return 2 + resultant_size * (parts_.size() + (inertia_ ? 2 : 1));
  }

  std::string column_;
  std::vector<std::string> parts_;
  bool inertia_;
  std::vector<Record> records_;
};

}  // namespace mfree

#include "mfree/io/reaction_output.hpp"

#include <fmt/format.h>

#include "mfree/io/csv.hpp"

namespace mfree {

namespace {

/// A part's name as one CSV cell: separators, quotes and line breaks replaced as csv_status
/// replaces them.
std::string csv_name(std::string name) {
  for (char& c : name) {
    if (c == ',') c = ';';
    if (c == '"') c = '\'';
    if (c == '\n' || c == '\r') c = ' ';
  }
  return name;
}

std::string line(const std::string& indent, const std::string& label, const char* symbol,
                 const Resultant<2>& r) {
  return fmt::format("{}  {:<22} {} = ({:14.6e}, {:14.6e}), M = {:14.6e}\n", indent, label, symbol,
                     r.force.x(), r.force.y(), r.moment);
}

RunSummary::Record record(const Resultant<2>& r) {
  return {{"force_x", r.force.x()}, {"force_y", r.force.y()}, {"moment", r.moment}};
}

}  // namespace

std::string reaction_lines(const Reactions<2>& r, const std::string& indent) {
  std::string out = fmt::format(
      "{}reactions of the essential parts (force per unit thickness, moment about the origin, arm {}):\n",
      indent, r.current_arm ? "X + u^h" : "X");
  for (const PartReaction<2>& p : r.parts) out += line(indent, p.name, "R", p.reaction);
  out += line(indent, "applied loads", "F", r.applied);
  if (r.inertia) out += line(indent, "inertia", "M a", *r.inertia);
  out += line(indent, r.inertia ? "sum R + F - M a" : "sum R + F", " ", r.balance());
  out += fmt::format("{}  imbalance {:.3e} of the largest force, moment {:.3e}\n", indent,
                     r.force_imbalance(), r.moment_imbalance());
  return out;
}

void summarise_reactions(RunSummary& summary, const Reactions<2>& r) {
  std::vector<std::pair<std::string, RunSummary::Record>> parts;
  for (const PartReaction<2>& p : r.parts) parts.emplace_back(p.name, record(p.reaction));
  summary.objects("reactions", parts);
  summary.object("applied", record(r.applied));
  if (r.inertia) summary.object("inertia", record(*r.inertia));
  summary.number("imbalance", r.force_imbalance());
  summary.number("moment_imbalance", r.moment_imbalance());
}

ReactionTable::ReactionTable(std::string column, std::vector<std::string> parts, bool inertia)
    : column_(std::move(column)), parts_(std::move(parts)), inertia_(inertia) {}

void ReactionTable::add(int step, double at, const Reactions<2>& r) {
  Record rec{step, at, {}, r.applied, r.inertia.value_or(Resultant<2>{})};
  for (const PartReaction<2>& p : r.parts) rec.parts.push_back(p.reaction);
  records_.push_back(std::move(rec));
}

std::string ReactionTable::csv() const {
  std::string out = fmt::format("step,{},part,rx,ry,moment\n", column_);
  for (const Record& rec : records_) {
    const auto row = [&](const std::string& part, const Resultant<2>& r) {
      out += fmt::format("{},{:.9g},{},{},{},{}\n", rec.step, rec.at, csv_name(part),
                         csv_number(r.force.x(), "{:.9e}"), csv_number(r.force.y(), "{:.9e}"),
                         csv_number(r.moment, "{:.9e}"));
    };
    Resultant<2> balance = rec.applied;
    for (std::size_t p = 0; p < parts_.size(); ++p) {
      row(parts_[p], rec.parts[p]);
      balance += rec.parts[p];
    }
    row("applied", rec.applied);
    if (inertia_) {
      row("inertia", rec.inertia);
      balance.force -= rec.inertia.force;
      balance.moment -= rec.inertia.moment;
    }
    row("balance", balance);
  }
  return out;
}

void ReactionTable::save(CheckpointState& state) const {
  std::vector<double> v;
  v.reserve(records_.size() * width());
  const auto put = [&](const Resultant<2>& r) { v.insert(v.end(), {r.force.x(), r.force.y(), r.moment}); };
  for (const Record& rec : records_) {
    v.insert(v.end(), {static_cast<double>(rec.step), rec.at});
    for (const Resultant<2>& r : rec.parts) put(r);
    put(rec.applied);
    if (inertia_) put(rec.inertia);
  }
  state.put("reactions", std::move(v));
}

void ReactionTable::restore(const CheckpointState& state, long long step, double time) {
  const std::vector<double>& v = state.get("reactions");
  const std::size_t n = width();
  if (v.size() % n != 0)
    state.refuse("reactions", fmt::format("it holds {} numbers, not {} per record ({} essential part(s){})",
                                          v.size(), n, parts_.size(), inertia_ ? " and the inertia" : ""));
  records_.clear();
  for (std::size_t at = 0; at < v.size(); at += n) {
    const double s = v[at];
    const long long before = records_.empty() ? -1 : records_.back().step;
    if (!(s > static_cast<double>(before) && s <= static_cast<double>(step) &&
          s == static_cast<double>(static_cast<long long>(s))))
      state.refuse("reactions",
                   fmt::format("value {} is {}, not a step after {} and up to the checkpoint's {}", at, s,
                               before, step));
    if (!(v[at + 1] >= 0.0 && v[at + 1] <= time))
      state.refuse("reactions", fmt::format("value {} is {}, not a {} of the run so far (0 to {})", at + 1,
                                            v[at + 1], column_, time));
    Record rec{static_cast<int>(s), v[at + 1], {}, {}, {}};
    const auto get = [&](std::size_t k) { return Resultant<2>{Vec2(v[k], v[k + 1]), v[k + 2]}; };
    std::size_t k = at + 2;
    for (std::size_t p = 0; p < parts_.size(); ++p, k += 3) rec.parts.push_back(get(k));
    rec.applied = get(k);
    if (inertia_) rec.inertia = get(k + 3);
    records_.push_back(std::move(rec));
  }
}

}  // namespace mfree

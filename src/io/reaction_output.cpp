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
std::string line(const std::string& indent, const std::string& label, const char* symbol,
                 const Resultant<3>& r) {
  return fmt::format("{}  {:<22} {} = ({:14.6e}, {:14.6e}, {:14.6e}), M = ({:14.6e}, {:14.6e}, {:14.6e})\n",
                     indent, label, symbol, r.force.x(), r.force.y(), r.force.z(), r.moment.x(), r.moment.y(),
                     r.moment.z());
}

RunSummary::Record record(const Resultant<2>& r) {
  return {{"force_x", r.force.x()}, {"force_y", r.force.y()}, {"moment", r.moment}};
}
RunSummary::Record record(const Resultant<3>& r) {
  return {{"force_x", r.force.x()},   {"force_y", r.force.y()},   {"force_z", r.force.z()},
          {"moment_x", r.moment.x()}, {"moment_y", r.moment.y()}, {"moment_z", r.moment.z()}};
}

/// A resultant's numbers: the force, then the moment.
void append(std::vector<double>& v, const Resultant<2>& r) {
  v.insert(v.end(), {r.force.x(), r.force.y(), r.moment});
}
void append(std::vector<double>& v, const Resultant<3>& r) {
  v.insert(v.end(), {r.force.x(), r.force.y(), r.force.z(), r.moment.x(), r.moment.y(), r.moment.z()});
}
template <int dim>
Resultant<dim> resultant_at(const double* x) {
  Resultant<dim> r;
  r.force = Eigen::Map<const Point<dim>>(x);
  if constexpr (dim == 2)
    r.moment = x[2];
  else
    r.moment = Eigen::Map<const Point<3>>(x + 3);
  return r;
}

}  // namespace

template <int dim>
std::string reaction_lines(const Reactions<dim>& r, const std::string& indent) {
  std::string out =
      fmt::format("{}reactions of the essential parts ({}, moment about the origin, arm {}):\n", indent,
                  dim == 2 ? "force per unit thickness" : "force", r.current_arm ? "X + u^h" : "X");
  for (const PartReaction<dim>& p : r.parts) out += line(indent, p.name, "R", p.reaction);
  out += line(indent, "applied loads", "F", r.applied);
  if (r.inertia) out += line(indent, "inertia", "M a", *r.inertia);
  out += line(indent, r.inertia ? "sum R + F - M a" : "sum R + F", " ", r.balance());
  out += fmt::format("{}  imbalance {:.3e} of the largest force, moment {:.3e}\n", indent,
                     r.force_imbalance(), r.moment_imbalance());
  return out;
}

template <int dim>
void summarise_reactions(RunSummary& summary, const Reactions<dim>& r) {
  std::vector<std::pair<std::string, RunSummary::Record>> parts;
  for (const PartReaction<dim>& p : r.parts) parts.emplace_back(p.name, record(p.reaction));
  summary.objects("reactions", parts);
  summary.object("applied", record(r.applied));
  if (r.inertia) summary.object("inertia", record(*r.inertia));
  summary.number("imbalance", r.force_imbalance());
  summary.number("moment_imbalance", r.moment_imbalance());
}

template <int dim>
ReactionTable<dim>::ReactionTable(std::string column, std::vector<std::string> parts, bool inertia)
    : column_(std::move(column)), parts_(std::move(parts)), inertia_(inertia) {}

template <int dim>
void ReactionTable<dim>::add(int step, double at, const Reactions<dim>& r) {
  Record rec{step, at, {}, r.applied, r.inertia.value_or(Resultant<dim>{})};
  for (const PartReaction<dim>& p : r.parts) rec.parts.push_back(p.reaction);
  records_.push_back(std::move(rec));
}

template <int dim>
std::string ReactionTable<dim>::csv() const {
  std::string out =
      fmt::format("step,{},part,{}\n", column_, dim == 2 ? "rx,ry,moment" : "rx,ry,rz,mx,my,mz");
  for (const Record& rec : records_) {
    const auto row = [&](const std::string& part, const Resultant<dim>& r) {
      std::vector<double> v;
      append(v, r);
      out += fmt::format("{},{:.9g},{}", rec.step, rec.at, csv_name(part));
      for (double x : v) {
        out += ',';
        out += csv_number(x, "{:.9e}");
      }
      out += "\n";
    };
    Resultant<dim> balance = rec.applied;
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

template <int dim>
void ReactionTable<dim>::save(CheckpointState& state) const {
  std::vector<double> v;
  v.reserve(records_.size() * width());
  for (const Record& rec : records_) {
    v.insert(v.end(), {static_cast<double>(rec.step), rec.at});
    for (const Resultant<dim>& r : rec.parts) append(v, r);
    append(v, rec.applied);
    if (inertia_) append(v, rec.inertia);
  }
  state.put("reactions", std::move(v));
}

template <int dim>
void ReactionTable<dim>::restore(const CheckpointState& state, long long step, double time) {
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
    const auto get = [&](std::size_t k) { return resultant_at<dim>(v.data() + k); };
    std::size_t k = at + 2;
    for (std::size_t p = 0; p < parts_.size(); ++p, k += resultant_size) rec.parts.push_back(get(k));
    rec.applied = get(k);
    if (inertia_) rec.inertia = get(k + resultant_size);
    records_.push_back(std::move(rec));
  }
}

template std::string reaction_lines<2>(const Reactions<2>&, const std::string&);
template std::string reaction_lines<3>(const Reactions<3>&, const std::string&);
template void summarise_reactions<2>(RunSummary&, const Reactions<2>&);
template void summarise_reactions<3>(RunSummary&, const Reactions<3>&);
template class ReactionTable<2>;
template class ReactionTable<3>;

}  // namespace mfree

#include "mfree/io/dynamics_checkpoint.hpp"

#include <fmt/format.h>

#include <limits>

#include "mfree/core/error.hpp"
#include "mfree/core/step_count.hpp"

namespace mfree {

namespace {

void put_vector(CheckpointState& s, const std::string& name, const Eigen::VectorXd& v) {
  s.put(name, std::vector<double>(v.data(), v.data() + v.size()));
}

Eigen::VectorXd get_vector(const CheckpointState& s, const std::string& name) {
  const std::vector<double>& v = s.get(name);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

/// Numbers a material state takes: E_p (dim^2), E_p,zz, alpha, dissipation.
template <int dim>
constexpr std::size_t state_size = dim* dim + 3;

template <int dim>
void put_history(CheckpointState& s, const std::string& name, const std::vector<MaterialState<dim>>& states) {
  std::vector<double> v;
  v.reserve(state_size<dim> * states.size());
  for (const MaterialState<dim>& m : states) {
    v.insert(v.end(), m.plastic_strain.data(), m.plastic_strain.data() + dim * dim);
    v.insert(v.end(), {m.plastic_strain_zz, m.alpha, m.dissipation});
  }
  s.put(name, std::move(v));
}

/// The states put_history() wrote: whole records, alpha (the equivalent plastic strain) 0 or
/// more. Their number is checked against the model by integrate_dynamics.
template <int dim>
std::vector<MaterialState<dim>> get_history(const CheckpointState& s, const std::string& name) {
  constexpr std::size_t n = state_size<dim>;
  const std::vector<double>& v = s.get(name);
  if (v.size() % n != 0) s.refuse(name, fmt::format("it holds {} numbers, not {} per point", v.size(), n));
  std::vector<MaterialState<dim>> states(v.size() / n);
  for (std::size_t k = 0; k < states.size(); ++k) {
    const double* x = v.data() + n * k;
    constexpr std::size_t alpha = dim * dim + 1;
    if (!(x[alpha] >= 0.0))
      s.refuse(name, fmt::format("value {} is {}, not an equivalent plastic strain (0 or more)",
                                 n * k + alpha, x[alpha]));
    states[k].plastic_strain = Eigen::Map<const Tensor2<dim>>(x);
    states[k].plastic_strain_zz = x[dim * dim];
    states[k].alpha = x[alpha];
    states[k].dissipation = x[alpha + 1];
  }
  return states;
}

}  // namespace

template <int dim>
void save_progress(CheckpointState& s, const DynamicsProgress<dim>& p) {
  s.put("step", p.step);
  put_vector(s, "d", p.d);
  put_vector(s, "v", p.v);
  put_vector(s, "a", p.a);
  put_vector(s, "v_half", p.v_half);
  put_vector(s, "g", p.g);
  s.put("work", p.work);
  std::vector<double> energy;
  for (const EnergyRecord& e : p.energy)
    energy.insert(energy.end(), {e.time, e.kinetic, e.strain, e.external_work, e.dissipated});
  s.put("energy", std::move(energy));
  put_history(s, "history.domain", p.history.domain);
  put_history(s, "history.boundary", p.history.boundary);
  s.put("newton_iterations", static_cast<double>(p.newton_iterations));
  s.put("factorisations", static_cast<double>(p.factorisations));
  put_vector(s, "tangent", p.tangent);
}

template <int dim>
DynamicsProgress<dim> restore_progress(const CheckpointState& s, long long step) {
  if (step > static_cast<long long>(max_time_steps))
    throw InputError(
        fmt::format("checkpoint {}: step {} is past the most steps a run may take ({:g}): the checkpoint "
                    "is damaged; restart from an earlier checkpoint or without --restart",
                    s.source.string(), step, max_time_steps));
  DynamicsProgress<dim> p;
  p.step =
      static_cast<int>(s.integers("step", step, step, fmt::format("the checkpoint's step {}", step), 1)[0]);
  p.d = get_vector(s, "d");
  p.v = get_vector(s, "v");
  p.a = get_vector(s, "a");
  p.v_half = get_vector(s, "v_half");
  p.g = get_vector(s, "g");
  p.work = s.scalar("work");
  const std::vector<double>& e = s.get("energy");
  if (e.size() % 5 != 0) s.refuse("energy", fmt::format("it holds {} numbers, not 5 per record", e.size()));
  for (std::size_t at = 0; at < e.size(); at += 5)
    p.energy.push_back({e[at], e[at + 1], e[at + 2], e[at + 3], e[at + 4]});
  p.history = {get_history<dim>(s, "history.domain"), get_history<dim>(s, "history.boundary")};
  constexpr long long most = 1LL << 53;  // doubles hold every whole number up to here
  p.newton_iterations =
      static_cast<long>(s.integers("newton_iterations", 0, most, "a count (0 or more)", 1)[0]);
  p.factorisations = static_cast<long>(s.integers("factorisations", 0, most, "a count (0 or more)", 1)[0]);
  p.tangent = get_vector(s, "tangent");
  return p;
}

template <int dim>
DynamicsCheckpointing<dim>::DynamicsCheckpointing(const Checkpoints* checkpoints,
                                                  std::filesystem::path staging, StageTimer& timer, Save save,
                                                  Restore restore, std::ostream* log)
    : save_(std::move(save)), restore_(std::move(restore)) {
  if (!checkpoints) return;
  if (const CheckpointState* state = checkpoints->resume()) {
    const long long step = checkpoints->resume_step();
    resume_ = restore_progress<dim>(*state, step);
    hooks_.resume = &*resume_;
    hooks_.refuse = [state](const std::string& name, const std::string& what) { state->refuse(name, what); };
    hooks_.resumed = [this, state, step](int, double dt) {
      if (restore_) restore_(*state, step, static_cast<double>(step) * dt);  // as the integrator's t = n dt
    };
    if (log)
      *log << fmt::format("  continuing from step {} of {}\n", step, state->source.parent_path().string());
  }
  if (checkpoints->every() > 0) {
    hooks_.every = checkpoints->every();
    hooks_.save = [this, checkpoints, staging = std::move(staging), &timer](const DynamicsProgress<dim>& p) {
      CheckpointState state;
      save_progress(state, p);
      if (save_) save_(state);
      timer.time("checkpoints", [&] { checkpoints->write(p.step, state, staging); });
    };
    if (log)
      *log << fmt::format("  checkpoints every {} steps in {}\n", hooks_.every,
                          checkpoints->folder().string());
  }
}

void save_errors(CheckpointState& s, const std::vector<MotionErrors>& errors) {
  std::vector<double> v;
  for (const MotionErrors& e : errors) v.insert(v.end(), {e.time, e.displacement, e.velocity, e.stress});
  s.put("errors", std::move(v));
}

std::vector<MotionErrors> restore_errors(const CheckpointState& s, long long step, double time,
                                         std::size_t most) {
  const std::vector<double>& v =
      s.within("errors", 0.0, std::numeric_limits<double>::infinity(), "a time or an error (0 or more)");
  if (v.size() % 4 != 0 || v.size() / 4 > most)
    s.refuse("errors",
             fmt::format("it holds {} numbers, not 4 for each of at most {} error times", v.size(), most));
  std::vector<MotionErrors> errors;
  for (std::size_t at = 0; at < v.size(); at += 4) {
    if (v[at] > time)
      s.refuse("errors",
               fmt::format("value {} is {}, after the run's time {} s at step {}", at, v[at], time, step));
    errors.push_back({v[at], v[at + 1], v[at + 2], v[at + 3]});
  }
  return errors;
}

template <int dim>
void save_probe(CheckpointState& s, const ProbeHistory<dim>& probe) {
  std::vector<double> v;
  for (const auto& [t, u] : probe) {
    v.push_back(t);
    v.insert(v.end(), u.data(), u.data() + dim);
  }
  s.put("probe", std::move(v));
}

template <int dim>
ProbeHistory<dim> restore_probe(const CheckpointState& s, long long step, double time, bool probe) {
  constexpr std::size_t n = 1 + dim;
  const std::vector<double>& v = s.get("probe", probe ? n * static_cast<std::size_t>(step + 1) : 0);
  ProbeHistory<dim> out;
  for (std::size_t at = 0; at < v.size(); at += n) {
    if (!(v[at] >= 0.0 && v[at] <= time))
      s.refuse("probe",
               fmt::format("value {} is {}, not a time of the run so far (0 to {} s)", at, v[at], time));
    out.emplace_back(v[at], Eigen::Map<const Point<dim>>(v.data() + at + 1));
  }
  return out;
}

template void save_probe<2>(CheckpointState&, const ProbeHistory<2>&);
template void save_probe<3>(CheckpointState&, const ProbeHistory<3>&);
template ProbeHistory<2> restore_probe<2>(const CheckpointState&, long long, double, bool);
template ProbeHistory<3> restore_probe<3>(const CheckpointState&, long long, double, bool);
template class DynamicsCheckpointing<2>;
template class DynamicsCheckpointing<3>;
template void save_progress<2>(CheckpointState&, const DynamicsProgress<2>&);
template void save_progress<3>(CheckpointState&, const DynamicsProgress<3>&);
template DynamicsProgress<2> restore_progress<2>(const CheckpointState&, long long);
template DynamicsProgress<3> restore_progress<3>(const CheckpointState&, long long);

}  // namespace mfree

#include "mfree/galerkin/elastodynamics.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <ostream>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/core/step_count.hpp"

namespace mfree {

const NameTable<TimeScheme>& time_scheme_names() {
  static const NameTable<TimeScheme> table{{"central_difference", TimeScheme::central_difference}, {"newmark", TimeScheme::newmark}};
  return table;
}

std::string_view to_string(TimeScheme s) { return time_scheme_names().name(s); }

template <int dim>
Eigen::VectorXd project_velocity(
    const TotalLagrangian<dim>& model, std::type_identity_t<std::span<const Point<dim>>> nodes,
    const std::type_identity_t<std::function<Point<dim>(const Point<dim>&)>>& field,
    const SolverSettings& settings) {
  // M v = int rho0 phi v0 with M's own densities: M^-1 of the rows is the L2 projection in rho0's weight.
  const GalerkinQuadrature<dim>& q = model.quadrature();
  const SparseMatrix m = model.mass_matrix();
  const std::vector<double> rho = model.point_densities();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(model.dofs());
  for (Index k = 0; k < q.size(); ++k) {
    const Point<dim> f = rho[static_cast<std::size_t>(k)] * q.weights[k] * field(q.points[k]);
    for (Index s = q.row_begin(k); s < q.row_end(k); ++s) rhs.segment<dim>(dim * q.nodes[s]) += q.phi[s] * f;
  }
  const std::unique_ptr<LinearSolver> solver =
      make_linear_solver(settings, {"mass", true, dim, nodes, false, true}, model.dofs());
  solver->analyze(m);
  solver->factorize(m);
  return solver->solve(rhs);
}

template <int dim>
double critical_time_step(const TotalLagrangian<dim>& model, const Eigen::VectorXd& lumped,
                          const Eigen::VectorXd& d) {
  SparseMatrix k = model.zero_matrix();
  model.tangent(d, {}, k);
  const Eigen::VectorXd scale = lumped.cwiseSqrt().cwiseInverse();
  // Power iteration on S = M^-1/2 K M^-1/2 from a seeded random start: the Rayleigh
  // quotient rises to omega_max^2. It stops when it changes by less than 1e-4 relative.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(lumped.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = u(rng);
  x.normalize();
  double lambda = 0.0;
  for (int it = 0; it < 2000; ++it) {
    const Eigen::VectorXd y = scale.cwiseProduct(k * scale.cwiseProduct(x));
    const double next = x.dot(y);
    x = y.normalized();
    if (it > 20 && std::abs(next - lambda) <= 1e-4 * std::abs(next)) {
      lambda = next;
      break;
    }
    lambda = next;
  }
  if (!(lambda > 0.0)) throw NumericalError("stability limit: the tangent has no positive eigenvalue");
  return 2.0 / std::sqrt(lambda);
}

namespace {

/// NumericalError when a nodal displacement or velocity is not finite: the first such value,
/// its node (index and position), the step and the time.
template <int dim>
void require_finite(const Eigen::VectorXd& d, const Eigen::VectorXd& v, const std::vector<Point<dim>>& nodes,
                    int step, double t) {
  for (const auto& [name, x] : {std::pair{"displacement", &d}, std::pair{"velocity", &v}}) {
    for (Eigen::Index k = 0; k < x->size(); ++k) {
      if (std::isfinite((*x)[k])) continue;
      const Point<dim>& at = nodes[static_cast<std::size_t>(k / dim)];
      throw NumericalError(fmt::format(
          "dynamics: the {} coefficient {} of node {} at ({:.6g}) is {} at step {} "
          "(t = {:.4e} s): the run diverged",
          name, "xyz"[k % dim], k / dim, fmt::join(at.begin(), at.end(), ", "), (*x)[k], step, t));
    }
  }
}

/// NumericalError when a term of the energy balance over the body is not finite.
void require_finite(const EnergyRecord& e, int step) {
  for (const auto& [name, value] :
       {std::pair{"kinetic energy", e.kinetic}, std::pair{"strain energy", e.strain},
        std::pair{"external work", e.external_work}, std::pair{"dissipated energy", e.dissipated}}) {
    if (!std::isfinite(value))
      throw NumericalError(fmt::format("dynamics: the {} of the body is {} at step {} (t = {:.4e} s)", name,
                                       value, step, e.time));
  }
}

/// dt = end / n, n = ceil(end / requested) (core/step_count.hpp).
std::pair<double, int> equal_steps(double end_time, double requested) {
  const int n = step_count(end_time, requested, "dynamics");
  return {end_time / n, n};
}

/// What a resumed state must fit (integrate_dynamics).
struct ResumeLimits {
  int steps = 0;
  double dt = 0.0;
  bool explicit_scheme = false;
  int energy_every = 0;       ///< 0: no energy recorded
  Eigen::Index nonzeros = 0;  ///< of the effective tangent (Newmark)
};

/// Refuses (through `refuse`) the first part of `p` that does not fit `model` and `limits`
/// (the checks integrate_dynamics lists).
template <int dim>
void check_resume(const DynamicsProgress<dim>& p, const TotalLagrangian<dim>& model,
                  const ResumeLimits& limits,
                  const std::function<void(const std::string&, const std::string&)>& refuse) {
  if (p.step < 0 || p.step >= limits.steps)
    refuse("step",
           fmt::format("value 0 is {}, not one of this run's steps (0 to {})", p.step, limits.steps - 1));
  const Eigen::Index n = model.dofs();
  const auto sized = [&](const char* name, const Eigen::VectorXd& x, Eigen::Index size, const char* of) {
    if (x.size() != size)
      refuse(name, fmt::format("it holds {} values, and this run needs {} ({})", x.size(), size, of));
  };
  sized("d", p.d, n, "its DOFs");
  sized("v", p.v, n, "its DOFs");
  sized("a", p.a, n, "its DOFs");
  sized("v_half", p.v_half, n, "its DOFs");
  sized("g", p.g, limits.energy_every > 0 ? n : 0,
        limits.energy_every > 0 ? "its DOFs" : "none: no energy is recorded");
  if (limits.explicit_scheme)
    sized("tangent", p.tangent, 0, "none: central differences keep no tangent");
  else if (p.tangent.size() > 0)
    sized("tangent", p.tangent, limits.nonzeros, "the nonzeros of its tangent, or none");
  const PointHistory<dim>& h = model.history();
  if (p.history.domain.size() != h.domain.size())
    refuse("history.domain",
           fmt::format("it holds {} points, and this run has {}", p.history.domain.size(), h.domain.size()));
  if (p.history.boundary.size() != h.boundary.size())
    refuse("history.boundary", fmt::format("it holds {} points, and this run has {}",
                                           p.history.boundary.size(), h.boundary.size()));
  // Records at step 0 and every energy_every-th step up to p.step, at t = n dt.
  const std::size_t records =
      limits.energy_every > 0 ? static_cast<std::size_t>(p.step / limits.energy_every) + 1 : 0;
  if (p.energy.size() != records)
    refuse("energy", fmt::format("it holds {} records, and the run wrote {} by step {}", p.energy.size(),
                                 records, p.step));
  const double time = p.step * limits.dt;
  for (std::size_t k = 0; k < p.energy.size(); ++k) {
    const EnergyRecord& e = p.energy[k];
    if (!(e.time >= 0.0 && e.time <= time))
      refuse("energy", fmt::format("record {} is at t = {} s, not a time of the run so far (0 to {} s)", k,
                                   e.time, time));
    if (!(e.kinetic >= 0.0))
      refuse("energy", fmt::format("record {} has kinetic energy {}, not 0 or more", k, e.kinetic));
  }
  if (p.newton_iterations < 0 || p.factorisations < 0)
    refuse("newton_iterations", "the counts of Newton iterations and factorisations must be 0 or more");
  for (Index k = 0; k < model.quadrature().size(); ++k)
    if (const double J = model.deformation_gradient(k, p.d).determinant(); !(J > 0.0))
      refuse("d", fmt::format("det F = {} at quadrature point {} ({:.6g}), not positive", J, k,
                              fmt::join(model.quadrature().points[k].begin(),
                                        model.quadrature().points[k].end(), ", ")));
}

}  // namespace

template <int dim>
DynamicsResult integrate_dynamics(TotalLagrangian<dim>& model, const std::vector<Point<dim>>& node_positions,
                                  Eigen::VectorXd d, Eigen::VectorXd v, const DynamicsSettings& s,
                                  StageTimer& timer, const std::function<void(const DynamicState&)>& on_step,
                                  const DynamicsCheckpoints<dim>& checkpoints) {
  if (!(s.end_time > 0.0)) throw InputError(fmt::format("dynamics: end_time must be positive, got {}", s.end_time));
  DynamicsResult out;
  const bool explicit_scheme = s.scheme == TimeScheme::central_difference;

  // Masses and the step.
  Eigen::VectorXd lumped;
  SparseMatrix mass;
  double dt = 0.0;
  if (explicit_scheme) {
    lumped = model.lumped_mass(node_positions);
    out.stability_limit = timer.time("stability limit", [&] { return critical_time_step(model, lumped, d); });
    if (s.time_step && *s.time_step > *out.stability_limit)
      throw InputError(fmt::format(
          "dynamics: time_step {:.4e} s is above the stability limit {:.4e} s of the central-difference "
          "scheme (2 / omega_max, omega_max^2 the largest eigenvalue of M_L^-1 K by power iteration); use "
          "a smaller time_step or the newmark scheme",
          *s.time_step, *out.stability_limit));
    std::tie(dt, out.steps) = equal_steps(s.end_time, s.time_step.value_or(s.stability_factor * *out.stability_limit));
  } else {
    if (!s.time_step) throw InputError("dynamics: the newmark scheme needs a time_step");
    mass = model.mass_matrix();
    std::tie(dt, out.steps) = equal_steps(s.end_time, *s.time_step);
  }
  out.time_step = dt;

  // Forces: g = f_ext - f_c (the work term), and the acceleration they and f_int give.
  const auto applied = [&](const Eigen::VectorXd& x, double t) {
    return timer.time("residual", [&] { return Eigen::VectorXd(model.external_force({1.0, t}) - model.boundary_force(x, {1.0, t})); });
  };
  const auto internal = [&](const Eigen::VectorXd& x) { return timer.time("residual", [&] { return model.internal_force(x); }); };
  Eigen::VectorXd g = applied(d, 0.0);
  Eigen::VectorXd a;
  if (explicit_scheme) {
    a = (g - internal(d)).cwiseQuotient(lumped);
  } else {
    const std::unique_ptr<LinearSolver> mass_solver =
        make_linear_solver(s.newton.solver, {"mass", true, dim, node_positions, false, true}, model.dofs());
    mass_solver->analyze(mass);
    mass_solver->factorize(mass);
    a = mass_solver->solve(g - internal(d));
  }
  const auto kinetic = [&](const Eigen::VectorXd& vel) {
    return 0.5 * (explicit_scheme ? vel.dot(lumped.cwiseProduct(vel)) : vel.dot(mass * vel));
  };
  // The energy balance only when asked for (energy_every > 0): its work term needs the
  // applied forces at every step, which Newmark does not otherwise evaluate.
  const bool energy = s.energy_every > 0;
  double work = 0.0;
  const auto record = [&](int step, double t) {
    require_finite(d, v, node_positions, step, t);
    if (on_step)
      on_step({step, t, d, v, a, explicit_scheme ? &lumped : nullptr, explicit_scheme ? nullptr : &mass});
    if (energy && (step % s.energy_every == 0 || step == out.steps)) {
      timer.time("energy", [&] { out.energy.push_back({t, kinetic(v), model.strain_energy(d), work, model.dissipated()}); });
      require_finite(out.energy.back(), step);
    }
  };

  // Newmark: the effective tangent K + 4 / dt^2 M on the one pattern, analysed once, at the
  // start state (the values matter to UMFPACK's pivoting: a resumed run analyses the same).
  std::unique_ptr<LinearSolver> solver;
  SparseMatrix k;
  const double c = 4.0 / (dt * dt);
  const auto effective_tangent = [&](const Eigen::VectorXd& x, double t, SparseMatrix& kt) {
    model.tangent(x, {1.0, t}, kt);
    Eigen::Map<Eigen::VectorXd>(kt.valuePtr(), kt.nonZeros()) +=
        c * Eigen::Map<const Eigen::VectorXd>(mass.valuePtr(), mass.nonZeros());
  };
  if (!explicit_scheme) {
    k = model.zero_matrix();
    timer.time("assembly", [&] { effective_tangent(d, 0.0, k); });
    solver = make_linear_solver(
        s.newton.solver,
        {"effective tangent", model.symmetric(), dim, node_positions, s.newton.nearly_symmetric, true},
        model.dofs());
    timer.time("factorisation", [&] { solver->analyze(k); });
  }

  Eigen::VectorXd v_half = v + 0.5 * dt * a;
  int first = 1;
  if (const DynamicsProgress<dim>* p = checkpoints.resume) {
    const auto refuse = [&](const std::string& name, const std::string& what) {
      if (checkpoints.refuse) checkpoints.refuse(name, what);
      throw InputError(fmt::format("dynamics: the saved state to resume from: '{}': {}", name, what));
    };
    check_resume(*p, model, {out.steps, dt, explicit_scheme, energy ? s.energy_every : 0, k.nonZeros()},
                 refuse);
    if (checkpoints.resumed) checkpoints.resumed(out.steps, dt);
    d = p->d;
    v = p->v;
    a = p->a;
    v_half = p->v_half;
    if (energy) g = p->g;
    work = p->work;
    out.energy = p->energy;
    out.newton_iterations = p->newton_iterations;
    out.factorisations = p->factorisations;
    if (!explicit_scheme && p->tangent.size() > 0) {
      Eigen::Map<Eigen::VectorXd>(k.valuePtr(), k.nonZeros()) = p->tangent;
      timer.time("factorisation", [&] { solver->factorize(k); });
    }
    model.set_history(p->history);
    first = p->step + 1;
  } else {
    model.commit(d);
    record(0, 0.0);
  }
  const auto save = [&](int n) {
    DynamicsProgress<dim> p{n,
                            d,
                            v,
                            a,
                            v_half,
                            energy ? g : Eigen::VectorXd(),
                            work,
                            out.energy,
                            out.newton_iterations,
                            out.factorisations,
                            Eigen::VectorXd(),
                            model.history()};
    if (!explicit_scheme && solver->factorized())
      p.tangent = Eigen::Map<const Eigen::VectorXd>(k.valuePtr(), k.nonZeros());
    checkpoints.save(p);
  };

  Eigen::VectorXd d_old;  // the work term's d_n
  for (int n = first; n <= out.steps; ++n) {
    const double t = n * dt;
    if (energy) d_old = d;
    Eigen::VectorXd g_new;  // f_ext - f_c at the new state
    if (explicit_scheme) {
      d += dt * v_half;
      try {
        g_new = applied(d, t);  // Nitsche's terms from the states of step n, then the step's states committed
        a = (g_new - timer.time("residual", [&] { return model.internal_force_committed(d); })).cwiseQuotient(lumped);
      } catch (const NumericalError& e) {  // the model knows where, the integrator when
        throw NumericalError(fmt::format("{} (central differences, step {}, t = {:.4e} s)", e.what(), n, t));
      }
      v = v_half + 0.5 * dt * a;
      v_half = v + 0.5 * dt * a;
      if (!std::isfinite(d.squaredNorm()))
        throw NumericalError(fmt::format("central differences diverged at step {} (t = {:.4e} s)", n, t));
    } else {
      const Eigen::VectorXd base = d + dt * v + 0.25 * dt * dt * a;  // d_n+1 = base + dt^2/4 a_n+1
      const Eigen::VectorXd f_ext = model.external_force({1.0, t});
      const NonlinearSystem system{
          [&](const Eigen::VectorXd& x) {
            const Eigen::VectorXd acc = c * (x - base);
            return Eigen::VectorXd(mass * acc + model.internal_force(x) + model.boundary_force(x, {1.0, t}) - f_ext);
          },
          [&](const Eigen::VectorXd& x, SparseMatrix& kt) { effective_tangent(x, t, kt); }};
      NewtonSettings ns = s.newton;
      ns.reuse_tangent = true;  // 4 M / dt^2 dominates the effective tangent: it hardly changes
      // A good predictor starts close to the solution: judge |R| against the step's forces.
      ns.absolute_tolerance = std::max(ns.absolute_tolerance, ns.tolerance * (f_ext.norm() + (mass * a).norm()));
      Eigen::VectorXd x = base + 0.25 * dt * dt * a;  // predictor: a_n+1 = a_n
      const NewtonOutcome o = newton(system, x, k, *solver, ns, timer);
      if (!o.converged)
        throw NumericalError(fmt::format("Newmark step {} (t = {:.4e} s): Newton failed: {}. Use a smaller time_step.",
                                         n, t, o.failure));
      out.newton_iterations += static_cast<long>(o.history.size()) - 1;
      out.factorisations += o.factorisations;
      const Eigen::VectorXd a_new = c * (x - base);
      v += 0.5 * dt * (a + a_new);
      a = a_new;
      d = std::move(x);
      if (energy) g_new = f_ext - timer.time("residual", [&] { return model.boundary_force(d, {1.0, t}); });
    }
    if (!explicit_scheme) model.commit(d);  // explicit steps committed with their forces
    if (energy) {
      work += 0.5 * (g + g_new).dot(d - d_old);
      g = g_new;
    }
    record(n, t);
    if (s.progress && (n % std::max(1, out.steps / 10) == 0 || n == out.steps))
      *s.progress << fmt::format("    step {}/{}  t = {:.5f} s{}\n", n, out.steps, t,
                                 energy ? fmt::format("  energy {:.6e}", out.energy.back().total()) : "")
                  << std::flush;
    if (checkpoints.every > 0 && checkpoints.save && n < out.steps && n % checkpoints.every == 0) save(n);
  }
  if (solver) out.solver = report(*solver);
  out.d = std::move(d);
  out.v = std::move(v);
  return out;
}

template Eigen::VectorXd project_velocity(const TotalLagrangian<2>&, std::span<const Point<2>>,
                                          const std::function<Point<2>(const Point<2>&)>&,
                                          const SolverSettings&);
template Eigen::VectorXd project_velocity(const TotalLagrangian<3>&, std::span<const Point<3>>,
                                          const std::function<Point<3>(const Point<3>&)>&,
                                          const SolverSettings&);
template double critical_time_step(const TotalLagrangian<2>&, const Eigen::VectorXd&, const Eigen::VectorXd&);
template double critical_time_step(const TotalLagrangian<3>&, const Eigen::VectorXd&, const Eigen::VectorXd&);
template DynamicsResult integrate_dynamics(TotalLagrangian<2>&, const std::vector<Point<2>>&, Eigen::VectorXd,
                                           Eigen::VectorXd, const DynamicsSettings&, StageTimer&,
                                           const std::function<void(const DynamicState&)>&,
                                           const DynamicsCheckpoints<2>&);
template DynamicsResult integrate_dynamics(TotalLagrangian<3>&, const std::vector<Point<3>>&, Eigen::VectorXd,
                                           Eigen::VectorXd, const DynamicsSettings&, StageTimer&,
                                           const std::function<void(const DynamicState&)>&,
                                           const DynamicsCheckpoints<3>&);

}  // namespace mfree

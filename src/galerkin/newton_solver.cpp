#include "mfree/galerkin/newton_solver.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <ostream>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

/// |R(d)|, or nullopt when d is not admissible (J <= 0 somewhere: `why` says where).
std::optional<double> residual_norm(const NonlinearSystem& system, const Eigen::VectorXd& d, Eigen::VectorXd& r,
                                    std::string& why) {
  try {
    r = system.residual(d);
  } catch (const NumericalError& e) {
    why = e.what();
    return std::nullopt;
  }
  return r.norm();
}

double observed_order(const std::vector<NewtonIterate>& h) {
  const std::size_t n = h.size();
  if (n < 3) return 0.0;
  const double r2 = h[n - 1].residual, r1 = h[n - 2].residual, r0 = h[n - 3].residual;
  if (!(r2 > 0.0 && r1 > 0.0 && r0 > 0.0) || r1 >= r0) return 0.0;
  return std::log(r2 / r1) / std::log(r1 / r0);
}

}  // namespace

NewtonOutcome newton(const NonlinearSystem& system, Eigen::VectorXd& d, SparseMatrix& k, LinearSolver& solver,
                     const NewtonSettings& s, StageTimer& timer) {
  NewtonOutcome out;
  Eigen::VectorXd r;
  std::string why;
  const std::optional<double> r0 = timer.time("residual", [&] { return residual_norm(system, d, r, why); });
  if (!r0) {
    out.failure = "the start state is not admissible: " + why;
    return out;
  }
  out.history.push_back({0, *r0, 1.0, 0.0});
  const auto log = [&](const NewtonIterate& it) {
    if (s.log)
      *s.log << fmt::format("      newton {:2d}  |R| = {:.6e}  |R|/|R0| = {:.3e}  alpha = {:<6g} order = {}\n",
                            it.iteration, it.residual, *r0 > 0.0 ? it.residual / *r0 : 0.0, it.alpha,
                            it.order > 0.0 ? fmt::format("{:.2f}", it.order) : "-")
             << std::flush;
  };
  log(out.history.back());
  const auto converged = [&](double norm) { return norm <= s.tolerance * *r0 || norm <= s.absolute_tolerance; };
  if (converged(*r0)) {
    out.converged = true;
    return out;
  }
  double norm = *r0;
  for (int it = 1; it <= s.max_iterations; ++it) {
    const bool slow = out.history.size() >= 2 && norm > 0.1 * out.history[out.history.size() - 2].residual;
    if (!s.reuse_tangent || !solver.factorized() || slow) {
      timer.time("assembly", [&] { system.tangent(d, k); });
      try {
        timer.time("factorisation", [&] {
          if (!solver.analyzed()) solver.analyze(k);  // once: the pattern never changes
          solver.factorize(k);
        });
      } catch (const NumericalError& e) {
        out.failure = fmt::format("tangent not factorisable at iteration {} ({})", it, e.what());
        return out;
      }
      ++out.factorisations;
    }
    const Eigen::VectorXd delta = timer.time("solve", [&] { return solver.solve(-r); });
    double alpha = 1.0;
    Eigen::VectorXd trial, r_trial;
    std::optional<double> n_trial;
    // Line search on s(alpha) = delta . R(d + alpha delta), the slope of the energy along
    // delta for a potential problem (Crisfield's): s(0) < 0, and a step is accepted when
    // |s(alpha)| <= 0.8 |s(0)|. The residual norm is a poor guide in bending (axial
    // residuals of a rotated linear predictor dominate it); the energy slope is not. An
    // inadmissible trial (J <= 0) halves alpha; otherwise alpha moves by the secant through
    // s(0) and s(alpha), kept within [alpha / 10, 1].
    const double s0 = delta.dot(r);
    for (int search = 0;; ++search) {
      trial = d + alpha * delta;
      n_trial = timer.time("residual", [&] { return residual_norm(system, trial, r_trial, why); });
      if (!s.line_search) break;
      const bool last = search == s.max_line_search_steps;
      if (!n_trial) {
        if (last) {
          out.failure = fmt::format("every line-search step is inadmissible at iteration {}: {}", it, why);
          return out;
        }
        alpha *= 0.5;
        continue;
      }
      const double sa = delta.dot(r_trial);
      if (!(s0 < 0.0) || std::abs(sa) <= 0.8 * std::abs(s0) || last) break;
      const double secant = alpha * s0 / (s0 - sa);
      alpha = std::isfinite(secant) ? std::clamp(secant, 0.1 * alpha, 1.0) : 0.5 * alpha;
    }
    if (!n_trial) {
      out.failure = fmt::format("iteration {}: {}", it, why);
      return out;
    }
    d = std::move(trial);
    r = std::move(r_trial);
    norm = *n_trial;
    out.history.push_back({it, norm, alpha, 0.0});
    out.history.back().order = observed_order(out.history);
    log(out.history.back());
    if (!std::isfinite(norm)) {
      out.failure = fmt::format("non-finite residual at iteration {}", it);
      return out;
    }
    if (converged(norm)) {
      out.converged = true;
      return out;
    }
    // Stagnation at round-off: far below the start (1e-8 |R_0|) and no longer falling (not
    // halved by the last iteration). More iterations, or a cut-back, would not lower it.
    const double before = out.history[out.history.size() - 2].residual;
    if (norm <= 1e-8 * *r0 && norm > 0.5 * before) {
      out.converged = out.stagnated = true;
      if (s.log) *s.log << fmt::format("      newton: stagnated at |R|/|R0| = {:.3e} (round-off): accepted\n", norm / *r0);
      return out;
    }
  }
  out.failure = fmt::format("no convergence in {} iterations (|R|/|R0| = {:.3e})", s.max_iterations, norm / *r0);
  return out;
}

template <int dim>
StaticSolution solve_static(
    TotalLagrangian<dim>& model, std::type_identity_t<std::span<const Point<dim>>> nodes,
    const NewtonSettings& s, StageTimer& timer,
    const std::function<void(const LoadStepRecord&, const Eigen::VectorXd&)>& on_step) {
  std::vector<double> targets = s.load_factors;
  if (targets.empty())
    for (int i = 1; i <= s.load_steps; ++i) targets.push_back(static_cast<double>(i) / s.load_steps);
  for (std::size_t i = 0; i < targets.size(); ++i)
    if (!(targets[i] > (i ? targets[i - 1] : 0.0)))
      throw InputError(fmt::format("load factors must increase from above 0, got {} after {}", targets[i],
                                   i ? targets[i - 1] : 0.0));

  StaticSolution out;
  const std::unique_ptr<LinearSolver> solver = make_linear_solver(
      s.solver, {"tangent stiffness", model.symmetric(), dim, nodes, s.nearly_symmetric}, model.dofs());
  SparseMatrix k = model.zero_matrix();

  const Eigen::VectorXd f_unit = model.external_force({});
  Eigen::VectorXd d = Eigen::VectorXd::Zero(model.dofs());
  // The absolute tolerance, unless given: tolerance times the residual of the whole load on
  // the undeformed body (the external force and the prescribed displacements' terms). One
  // scale for every step: a cut-back, which shrinks |R_0|, does not tighten it below
  // round-off.
  NewtonSettings ns = s;
  if (!(ns.absolute_tolerance > 0.0))
    ns.absolute_tolerance = s.tolerance * (model.internal_force(d) + model.boundary_force(d, {1.0, 0.0}) - f_unit).norm();
  double done = 0.0;  // last converged load factor
  for (double target : targets) {
    double factor = target;
    int cutbacks = 0;
    for (;;) {
      if (s.log) *s.log << fmt::format("    load factor {:.6g}\n", factor);
      const NonlinearSystem system{
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return model.internal_force(x) + model.boundary_force(x, {factor, 0.0}) - factor * f_unit;
          },
          [&](const Eigen::VectorXd& x, SparseMatrix& t) { model.tangent(x, {factor, 0.0}, t); }};
      Eigen::VectorXd trial = d;
      const NewtonOutcome o = newton(system, trial, k, *solver, ns, timer);
      if (o.converged) {
        d = std::move(trial);
        model.commit(d);
        out.steps.push_back({factor, cutbacks, o.history});
        if (on_step) on_step(out.steps.back(), d);
        done = factor;
        if (factor == target) break;
        factor = target;  // the rest of the increment
        cutbacks = 0;
        continue;
      }
      if (++cutbacks > s.max_cutbacks)
        throw NumericalError(fmt::format(
            "Newton gave up at load factor {:.6g} (last converged {:.6g}) after {} cut-backs: {}. Use more "
            "load steps ([newton] load_steps or load_factors) or check the loads and boundary conditions.",
            factor, done, s.max_cutbacks, o.failure));
      if (s.log) *s.log << fmt::format("    cut back: {}\n", o.failure);
      factor = done + 0.5 * (factor - done);
    }
  }
  out.coefficients = std::move(d);
  out.solver = report(*solver);
  return out;
}

template StaticSolution solve_static(
    TotalLagrangian<2>&, std::span<const Point<2>>, const NewtonSettings&, StageTimer&,
    const std::function<void(const LoadStepRecord&, const Eigen::VectorXd&)>&);
template StaticSolution solve_static(
    TotalLagrangian<3>&, std::span<const Point<3>>, const NewtonSettings&, StageTimer&,
    const std::function<void(const LoadStepRecord&, const Eigen::VectorXd&)>&);

}  // namespace mfree

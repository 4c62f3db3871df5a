#include <catch2/catch.hpp>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/galerkin/elastodynamics.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/motion_errors.hpp"
#include "mfree/problems/axis_aligned_vibration.hpp"
#include "mfree/quadrature/gauss_cells.hpp"
#include "../test_support.hpp"

using namespace mfree;

namespace {

/// The vibration problem of SPEC section 6 on the unit square, lattice nodes of spacing h,
/// slip walls by Nitsche's method (walls = false: a free body).
struct VibrationCase {
  AxisAlignedVibration exact;
  Domain domain = Domain::rectangle(Vec2(0.0, 0.0), Vec2(1.0, 1.0));
  Discretisation<2> disc;
  std::unique_ptr<TotalLagrangian<2>> model;

  VibrationCase(double amplitude, double h, bool walls, bool body_force) : exact{amplitude} {
    ElasticitySettings s;
    s.scheme = QuadratureScheme::projected;  // symmetric correction: the trial gradients are the test ones
    s.nodes.spacing = h;
    StageTimer timer;
    disc = discretise(domain, s, timer);
    SolidProblem<2> p;
    p.material = exact.material();
    p.density = exact.density;
    p.spacing = h;
    if (walls) {
      const auto zero = [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); };
      p.conditions = {{BoundaryCondition<2>::Type::slip, select_part(domain, "bottom"), zero, "bottom"},
                      {BoundaryCondition<2>::Type::slip, select_part(domain, "top"), zero, "top"},
                      {BoundaryCondition<2>::Type::slip, select_part(domain, "left"), zero, "left"},
                      {BoundaryCondition<2>::Type::slip, select_part(domain, "right"), zero, "right"}};
    }
    if (body_force)
      p.body_force = [e = exact](const Vec2& x, double t) { return e.density * e.body_force(x, t); };
    model = std::make_unique<TotalLagrangian<2>>(p, domain, disc.node_count(), disc.quadrature, nullptr,
                                                 disc.boundary, disc.at_boundary);
  }

  [[nodiscard]] Eigen::VectorXd initial_velocity() const {
    return project_velocity(*model, disc.nodes, [&](const Vec2& x) { return exact.velocity(x, 0.0); }, {});
  }

  /// RMS errors at the times given as fractions of the period.
  std::vector<MotionErrors> errors_at(const std::vector<double>& fractions, DynamicsSettings s) const {
    const MotionErrorSampler<2> sampler(
        *disc.trial, gauss_cell_rule(domain, 0.5 * disc.nodes[1].x(), 5),
        [m = Material(exact.material())](const Vec2&) -> const Material& { return m; });
    const ExactMotion<2> motion{[&](const Vec2& x, double t) { return exact.displacement(x, t); },
                                [&](const Vec2& x, double t) { return exact.velocity(x, t); },
                                [&](const Vec2& x, double t) { return exact.cauchy_stress(x, t); }};
    std::vector<MotionErrors> out;
    std::size_t next = 0;
    s.end_time = fractions.back() * exact.period();
    StageTimer timer;
    (void)integrate_dynamics(*model, disc.nodes, Eigen::VectorXd::Zero(model->dofs()), initial_velocity(), s, timer,
                             [&](const DynamicState& st) {
                               if (next < fractions.size() && st.time >= fractions[next] * exact.period() * (1 - 1e-12)) {
                                 out.push_back(sampler(st.d, st.v, st.time, motion));
                                 ++next;
                               }
                             });
    return out;
  }
};

}  // namespace

TEST_CASE("vibration, central differences: displacement converges at rate >= 1.8 (A = 0.05)",
          "[galerkin][dynamics][study]") {
  DynamicsSettings s;
  s.scheme = TimeScheme::central_difference;
  s.time_step = 2.5e-5;  // below the stability limits of both levels (about 1e-4 s and 5e-5 s)
  std::vector<std::vector<MotionErrors>> levels;
  for (double h : {1.0 / 16, 1.0 / 32}) levels.push_back(VibrationCase(0.05, h, true, true).errors_at({0.25, 0.75}, s));
  for (std::size_t k = 0; k < 2; ++k) {
    const double rate = std::log(levels[0][k].displacement / levels[1][k].displacement) / std::log(2.0);
    INFO("t = " << levels[1][k].time << ": RMS displacement errors " << levels[0][k].displacement << " -> "
                << levels[1][k].displacement << ", rate " << rate);
    CHECK(rate >= 1.8);
  }
}

TEST_CASE("free vibration, Newmark: energy error falls with dt^2, below 5e-3 over 10 periods",
          "[galerkin][dynamics][study]") {
  // A free Neo-Hookean body (no walls, no body force) set moving by the vibration's initial
  // velocity: nothing does work on it, so kinetic + strain energy must stay constant. The
  // average-acceleration rule conserves it exactly for linear problems only; for this large
  // motion its energy error must fall with dt^2.
  const VibrationCase c(0.05, 1.0 / 8, false, false);
  std::vector<double> drifts;
  for (int steps_per_period : {50, 100}) {
    DynamicsSettings s;
    s.scheme = TimeScheme::newmark;
    s.end_time = 10 * c.exact.period();
    s.time_step = c.exact.period() / steps_per_period;
    s.newton.tolerance = 1e-12;
    StageTimer timer;
    const DynamicsResult r =
        integrate_dynamics(*c.model, c.disc.nodes, Eigen::VectorXd::Zero(c.model->dofs()), c.initial_velocity(), s, timer);
    double scale = 0.0, drift = 0.0, most_strain = 0.0;
    for (const EnergyRecord& e : r.energy) {
      scale = std::max(scale, e.kinetic + e.strain);
      drift = std::max(drift, std::abs(e.total() - r.energy.front().total()));
      CHECK(e.external_work == 0.0);
    }
    for (const EnergyRecord& e : r.energy) most_strain = std::max(most_strain, e.strain / scale);
    CHECK(most_strain > 0.5);  // a large motion: strain energy takes most of the total at times
    drifts.push_back(drift / scale);
  }
  INFO("largest energy drift over 10 periods: " << drifts[0] << " (T/50), " << drifts[1] << " (T/100)");
  CHECK(drifts[1] <= 5e-3);
  CHECK(std::log2(drifts[0] / drifts[1]) >= 1.6);
}

TEST_CASE("central differences refuse a time step above the stability limit", "[galerkin][dynamics]") {
  const VibrationCase c(0.05, 1.0 / 8, true, true);
  DynamicsSettings s;
  s.scheme = TimeScheme::central_difference;
  s.end_time = 1e-3;
  const Eigen::VectorXd lumped = c.model->lumped_mass(c.disc.nodes);
  CHECK((lumped.array() > 0.0).all());
  const double limit = critical_time_step(*c.model, lumped, Eigen::VectorXd::Zero(c.model->dofs()));
  // The limit is that of the dilatational wave on about the nodal spacing: h / c_d up to a
  // factor of order one (RK supports reach 2 h; the walls' penalty stiffens the edges).
  const double hc = (1.0 / 8) / wave_speed(c.exact.material(), c.exact.density);
  INFO("stability limit " << limit << " s, h / c_d = " << hc << " s");
  CHECK(limit > 0.1 * hc);
  CHECK(limit < 2.0 * hc);
  s.time_step = 1.01 * limit;
  StageTimer timer;
  const std::string m = testing::message_of<InputError>([&] {
    (void)integrate_dynamics(*c.model, c.disc.nodes, Eigen::VectorXd::Zero(c.model->dofs()), c.initial_velocity(), s, timer);
  });
  CHECK_THAT(m, Catch::Contains("above the stability limit"));
  // Just below it the run is stable: the energy stays bounded.
  s.time_step = 0.99 * limit;
  s.end_time = 200 * limit;
  const DynamicsResult r =
      integrate_dynamics(*c.model, c.disc.nodes, Eigen::VectorXd::Zero(c.model->dofs()), c.initial_velocity(), s, timer);
  CHECK(std::abs(r.energy.back().total() - r.energy.front().total()) <= 1e-3 * r.energy.front().kinetic);
}

TEST_CASE("energy_every = 0 records no energy and leaves the motion bit for bit as it is", "[galerkin][dynamics]") {
  const VibrationCase c(0.05, 1.0 / 8, true, true);
  for (TimeScheme scheme : {TimeScheme::central_difference, TimeScheme::newmark}) {
    CAPTURE(to_string(scheme));
    DynamicsSettings s;
    s.scheme = scheme;
    s.end_time = 0.05 * c.exact.period();
    s.time_step = c.exact.period() / 400;
    const auto run = [&](int energy_every, StageTimer& timer) {
      s.energy_every = energy_every;
      return integrate_dynamics(*c.model, c.disc.nodes, Eigen::VectorXd::Zero(c.model->dofs()), c.initial_velocity(),
                                s, timer);
    };
    StageTimer with, without;
    const DynamicsResult recorded = run(1, with), silent = run(0, without);
    CHECK(recorded.energy.size() == static_cast<std::size_t>(recorded.steps) + 1);
    CHECK(silent.energy.empty());
    const auto calls = [](const StageTimer& t, const std::string& stage) {
      for (std::size_t i = 0; i < t.stages().size(); ++i)
        if (t.stages()[i].first == stage) return t.calls()[i];
      return 0L;
    };
    CHECK(calls(with, "energy") == recorded.steps + 1);
    CHECK(calls(without, "energy") == 0);
    // Newmark evaluates the applied forces at the new state for the work term alone.
    CHECK(calls(without, "residual") ==
          calls(with, "residual") - (scheme == TimeScheme::newmark ? recorded.steps : 0));
    CHECK((silent.d - recorded.d).norm() == 0.0);
    CHECK((silent.v - recorded.v).norm() == 0.0);
  }
}

TEST_CASE("J2 body in free motion: kinetic + stored + dissipated energy stays constant, both schemes",
          "[galerkin][dynamics][plasticity]") {
  // A free unit square of J2 material (no walls, no loads) set moving by a shearing velocity
  // v0 = (0, 2 cos(2 pi x)) [m/s] (no momentum, no angular momentum), strains well beyond the
  // yield strain: the motion is
  // damped by plastic work, which must account for the kinetic energy lost. The history is
  // committed after every step (a history kept from one iteration to the next would not
  // balance).
  const Domain domain = Domain::rectangle(Vec2(0.0, 0.0), Vec2(1.0, 1.0));
  ElasticitySettings es;
  es.scheme = QuadratureScheme::projected;
  es.nodes.spacing = 1.0 / 8;
  StageTimer timer;
  const Discretisation<2> disc = discretise(domain, es, timer);
  J2Plasticity law;
  law.lame = lame_constants(1000.0, 0.3);
  law.yield_stress = 10.0;
  law.isotropic_modulus = 50.0;
  SolidProblem<2> p;
  p.material = law;
  p.density = 1.0;
  p.spacing = es.nodes.spacing;
  TotalLagrangian<2> model(p, domain, disc.node_count(), disc.quadrature, nullptr, disc.boundary,
                           disc.at_boundary);
  const Eigen::VectorXd v0 = project_velocity(
      model, disc.nodes, [](const Vec2& x) { return Vec2(0.0, 2.0 * std::cos(2.0 * M_PI * x.x())); }, {});
  for (TimeScheme scheme : {TimeScheme::central_difference, TimeScheme::newmark}) {
    CAPTURE(to_string(scheme));
    model.set_history({std::vector<MaterialState<2>>(disc.quadrature.size()), {}});  // a fresh body
    DynamicsSettings s;
    s.scheme = scheme;
    s.end_time = 0.15;  // about one and a half periods of the lowest shear mode
    s.time_step = 2.5e-4;
    const DynamicsResult r = integrate_dynamics(model, disc.nodes, Eigen::VectorXd::Zero(model.dofs()), v0, s, timer);
    const EnergyRecord &first = r.energy.front(), &last = r.energy.back();
    double drift = 0.0;
    for (const EnergyRecord& e : r.energy) drift = std::max(drift, std::abs(e.total() - first.total()));
    INFO("kinetic " << first.kinetic << " -> " << last.kinetic << ", dissipated " << last.dissipated
                    << ", largest drift " << drift);
    CHECK(first.dissipated == 0.0);
    CHECK(last.dissipated > 0.2 * first.kinetic);  // plastic work took a good part of the energy
    CHECK(drift <= 5e-3 * first.kinetic);
  }
}

TEST_CASE("Newmark with PETSc CG + GAMG for the effective tangent and the mass follows the direct solves",
          "[galerkin][dynamics][krylov]") {
  const VibrationCase c(0.05, 1.0 / 8, false, false);
  const auto run = [&](const SolverSettings& solver) {
    DynamicsSettings s;
    s.scheme = TimeScheme::newmark;
    s.end_time = c.exact.period();
    s.time_step = c.exact.period() / 50;
    s.newton.tolerance = 1e-12;
    s.newton.solver = solver;
    StageTimer timer;
    return integrate_dynamics(*c.model, c.disc.nodes, Eigen::VectorXd::Zero(c.model->dofs()), c.initial_velocity(), s,
                              timer);
  };
  SolverSettings krylov;
  krylov.kind = SolverKind::cg;
  krylov.tolerance = 1e-12;
  const DynamicsResult direct = run({}), iterative = run(krylov);
  REQUIRE(direct.solver);
  REQUIRE(iterative.solver);
  INFO(iterative.solver->text());
  CHECK(direct.solver->kind == SolverKind::cholmod);
  CHECK_THAT(iterative.solver->method, Catch::StartsWith("cg + gamg"));
  CHECK((iterative.d - direct.d).norm() <= 1e-8 * direct.d.norm());
  CHECK(iterative.newton_iterations == direct.newton_iterations);
}

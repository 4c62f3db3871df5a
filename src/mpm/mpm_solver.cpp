#include "mfree/mpm/mpm_solver.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string_view>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/core/step_count.hpp"

namespace mfree {

const NameTable<UpdateScheme>& update_names() {
  static const NameTable<UpdateScheme> table{
      {"usf", UpdateScheme::usf},     {"usl", UpdateScheme::usl},       {"szs", UpdateScheme::szs},
      {"usavg", UpdateScheme::usavg}, {"verlet", UpdateScheme::verlet}};
  return table;
}

std::string_view to_string(UpdateScheme s) { return update_names().name(s); }

namespace {

/// Sums per body over the particles in one contiguous range per thread (parallel_ranges):
/// one row per thread, the rows at least a cache line (8 doubles) apart, as every particle
/// adds to its thread's row; added up in thread order (reproducible).
class BodySums {
 public:
  explicit BodySums(int bodies)
      : bodies_(static_cast<std::size_t>(bodies)),
        row_((bodies_ + 7) / 8 * 8 + 8),
        sums_(static_cast<std::size_t>(thread_count()) * row_, 0.0) {}
  double* row(int thread) { return sums_.data() + static_cast<std::size_t>(thread) * row_; }
  void add_to(std::vector<double>& total) const {
    for (std::size_t t = 0; t < sums_.size() / row_; ++t)
      for (std::size_t b = 0; b < bodies_; ++b) total[b] += sums_[t * row_ + b];
  }

 private:
  std::size_t bodies_, row_;
  std::vector<double> sums_;
};

/// Runs f; a NumericalError from it (which knows where) gets the time appended (the solver
/// knows when).
template <class F>
void at_time(double t, F&& f) {
  try {
    f();
  } catch (const NumericalError& e) {
    throw NumericalError(fmt::format("{} at t = {:.6g} s", e.what(), t));
  }
}

const MPMSettings& checked(const MPMSettings& s, const MPMProblem& p) {
  if (p.materials.empty()) throw InputError("MPM: the problem has no material");
  for (const MPMMaterial& m : p.materials)
    if (!(m.density > 0.0))
      throw InputError(fmt::format("MPM: the density of material '{}' must be positive (got {})", m.name, m.density));
  if (!(s.damping >= 0.0)) throw InputError(fmt::format("MPM: damping must be zero or positive (got {})", s.damping));
  if (!(s.end_time > 0.0)) throw InputError(fmt::format("MPM: end_time must be positive (got {})", s.end_time));
  if (s.cells < 1) throw InputError(fmt::format("MPM: needs at least one cell (got {})", s.cells));
  if (is_bspline(s.method) && (s.degree < 2 || s.degree > 3))
    throw InputError(fmt::format("MPM: B-spline degree must be 2 or 3 (got {})", s.degree));
  if (s.deformation_terms < 1 || s.deformation_terms > 10)
    throw InputError(fmt::format("MPM: deformation_terms (kmax) must lie in [1, 10] (got {})", s.deformation_terms));
  if (!(s.courant > 0.0)) throw InputError(fmt::format("MPM: the Courant factor must be positive (got {})", s.courant));
  if (s.update == UpdateScheme::verlet && s.damping > 0.0)
    throw InputError("MPM: the verlet update takes no damping; use usf, usl, szs or usavg with damping");
  if (s.method == MPMMethod::bspline_mls && !(s.mls_support >= 1.0))
    throw InputError(fmt::format("MPM: mls_support must be at least one cell (got {})", s.mls_support));
  if (!(s.mass_filter >= 0.0 && s.mass_filter <= 1.0))
    throw InputError(fmt::format("MPM: mass_filter must lie in [0, 1] (got {})", s.mass_filter));
  if (s.mass_filter > 0.0 && s.mapping != GridMapping::pseudo_inverse)
    throw InputError(
        "MPM: mass_filter filters the pseudo-inverse mapping's mass matrix; the lumped mapping has none");
  return s;
}

/// dF = exp(dt L) by its series to kmax terms, sum_{k <= kmax} (dt L)^k / k! (seed 002,
/// "Incremental Deformation Gradient"). Column by column: Eigen adds whole 2 x 2 matrices as
/// one 32-byte packet but forms products by 16-byte columns, and each such mix stalls a
/// store-to-load forward (two 16-byte stores read back as one 32-byte load).
Mat2 exp_series(const Mat2& L, double dt, int kmax) {
  const Vec2 a0 = dt * L.col(0), a1 = dt * L.col(1);
  Vec2 t0(1.0, 0.0), t1(0.0, 1.0);  // the term (dt L)^k / k!
  Vec2 s0 = t0, s1 = t1;             // the sum
  for (int k = 1; k <= kmax; ++k) {
    const double r = 1.0 / k;  // off the chain of dependent products
    const Vec2 n0 = (t0 * a0.x() + t1 * a0.y()) * r, n1 = (t0 * a1.x() + t1 * a1.y()) * r;
    t0 = n0;
    t1 = n1;
    s0 += t0;
    s1 += t1;
  }
  Mat2 dF;
  dF << s0, s1;
  return dF;
}

/// The largest node distance (per axis) of two nodes one particle reaches: the degree for the
/// point-evaluated bases, the degree + 1 for the averaged B-splines (a domain within two
/// cells), 3 for the averaged hats of the other methods with domains (a domain up to two
/// cells wide).
int mass_matrix_radius(MPMMethod m, int degree) {
  if (m == MPMMethod::bspline_cpgimp) return degree + 1;
  if (uses_domains(m)) return 3;
  return m == MPMMethod::classic ? 1 : degree;
}

/// The stable time step with the consistent mass of the pseudo-inverse mapping, as a fraction
/// of the lumped mass's: sqrt(M(pi)) with M(theta) the 1D mass symbol of the grid functions
/// under particle quadrature (2 or 3 particles per cell: hats and their averages 0.50-0.54,
/// quadratic B-splines 0.36-0.38, cubic 0.23), at the highest wave number where the
/// stiffness symbol peaks; rounded down.
double consistent_mass_courant(MPMMethod m, int degree) {
  if (!is_bspline(m)) return 0.5;
  return degree == 2 ? 0.35 : 0.22;
}

/// eq. (34): L_p = sum_i (v_i - v_p) G_ip^T, relative to v_p; nodes without mass carry no
/// velocity and are left out. Column by column, as in exp_series().
Mat2 velocity_gradient(const WeightTable& weights, Index p, const Vec2& vp, const double* mass, const Vec2* velocity,
                       double floor) {
  Mat2 L = Mat2::Zero();
  weights.for_each(p, [&](Index i, double, const Vec2& G) {
    if (!(std::abs(mass[i]) > floor)) return;
    const Vec2 dv = velocity[i] - vp;
    L.col(0) += dv * G.x();
    L.col(1) += dv * G.y();
  });
  return L;
}

/// The grid of a problem and its settings (its constructor checks the memory of its nodes).
Grid grid_for(const MPMProblem& p, const MPMSettings& s) {
  return {p.box, s.cells, is_bspline(s.method) ? s.degree : 1, grid_padding(s.method)};
}

/// Refuses sizes that overflow or vanish in double precision: the cell size h, the particle
/// volumes (h / n)^2 and masses rho0 (h / n)^2 for n = 1 to 5 particles per side, and the
/// materials' wave speeds.
void check_scales(const MPMProblem& p, double h) {
  const double smallest = (h / 5.0) * (h / 5.0), largest = h * h;
  if (!(std::isfinite(largest) && smallest >= std::numeric_limits<double>::min()))
    throw InputError(fmt::format(
        "MPM: the grid box {:.4g} x {:.4g} m with cells of h = {:.4g} m gives particle volumes (h / n)^2 of "
        "{:.4g} to {:.4g} m^2, outside what a double holds; give the box in units that make its size of "
        "order one",
        p.box.size().x(), p.box.size().y(), h, smallest, largest));
  for (const MPMMaterial& m : p.materials) {
    const double c = wave_speed(m.law, m.density);
    if (!(std::isfinite(m.density * largest) && m.density * smallest >= std::numeric_limits<double>::min()))
      throw InputError(
          fmt::format("MPM: material '{}': density {:.4g} kg/m^3 gives particle masses of {:.4g} to "
                      "{:.4g} kg, outside what a double holds; check its units",
                      m.name, m.density, m.density * smallest, m.density * largest));
    if (!(std::isfinite(c) && c > 0.0 && std::isfinite(h / c) && h / c > 0.0))
      throw InputError(
          fmt::format("MPM: material '{}': its wave speed {:.4g} m/s (density {:.4g} kg/m^3) gives no "
                      "time step h / c with h = {:.4g} m; check its modulus and density",
                      m.name, c, m.density, h));
  }
}

/// The time step of a run (seed 002, "Theory: MPM Time Step"): dt = C h / c with C < 1, or a
/// fixed step, whichever is smaller; c the fastest of the materials' wave speeds; then
/// shortened so that a whole number of steps reaches end_time. InputError for a Courant
/// number above 1 (unless allowed) and for more steps than a run may take.
struct TimeStepPlan {
  double h_over_c = 0.0;  ///< the Courant limit [s] (the consistent mass's fraction of h / c with it)
  double dt = 0.0;        ///< [s]
  int steps = 0;
};

TimeStepPlan plan_time_step(const MPMProblem& p, const MPMSettings& s, double h) {
  check_scales(p, h);
  double c = 0.0;
  for (const MPMMaterial& m : p.materials) c = std::max(c, wave_speed(m.law, m.density));
  TimeStepPlan plan;
  plan.h_over_c = h / c;
  std::string limit = "h / c";
  if (s.mapping == GridMapping::pseudo_inverse) {
    const double factor = consistent_mass_courant(s.method, s.degree);
    plan.h_over_c *= factor;
    limit = fmt::format("{} h / c (the pseudo-inverse mapping's consistent mass)", factor);
  }
  const bool allowed = s.allow_unstable_time_step;
  if (s.courant > 1.0 && !allowed)
    throw InputError(
        fmt::format("MPM: Courant factor {} is above 1: the explicit step would exceed {} = {:.4g} s (h = "
                    "{:.4g}, c = {:.4g} m/s); use courant <= 1 or set allow_unstable_time_step = true",
                    s.courant, limit, plan.h_over_c, h, c));
  if (s.time_step && *s.time_step > plan.h_over_c && !allowed)
    throw InputError(
        fmt::format("MPM: time_step {:.4g} s is above the Courant limit {} = {:.4g} s (h = {:.4g}, c = "
                    "{:.4g} m/s, Courant number {:.3g}); use a smaller time_step or set "
                    "allow_unstable_time_step = true",
                    *s.time_step, limit, plan.h_over_c, h, c, *s.time_step / plan.h_over_c));
  double dt = s.courant * plan.h_over_c;
  if (s.time_step) dt = std::min(dt, *s.time_step);
  plan.steps = step_count(s.end_time, dt, "MPM");
  plan.dt = s.end_time / plan.steps;
  return plan;
}

/// What to change for a particle of initial velocity v [m/s] that crosses |v| dt / h > 1 cells
/// per step: a step that keeps it within one, or (when such steps could not reach end_time in
/// max_time_steps) a lower velocity.
std::string crossing_advice(double speed, double h, double end_time) {
  const double step = h / speed;
  if (!(end_time / step <= max_time_steps))
    return fmt::format(
        "a step short enough, h / |v| = {:.3g} s, would take {:.3g} steps to end_time {:.4g} s: lower the "
        "velocity",
        step, end_time / step, end_time);
  return fmt::format("use time_step <= h / |v| = {:.3g} s or lower the velocity", step);
}

/// InputError (at `where`) for an initial velocity v at X whose kinetic energy overflows or
/// that crosses more than a cell per step, |v| dt > h (the Courant condition of the velocity:
/// the grid transfers assume a particle stays near the nodes it weighs); `allowed` (stability
/// studies) lets the crossing through.
void check_initial_velocity(const std::string& where, const Vec2& X, const Vec2& v, double dt, double h,
                            double end_time, bool allowed) {
  const double speed = v.stableNorm();  // no overflow of |v|^2 on the way
  if (speed * dt > h && !allowed)
    throw InputError(fmt::format(
        "{}: the initial velocity at X = ({:.6g}, {:.6g}) is ({:.4g}, {:.4g}) m/s: a particle would cross "
        "|v| dt / h = {:.3g} cells in one step (dt = {:.4g} s, h = {:.4g} m), more than the one cell the "
        "grid transfers follow; {}",
        where, X.x(), X.y(), v.x(), v.y(), speed * dt / h, dt, h, crossing_advice(speed, h, end_time)));
  if (!std::isfinite(v.squaredNorm()))
    throw InputError(
        fmt::format("{}: the initial velocity at X = ({:.6g}, {:.6g}) is ({:.4g}, {:.4g}) m/s: its "
                    "kinetic energy 1/2 m |v|^2 overflows; lower the velocity",
                    where, X.x(), X.y(), v.x(), v.y()));
}

/// The particles of the problem's bodies, after every check that costs no particle: the
/// settings, the grid's memory, the time step (Courant number, step count, sizes, wave
/// speeds), the particles' count and memory (seed_bodies); each initial velocity as it is
/// seeded.
Particles seeded_particles(const MPMProblem& p, const MPMSettings& s) {
  checked(s, p);
  const double h = grid_for(p, s).spacing();
  const TimeStepPlan plan = plan_time_step(p, s, h);
  return seed_bodies(p.bodies, p.materials, p.box, h, s.particles_per_side, uses_domains(s.method),
                     [&](const MPMBody& body, const Vec2& X, const Vec2& v) {
                       check_initial_velocity(fmt::format("{}: body '{}'", body.velocity_key(), body.name), X,
                                              v, plan.dt, h, s.end_time, s.allow_unstable_time_step);
                     });
}

/// Runs f for particle p; a NumericalError from it (a grid function or a domain that fails
/// there) gets the particle's index and reference position.
template <class F>
void for_particle(const Particles& P, Index p, F&& f) {
  try {
    f();
  } catch (const NumericalError& e) {
    std::string_view what = e.what();
    if (what.starts_with("MPM: ")) what.remove_prefix(5);
    throw NumericalError(fmt::format("MPM: {}: {}", particle_name(P, p), what));
  }
}

/// A number as messages print it: "not finite" for an infinity or a NaN.
std::string finite_text(double x) {
  return std::isfinite(x) ? fmt::format("{:.4g}", x) : std::string("not finite");
}

/// "(x, y)" of a finite vector, "not finite" otherwise (messages never print a NaN).
std::string vector_text(const Vec2& v) {
  return v.allFinite() ? fmt::format("({:.4g}, {:.4g})", v.x(), v.y()) : std::string("not finite");
}

}  // namespace

MPMSolver::MPMSolver(MPMProblem problem, MPMSettings settings)
    : MPMSolver(problem, settings, seeded_particles(problem, settings)) {}

MPMSolver::MPMSolver(MPMProblem problem, MPMSettings settings, Particles particles)
    : problem_(std::move(problem)),
      settings_(checked(settings, problem_)),
      grid_(grid_for(problem_, settings_)),
      basis_(settings_.method, grid_),
      particles_(std::move(particles)) {
  const TimeStepPlan plan = plan_time_step(problem_, settings_, grid_.spacing());
  h_over_c_ = plan.h_over_c;
  dt_ = plan.dt;
  steps_ = plan.steps;
  if (uses_domains(settings_.method) && particles_.half_size.size() != particles_.mass.size())
    throw InputError(fmt::format("MPM: method {} needs the particle domains", to_string(settings_.method)));
  if (particles_.size() == 0) throw InputError("MPM: the problem has no particles");
  check_initial_state();
  if (settings_.method == MPMMethod::cpdi2 && particles_.corners.empty()) {
    particles_.corners.resize(particles_.mass.size());
    for (Index p = 0; p < particles_.size(); ++p)
      particles_.corners[p] = parallelogram_corners(particles_.position[p], particles_.deformation[p], particles_.half_size[p]);
  }
  check_corners(particles_);
  if (particles_.material.size() != particles_.mass.size() || particles_.body.size() != particles_.mass.size())
    throw InputError("MPM: every particle needs a body and a material");
  particles_.state.resize(particles_.mass.size());  // virgin states where none were given
  particles_.stress_zz.resize(particles_.mass.size(), 0.0);
  for (Index p = 0; p < particles_.size(); ++p) {
    if (particles_.material[p] < 0 || particles_.material[p] >= static_cast<int>(problem_.materials.size()))
      throw InputError(fmt::format("MPM: particle {} has material {}, not one of the problem's {}", p,
                                   particles_.material[p], problem_.materials.size()));
    bodies_ = std::max(bodies_, particles_.body[p] + 1);
    const Material& law = problem_.materials[particles_.material[p]].law;
    const MaterialUpdate<2> u = update(law, particles_.deformation[p], particles_.state[p], false);
    particles_.stress[p] = cauchy_stress(law, u.stress, particles_.deformation[p]);
    particles_.stress_zz[p] = u.stress_zz;
    if (!particles_.stress[p].allFinite())
      throw InputError(
          fmt::format("MPM: {} starts with a stress that is not finite (J = det F = {:.4g}): the "
                      "initial state is out of the material's range",
                      particle_name(particles_, p), particles_.deformation[p].determinant()));
  }
  external_work_.assign(static_cast<std::size_t>(bodies_), 0.0);
  walls_ = grid_.wall_mask(settings_.walls);
  for (double m : particles_.mass) particle_mass_ += m;
  body_.assign(particles_.mass.size(), Vec2::Zero());
  if (settings_.method == MPMMethod::bspline_mls)
    mls_ = std::make_unique<MLSReconstruction>(grid_, basis_, settings_.mls_basis, settings_.mls_support);
  if (settings_.mapping == GridMapping::pseudo_inverse)
    mass_matrix_ = std::make_unique<GridMassMatrix>(
        grid_, mass_matrix_radius(settings_.method, settings_.degree), settings_.mass_filter);
}

void MPMSolver::check_initial_state() const {
  const Particles& P = particles_;
  const std::size_t n = P.mass.size();
  for (const std::size_t size : {P.volume0.size(), P.volume.size(), P.reference.size(), P.position.size(),
                                 P.velocity.size(), P.deformation.size(), P.stress.size()})
    if (size != n)
      throw InputError(fmt::format("MPM: particle arrays of unequal length ({} and {})", n, size));
  for (Index p = 0; p < P.size(); ++p) {
    if (!P.reference[p].allFinite())
      throw InputError(fmt::format("MPM: particle {} has a reference position that is not finite", p));
    const auto refuse = [&](const std::string& what) {
      throw InputError(fmt::format("MPM: {} starts with {}: the initial state is not a valid one",
                                   particle_name(P, p), what));
    };
    if (!(P.mass[p] > 0.0 && std::isfinite(P.mass[p]))) refuse(fmt::format("mass {:.4g} kg", P.mass[p]));
    if (!(P.volume0[p] > 0.0 && std::isfinite(P.volume0[p])))
      refuse(fmt::format("volume {:.4g} m^2", P.volume0[p]));
    if (!P.position[p].allFinite()) refuse("a position that is not finite");
    const Mat2& F = P.deformation[p];
    if (!F.allFinite() || !(F.determinant() > 0.0))
      refuse(F.allFinite() ? fmt::format("J = det F = {:.4g} <= 0", F.determinant())
                           : std::string("a non-finite F"));
    if (!P.velocity[p].allFinite()) refuse("a velocity that is not finite");
    check_initial_velocity(fmt::format("MPM: {}", particle_name(P, p)), P.reference[p], P.velocity[p], dt_,
                           grid_.spacing(), settings_.end_time, settings_.allow_unstable_time_step);
  }
}

MPMSolver::~MPMSolver() = default;

void MPMSolver::resume(Particles particles, double time, std::vector<double> external_work) {
  if (particles.size() != particles_.size() || external_work.size() != external_work_.size())
    throw InputError(fmt::format("MPM: a saved state of {} particles and {} bodies does not fit this problem's {} and {}",
                                 particles.size(), external_work.size(), particles_.size(), external_work_.size()));
  check_corners(particles);
  particles_ = std::move(particles);
  forces_current_ = false;
  time_ = time;
  external_work_ = std::move(external_work);
}

void MPMSolver::check_corners(const Particles& P) const {
  const bool wanted = settings_.method == MPMMethod::cpdi2;
  if (wanted && P.corners.size() != P.mass.size())
    throw InputError(fmt::format("MPM: cpdi2 needs the domain corners of all {} particles (got {})", P.mass.size(),
                                 P.corners.size()));
  if (!wanted && !P.corners.empty())
    throw InputError(fmt::format("MPM: method {} does not track domain corners (only cpdi2 does)",
                                 to_string(settings_.method)));
}

void MPMSolver::step() {
  demoted_cells_ = 0;
  if (settings_.update == UpdateScheme::verlet) return verlet_step();
  const bool first = settings_.update == UpdateScheme::usf || settings_.update == UpdateScheme::usavg;
  const bool again = settings_.update == UpdateScheme::szs || settings_.update == UpdateScheme::usavg;
  const double stress_dt = settings_.update == UpdateScheme::usavg ? 0.5 * dt_ : dt_;
  timer_.time("weights", [&] { compute_weights(); });
  if (mls_) timer_.time("MLS functions", [&] { update_mls_functions(particles_.position); });
  timer_.time("particles to grid", [&] { particles_to_grid(); });
  if (first) timer_.time("stress update", [&] { update_stress(stress_dt); });
  timer_.time("grid forces", [&] { compute_grid_forces(); });
  timer_.time("grid momentum", [&] { update_grid_momentum(); });
  timer_.time("grid to particles", [&] { grid_to_particles(); });
  if (settings_.update == UpdateScheme::usl) timer_.time("stress update", [&] { update_stress(dt_); });
  if (again) {
    timer_.time("second extrapolation", [&] { extrapolate_updated_momenta(); });
    timer_.time("stress update", [&] { update_stress(stress_dt); });
  }
  time_ += dt_;
}

void MPMSolver::verlet_step() {
  // Weights, masses, accelerations and grid velocities at t^n: the last step's second kick
  // computed them.
  if (!forces_current_) {
    accelerations_at_positions();
    timer_.time("particles to grid", [&] { scatter_momentum(); });
  }
  timer_.time("grid to particles", [&] { half_kick_particles(); });
  timer_.time("weights", [&] { midpoint_weights(); });
  timer_.time("particles to grid", [&] {
    scatter_mass();
    scatter_momentum();
  });
  timer_.time("grid to particles", [&] { move_particles<false>(); });
  timer_.time("stress update", [&] { update_stress(dt_); });
  time_ += dt_;
  accelerations_at_positions();
  if (problem_.body_force) timer_.time("grid to particles", [&] { complete_drift_work(); });
  timer_.time("grid to particles", [&] { half_kick_particles(); });
  timer_.time("particles to grid", [&] { scatter_momentum(); });
  forces_current_ = true;
}

void MPMSolver::accelerations_at_positions() {
  timer_.time("weights", [&] { compute_weights(); });
  if (mls_) timer_.time("MLS functions", [&] { update_mls_functions(particles_.position); });
  timer_.time("particles to grid", [&] { scatter_mass(); });
  // MLS with the pseudo-inverse: the particles carried the mass; the forces' rho b needs the
  // reconstructed densities all the same.
  if (mls_ && !mls_transfers()) timer_.time("particles to grid", [&] { reconstruct_density(); });
  timer_.time("grid forces", [&] { compute_grid_forces(); });
  timer_.time("grid momentum", [&] { grid_accelerations(); });
}

void MPMSolver::compute_weights() {
  Particles& P = particles_;
  basis_.resize(weights_, P.size());
  at_time(time_, [&] {
    parallel_blocks(P.size(), 512, [&](Index begin, Index end) {
      for (Index p = begin; p < end; ++p) for_particle(P, p, [&] { basis_.evaluate(P, p, weights_, p); });
    });
  });
}

void MPMSolver::update_mls_functions(const std::vector<Vec2>& positions) {
  const Particles& P = particles_;
  at_time(time_, [&] { mls_->update(positions, P.deformation, P.volume0); });
  demoted_cells_ = std::max(demoted_cells_, mls_->demoted_cells());
}

void MPMSolver::particles_to_grid() {
  const Particles& P = particles_;
  if (mls_) reconstruct_density();  // eqs. (18), (19), (22), (23)
  if (mls_transfers()) {
    scatter<Eigen::Vector3d>(mls_->grid_weights(), grid_.size(), mass_momentum_, partial3_, [&](Index g) {
      const Eigen::Vector3d& at = gauss_mass_momentum_[g];
      return [&at](double S, const Vec2&) { return Eigen::Vector3d(S * at); };
    });
  } else {
    scatter<Eigen::Vector3d>(weights_, grid_.size(), mass_momentum_, partial3_, [&](Index p) {
      const double m = P.mass[p];
      const Eigen::Vector3d at(m, m * P.velocity[p].x(), m * P.velocity[p].y());
      return [at](double S, const Vec2&) { return Eigen::Vector3d(S * at); };
    });
  }
  mass_.resize(mass_momentum_.size());
  momentum_.resize(mass_momentum_.size());
  for (std::size_t i = 0; i < mass_momentum_.size(); ++i) {
    mass_[i] = mass_momentum_[i][0];
    momentum_[i] = mass_momentum_[i].tail<2>();
  }
  grid_mass_ready();
  grid_velocities(momentum_);
}

void MPMSolver::reconstruct_density() {
  const Particles& P = particles_;
  // rho_p^t: the densities of the step's start serve every reconstruction of the step.
  density_.resize(P.mass.size());
  for (Index p = 0; p < P.size(); ++p) density_[p] = P.mass[p] / P.volume[p];
  mls_->reconstruct<Eigen::Vector3d>(gauss_mass_momentum_, [&](Index p) {
    return Eigen::Vector3d(density_[p], density_[p] * P.velocity[p].x(), density_[p] * P.velocity[p].y());
  });
  // The reconstruction reproduces 1, x, y but does not conserve mass: the reconstructed
  // densities are scaled so that the Gauss points carry the mass of the particles they stand
  // for (those of the interior cells), sum_g rho_g omega_g = sum_p m_p, and every field
  // reconstructed with them this step by the same factor (rho v, rho b), after the
  // reconstruction, so that a uniform velocity stays exact.
  const double omega = mls_->gauss_weight();
  double reconstructed = 0.0, own = 0.0;
  for (Index g = 0; g < mls_->gauss_count(); ++g) reconstructed += omega * gauss_mass_momentum_[g][0];
  for (const Index p : mls_->own_particles()) own += P.mass[p];
  const double carried = particle_mass_ - own;
  density_scale_ = reconstructed > 0.0 ? carried / reconstructed : 1.0;
  reconstruction_defect_ = std::abs(reconstructed - carried) / particle_mass_;
  weigh_quadrature(
      gauss_mass_momentum_, [&](Eigen::Vector3d& at) { at *= omega * density_scale_; },
      [&](Eigen::Vector3d& at, Index p) { at *= P.mass[p] / density_[p]; });
}

template <class T, class Gauss, class Own>
void MPMSolver::weigh_quadrature(std::vector<T>& at, Gauss&& gauss, Own&& own) const {
  const Index points = mls_->gauss_count();
  for (Index g = 0; g < points; ++g) gauss(at[g]);
  const std::vector<Index>& particles = mls_->own_particles();
  for (std::size_t k = 0; k < particles.size(); ++k) own(at[points + k], particles[k]);
}

void MPMSolver::scatter_mass() {
  const Particles& P = particles_;
  if (mls_transfers()) {
    reconstruct_density();
    scatter<double>(mls_->grid_weights(), grid_.size(), mass_, partial1_, [&](Index g) {
      const double m = gauss_mass_momentum_[g][0];
      return [m](double S, const Vec2&) { return S * m; };
    });
  } else {
    scatter<double>(weights_, grid_.size(), mass_, partial1_, [&](Index p) {
      const double m = P.mass[p];
      return [m](double S, const Vec2&) { return S * m; };
    });
  }
  grid_mass_ready();
}

void MPMSolver::scatter_momentum() {
  momenta_to_grid(momentum_);
  grid_velocities(momentum_);
}

void MPMSolver::momenta_to_grid(std::vector<Vec2>& grid) {
  const Particles& P = particles_;
  if (mls_transfers()) {  // eqs. (31)-(33)
    mls_->reconstruct<Vec2>(gauss_momentum_, [&](Index p) { return Vec2(density_[p] * P.velocity[p]); });
    const double factor = mls_->gauss_weight() * density_scale_;
    weigh_quadrature(
        gauss_momentum_, [factor](Vec2& at) { at *= factor; },
        [&](Vec2& at, Index p) { at *= P.mass[p] / density_[p]; });  // m_p v_p
    scatter<Vec2>(mls_->grid_weights(), grid_.size(), grid, partial2_, [&](Index g) {
      const Vec2& at = gauss_momentum_[g];
      return [&at](double S, const Vec2&) { return Vec2(S * at); };
    });
  } else {
    scatter<Vec2>(weights_, grid_.size(), grid, partial2_, [&](Index p) {
      const Vec2 mv = P.mass[p] * P.velocity[p];
      return [mv](double S, const Vec2&) { return Vec2(S * mv); };
    });
  }
}

void MPMSolver::grid_mass_ready() {
  double grid_total = 0.0;
  for (const double m : mass_) grid_total += m;
  mass_defect_ = std::abs(grid_total - particle_mass_) / particle_mass_;
  if (mass_matrix_) mass_matrix_->assemble(weights_, particles_.mass, particles_.volume);
}

void MPMSolver::grid_velocities(const std::vector<Vec2>& momentum) {
  if (mass_matrix_) {
    at_time(time_, [&] { velocity_ = mass_matrix_->solve(momentum, mass_, walls_, mass_floor()); });
    return;
  }
  velocity_.resize(momentum.size());
  const double floor = mass_floor();
  for (std::size_t i = 0; i < momentum.size(); ++i) {
    Vec2 v = std::abs(mass_[i]) > floor ? Vec2(momentum[i] / mass_[i]) : Vec2::Zero();
    if (walls_[i] & 1) v.x() = 0.0;
    if (walls_[i] & 2) v.y() = 0.0;
    velocity_[i] = v;
  }
}

void MPMSolver::update_stress(double dt) {
  Particles& P = particles_;
  const int kmax = settings_.deformation_terms;
  const double floor = mass_floor();
  // Raw pointers: Eigen's vector stores may alias anything, so what the loop read through
  // the members would be loaded again after every store.
  const double* mass = mass_.data();
  const Vec2* velocity = velocity_.data();
  const MPMMaterial* materials = problem_.materials.data();
  const int* material = P.material.data();
  // Each block stops at its first failing particle, and parallel_blocks reports the lowest
  // block's: the failure named is that of the lowest index, in every run.
  parallel_blocks(P.size(), 512, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p) {
      const Mat2 L = velocity_gradient(weights_, p, P.velocity[p], mass, velocity, floor);
      // eq. (35), by columns as well.
      const Mat2 dF = exp_series(L, dt, kmax);
      const Vec2 f0 = dF * P.deformation[p].col(0), f1 = dF * P.deformation[p].col(1);
      const double J = f0.x() * f1.y() - f0.y() * f1.x();
      // A finite J means finite columns (an infinite or NaN entry makes it NaN or infinite).
      if (!(J > 0.0 && J < std::numeric_limits<double>::infinity()))
        throw NumericalError(deformation_failure(p, L, dF, J, dt));
      Mat2& F = P.deformation[p];
      F.col(0) = f0;
      F.col(1) = f1;
      P.volume[p] = J * P.volume0[p];  // eq. (36)
      // eqs. (37) and (41): the law's update from the particle's state, committed at once
      // (an explicit step is always accepted).
      const Material& law = materials[material[p]].law;
      const MaterialUpdate<2> u = update(law, F, P.state[p], false);
      P.state[p] = u.state;
      P.stress[p] = cauchy_stress(law, u.stress, F);
      P.stress_zz[p] = u.stress_zz;
      if (!P.stress[p].allFinite() || !std::isfinite(u.stress_zz))
        throw NumericalError(
            fmt::format("MPM: {} has a stress that is not finite at t = {:.6g} s, at J = det F = {:.4g} (F = "
                        "[[{:.4g}, {:.4g}], [{:.4g}, {:.4g}]]): the material law overflowed on a nearly "
                        "inverted or extremely stretched particle; use a smaller time step, a finer grid or "
                        "another method",
                        particle_name(P, p), time_, J, F(0, 0), F(0, 1), F(1, 0), F(1, 1)));
    }
  });
}

std::string MPMSolver::deformation_failure(Index p, const Mat2& L, const Mat2& dF, double J,
                                           double dt) const {
  const Particles& P = particles_;
  const std::string who = particle_name(P, p);
  if (!L.allFinite()) {
    // The grid velocities it reads are not finite (an overflow in the grid sums or solve): name
    // the first such node.
    std::string node;
    weights_.for_each(p, [&](Index i, double, const Vec2&) {
      if (node.empty() && !velocity_[i].allFinite())
        node = fmt::format(" (node {} at ({:.6g}, {:.6g}))", i, grid_.node(i).x(), grid_.node(i).y());
    });
    return fmt::format(
        "MPM: {} has a velocity gradient that is not finite at t = {:.6g} s: the grid velocities it reads "
        "are not finite{}, the motion blew up; use a smaller time step",
        who, time_, node);
  }
  // det F was positive: the step's own increment dF = exp(dt L) inverted (or overflowed), so
  // dt |L| is of order one: the nodes around the particle approach each other by about a cell
  // per step. Whether the particle itself moves that far says which speed to lower.
  const double h = grid_.spacing(), rate = L.norm(), speed = P.velocity[p].stableNorm();
  const std::string what =
      std::isfinite(J) ? fmt::format("J = det F = {:.4g} <= 0", J) : std::string("F overflowed");
  std::string advice;
  if (!std::isfinite(rate * dt))
    advice = "its velocity gradient overflows: the motion blew up; use a smaller time step";
  else if (speed * dt > h)
    advice = fmt::format(
        "it moves |v| dt / h = {:.3g} cells per step (|v| = {:.4g} m/s, dt = {:.4g} s, h = {:.4g} m): the "
        "time step is too long for its velocity; {}",
        speed * dt / h, speed, dt, h, crossing_advice(speed, h, settings_.end_time));
  else
    advice = fmt::format(
        "dt |L| = {:.3g} (|L| = {:.4g} 1/s, dt = {:.4g} s): the grid velocities around it close a cell of h "
        "= {:.4g} m in about {:.3g} steps; the time step is too long for this rate of deformation: use "
        "time_step <= 0.5 / |L| = {:.3g} s or lower velocities",
        dt * rate, rate, dt, h, 1.0 / (dt * rate), 0.5 / rate);
  const double det = dF.determinant();
  return fmt::format(
      "MPM: {} has {} at t = {:.6g} s: the material inverted within one step (det dF = {} for the step's "
      "increment dF = exp(dt L)); {}",
      who, what, time_, std::isfinite(det) ? fmt::format("{:.4g}", det) : "not finite", advice);
}

void MPMSolver::compute_grid_forces() {
  const Particles& P = particles_;
  // The body force at the instant of the stress it acts with: t + dt after USF's update,
  // t + dt / 2 after USAVG's half update, t for USL and SZS (the stress of the last step's end)
  // and for Verlet (the stress of t^n).
  const double tb = time_ + (settings_.update == UpdateScheme::usf     ? dt_
                             : settings_.update == UpdateScheme::usavg ? 0.5 * dt_
                                                                       : 0.0);
  const auto& body_force = problem_.body_force;  // empty: body_ stays zero
  if (mls_) {  // eqs. (20), (21), (24), (25), reconstructing rho b (SPEC section 7)
    if (body_force)
      parallel_blocks(P.size(), 1024, [&](Index begin, Index end) {
        for (Index p = begin; p < end; ++p) body_[p] = checked_body_force(p, tb);
      });
    // Both fields in one pass over the MLS functions.
    mls_->reconstruct<Eigen::Matrix<double, 2, 3>>(gauss_forces_, [&](Index p) {
      Eigen::Matrix<double, 2, 3> at;
      at << density_[p] * body_[p], P.stress[p];
      return at;
    });
    const double omega = mls_->gauss_weight(), scale = density_scale_;
    weigh_quadrature(
        gauss_forces_,
        [omega, scale](Eigen::Matrix<double, 2, 3>& at) {
          at.col(0) *= scale;
          at *= omega;
        },
        [&](Eigen::Matrix<double, 2, 3>& at, Index p) {  // [m_p b_p | V_p sigma_p], as plain MPM
          at.col(0) *= P.mass[p] / density_[p];
          at.rightCols<2>() *= P.volume[p];
        });
    scatter<Vec2>(mls_->grid_weights(), grid_.size(), force_, partial2_, [&](Index g) {
      const Eigen::Matrix<double, 2, 3>& at = gauss_forces_[g];
      return [&at](double S, const Vec2& G) { return Vec2(S * at.col(0) - at.rightCols<2>() * G); };
    });
  } else {
    scatter<Vec2>(weights_, grid_.size(), force_, partial2_, [&](Index p) {
      // b_p by the thread that scatters p, at the particle's reference position.
      if (body_force) body_[p] = checked_body_force(p, tb);
      const Vec2 mb = P.mass[p] * body_[p];
      const Mat2 sv = P.volume[p] * P.stress[p];
      return [mb, sv](double S, const Vec2& G) { return Vec2(S * mb - sv * G); };  // eq. (26): f_b + f_int
    });
  }
}

Vec2 MPMSolver::checked_body_force(Index p, double t) const {
  const Vec2 b = problem_.body_force(particles_.reference[p], t);
  if (!b.allFinite()) [[unlikely]]
    refuse_body_force(p, t);
  return b;
}

void MPMSolver::refuse_body_force(Index p, double t) const {
  throw InputError(
      fmt::format("{}: the body force at {} is not finite at t = {:.6g} s; it must be finite wherever a "
                  "body is, at every time of the run",
                  problem_.body_force_where, particle_name(particles_, p), t));
}

void MPMSolver::update_grid_momentum() {
  // Mass-proportional damping, -alpha m_i v_i = -alpha (mv)_i, joins the force, so that the
  // particles' accelerations (grid_to_particles) see it too.
  if (settings_.damping > 0.0)
    for (std::size_t i = 0; i < momentum_.size(); ++i) force_[i] -= settings_.damping * momentum_[i];
  for (std::size_t i = 0; i < momentum_.size(); ++i) {
    if (walls_[i] & 1) force_[i].x() = momentum_[i].x() = 0.0;
    if (walls_[i] & 2) force_[i].y() = momentum_[i].y() = 0.0;
    momentum_[i] += dt_ * force_[i];  // eq. (28)
  }
}

void MPMSolver::grid_accelerations() {
  for (std::size_t i = 0; i < force_.size(); ++i) {
    if (walls_[i] & 1) force_[i].x() = 0.0;
    if (walls_[i] & 2) force_[i].y() = 0.0;
  }
  if (mass_matrix_) {
    at_time(time_, [&] { acceleration_ = mass_matrix_->solve(force_, mass_, walls_, mass_floor()); });
    return;
  }
  const double floor = mass_floor();
  acceleration_.resize(mass_.size());
  for (std::size_t i = 0; i < mass_.size(); ++i)
    acceleration_[i] = std::abs(mass_[i]) > floor ? Vec2(force_[i] / mass_[i]) : Vec2::Zero();
}

void MPMSolver::grid_to_particles() {
  grid_accelerations();
  if (mass_matrix_)  // M^-1 ((mv)_i + dt f_i), without solving again
    for (std::size_t i = 0; i < velocity_.size(); ++i) velocity_[i] += dt_ * acceleration_[i];
  else
    grid_velocities(momentum_);
  move_particles<true>();
}

void MPMSolver::midpoint_weights() {
  const Particles& P = particles_;
  const int kmax = settings_.deformation_terms;
  const double floor = mass_floor();
  const double* mass = mass_.data();  // raw pointers, as in update_stress()
  const Vec2* velocity = velocity_.data();
  // The domain follows F for these (CPDI2's follows its corners; the others have none that moves).
  const bool deforms = settings_.method == MPMMethod::cpgimp ||
                       settings_.method == MPMMethod::bspline_cpgimp || settings_.method == MPMMethod::cpdi ||
                       settings_.method == MPMMethod::qcpdi;
  const bool corners = settings_.method == MPMMethod::cpdi2;
  if (corners) midpoint_corners_.resize(P.corners.size());
  midpoint_positions_.resize(P.position.size());
  basis_.resize(midpoint_weights_, P.size());
  at_time(time_, [&] {
    parallel_blocks(P.size(), 512, [&](Index begin, Index end) {
      for (Index p = begin; p < end; ++p)
        for_particle(P, p, [&] {
          Vec2 v = Vec2::Zero();
          weights_.for_each(p, [&](Index i, double S, const Vec2&) { v += S * velocity[i]; });
          const Vec2 x = P.position[p] + 0.5 * dt_ * v;
          midpoint_positions_[p] = x;
          if (corners) {
            for (int k = 0; k < 4; ++k)
              midpoint_corners_[p][k] =
                  P.corners[p][k] + 0.5 * dt_ * basis_.hat_interpolate(P.corners[p][k], velocity_);
            basis_.evaluate_quadrilateral(midpoint_corners_[p], x, midpoint_weights_, p);
            return;
          }
          const Vec2 half = P.half_size.empty() ? Vec2::Zero() : P.half_size[p];
          if (!deforms) {
            basis_.evaluate(x, P.deformation[p], half, midpoint_weights_, p);
            return;
          }
          const Mat2 L = velocity_gradient(weights_, p, P.velocity[p], mass, velocity, floor);
          basis_.evaluate(x, Mat2(exp_series(L, 0.5 * dt_, kmax) * P.deformation[p]), half, midpoint_weights_,
                          p);
        });
    });
  });
  std::swap(weights_, midpoint_weights_);
  // MLS reconstructs mass and momenta at the midpoint only when it carries them (lumped).
  if (mls_transfers()) update_mls_functions(midpoint_positions_);
}

void MPMSolver::half_kick_particles() {
  Particles& P = particles_;
  const Vec2* acceleration = acceleration_.data();  // raw pointers, as in update_stress()
  const double kick = 0.5 * dt_;
  parallel_blocks(P.size(), 1024, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p) {
      Vec2 a = Vec2::Zero();
      weights_.for_each(p, [&](Index i, double S, const Vec2&) { a += S * acceleration[i]; });
      const Vec2 v = P.velocity[p] + kick * a;
      if (!v.allFinite()) throw NumericalError(motion_failure(p, a, Vec2::Zero(), v, P.position[p]));
      P.velocity[p] = v;
    }
  });
}

template <bool kick>
void MPMSolver::move_particles() {
  Particles& P = particles_;
  // The work of the body forces over the step, to the order of the update. b_p . dx_p with b
  // at the instant the forces took it leaves an error in the energy balance first order in
  // dt that grows with the run where b changes in time (with Verlet 9 % of the largest
  // kinetic + strain energy over the ten periods of verification/mpm-vibration/long_run.toml;
  // 1.3e-6 now). So:
  //   kick (USF, USL, SZS, USAVG)  the impulse dt m_p b_p on the mean of the grid velocities at
  //     the particle before and after the update, m_p b_p . dt (v - dt a / 2): the work of
  //     the update's own momentum change;
  //   drift (Verlet)  the trapezoidal rule in time, m_p (b(t) + b(t + dt)) / 2 . dx_p, the
  //     kicks' two forces: the first half here, the second once the forces at t + dt are
  //     known (complete_drift_work).
  BodySums work(bodies_);
  const bool drift_work = !kick && problem_.body_force;
  if (drift_work) drift_.resize(P.position.size());
  const Vec2* acceleration = acceleration_.data();  // raw pointers, as in update_stress()
  const Vec2* velocity = velocity_.data();
  const bool corners = settings_.method == MPMMethod::cpdi2;
  const bool midpoint = settings_.update == UpdateScheme::verlet;
  const Box extent = grid_.extent();
  // Each range stops at its first failing particle, and parallel_ranges reports the lowest
  // range's: the failure named is that of the lowest index, in every run.
  parallel_ranges(P.size(), [&](int t, Index begin, Index end) {
    double* w = work.row(t);
    for (Index p = begin; p < end; ++p) {
      Vec2 a = Vec2::Zero(), v = Vec2::Zero();
      weights_.for_each(p, [&](Index i, double S, const Vec2&) {
        if constexpr (kick) a += S * acceleration[i];
        v += S * velocity[i];
      });
      const Vec2 vp = kick ? Vec2(P.velocity[p] + dt_ * a) : P.velocity[p];  // eq. (29)
      const Vec2 dx = dt_ * v;   // eq. (30)
      const Vec2 x = P.position[p] + dx;
      // Checked before they are stored: a particle's state stays finite, and one that would
      // leave the grid is named here, with its step, not by the next step's weights.
      if (!vp.allFinite() || !x.allFinite()) throw NumericalError(motion_failure(p, a, v, vp, x));
      // CPDI2: the corners move with the updated grid velocity at them (Sadeghirad et al.
      // 2013), x_c += dt sum_i N_i(x_c) v_i; they lay on the grid for this step's weights.
      // Verlet reads the velocity at the midpoint corners. A corner leaves the grid before
      // its particle does: they are checked first.
      DomainCorners moved;
      if (corners)
        for (int k = 0; k < 4; ++k) {
          const Vec2& c = P.corners[p][k];
          moved[k] = c + dt_ * basis_.hat_interpolate(midpoint ? midpoint_corners_[p][k] : c, velocity_);
          if (!moved[k].allFinite() || !extent.contains(moved[k]))
            throw NumericalError(motion_failure(p, a, v, vp, moved[k], k));
        }
      if (!extent.contains(x)) throw NumericalError(motion_failure(p, a, v, vp, x));
      if (corners) P.corners[p] = moved;
      P.velocity[p] = vp;
      P.position[p] = x;
      if constexpr (kick) {
        w[P.body[p]] += P.mass[p] * body_[p].dot(dx - 0.5 * dt_ * dt_ * a);
      } else if (drift_work) {
        w[P.body[p]] += 0.5 * P.mass[p] * body_[p].dot(dx);
        drift_[p] = dx;
      }
    }
  });
  work.add_to(external_work_);
}

std::string MPMSolver::motion_failure(Index p, const Vec2& a, const Vec2& v, const Vec2& vp, const Vec2& x,
                                      int corner) const {
  const Particles& P = particles_;
  const std::string who = particle_name(P, p);
  const double to = time_ + dt_;
  // A grid value at the particle that is not finite: name the first node that holds one.
  const auto grid_value = [&](const char* quantity, const std::vector<Vec2>& nodal) {
    std::string node;
    weights_.for_each(p, [&](Index i, double, const Vec2&) {
      if (node.empty() && !nodal[i].allFinite())
        node =
            fmt::format("; node {} at ({:.6g}, {:.6g}) holds one", i, grid_.node(i).x(), grid_.node(i).y());
    });
    return fmt::format(
        "MPM: {}: the grid {} at it is not finite in the step to t = {:.6g} s{}: the grid momenta or forces "
        "overflowed, the motion blew up; use a smaller time step",
        who, quantity, to, node);
  };
  if (!a.allFinite()) return grid_value("acceleration", acceleration_);
  if (!v.allFinite()) return grid_value("velocity", velocity_);
  const std::string moving = corner < 0 ? who : fmt::format("{}: its CPDI2 domain corner {}", who, corner);
  if (!vp.allFinite() || !x.allFinite())
    return fmt::format(
        "MPM: {}: the velocity or position overflowed in the step to t = {:.6g} s (velocity {}, grid "
        "acceleration {}): the motion blew up; use a smaller time step",
        moving, to, vector_text(vp), vector_text(a));
  // It left the grid: by more than a cell in one step (the step is too long for its speed),
  // in an unstable run, or at the edge of the grid box.
  const Box e = grid_.extent();
  const Vec2& from = corner < 0 ? P.position[p] : P.corners[p][corner];
  const double h = grid_.spacing(), moved = (x - from).stableNorm();
  std::string cause;
  if (moved > h)
    cause = fmt::format(
        "it moved {:.3g} cells in one step (|v| = {:.4g} m/s, dt = {:.4g} s, h = {:.4g} m): the time step is "
        "too long for its velocity; {}",
        moved / h, moved / dt_, dt_, h, crossing_advice(moved / dt_, h, settings_.end_time));
  else if (dt_ > h_over_c_)
    cause = fmt::format(
        "the time step {:.4g} s is {:.3g} times the Courant limit {:.4g} s: the motion is unstable; use a "
        "smaller time step",
        dt_, dt_ / h_over_c_, h_over_c_);
  else
    cause =
        "the body reached the edge of the grid: enlarge the grid box ([mpm] box) or hold that side with a "
        "wall ([mpm] walls)";
  return fmt::format(
      "MPM: {} left the grid [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] in the step to t = {:.6g} s, from ({:.6g}, "
      "{:.6g}) to ({:.6g}, {:.6g}); {}",
      moving, e.lo.x(), e.hi.x(), e.lo.y(), e.hi.y(), to, from.x(), from.y(), x.x(), x.y(), cause);
}

void MPMSolver::complete_drift_work() {
  const Particles& P = particles_;
  BodySums work(bodies_);
  parallel_ranges(P.size(), [&](int t, Index begin, Index end) {
    double* w = work.row(t);
    for (Index p = begin; p < end; ++p) w[P.body[p]] += 0.5 * P.mass[p] * body_[p].dot(drift_[p]);
  });
  work.add_to(external_work_);
}

void MPMSolver::extrapolate_updated_momenta() {
  momenta_to_grid(updated_momentum_);
  grid_velocities(updated_momentum_);
}

std::vector<Vec2> MPMSolver::interpolated_grid_velocity() const {
  const Particles& P = particles_;
  std::vector<Vec2> out(P.mass.size());
  parallel_blocks(P.size(), 512, [&](Index begin, Index end) {
    WeightTable w;
    basis_.resize(w, 1);
    for (Index p = begin; p < end; ++p) {
      basis_.evaluate(P, p, w, 0);
      Vec2 v = Vec2::Zero();
      w.for_each(0, [&](Index i, double S, const Vec2&) { v += S * velocity_[i]; });
      out[p] = v;
    }
  });
  return out;
}

MPMEnergy MPMSolver::energy() const {
  const Particles& P = particles_;
  MPMEnergy e;
  e.time = time_;
  e.bodies.resize(static_cast<std::size_t>(bodies_));
  for (Index p = 0; p < P.size(); ++p) {
    BodyEnergy& b = e.bodies[P.body[p]];
    const double kinetic = 0.5 * P.mass[p] * P.velocity[p].squaredNorm();
    const double strain = P.volume0[p] * mfree::energy(problem_.materials[P.material[p]].law, P.deformation[p], P.state[p]);
    const double dissipated = P.volume0[p] * P.state[p].dissipation;
    if (!std::isfinite(kinetic) || !std::isfinite(strain) || !std::isfinite(dissipated))
      throw NumericalError(fmt::format(
          "MPM: {} has an energy that is not finite at t = {:.6g} s (kinetic {}, strain {}, dissipated {}; "
          "|v| = {}, J = det F = {}): the motion blew up; use a smaller time step",
          particle_name(P, p), time_, finite_text(kinetic), finite_text(strain), finite_text(dissipated),
          finite_text(P.velocity[p].norm()), finite_text(P.deformation[p].determinant())));
    b.kinetic += kinetic;
    b.strain += strain;
    b.dissipated += dissipated;
    b.momentum += P.mass[p] * P.velocity[p];
    // The sum in particle order, as one body's would be: a single body's figures are the same
    // bits in both.
    e.sum.kinetic += kinetic;
    e.sum.strain += strain;
    e.sum.dissipated += dissipated;
    e.sum.momentum += P.mass[p] * P.velocity[p];
  }
  for (int b = 0; b < bodies_; ++b) {
    if (!std::isfinite(external_work_[b]))
      throw NumericalError(
          fmt::format("MPM: the work of the body forces on body {} is not finite at t = {:.6g} s: the "
                      "motion blew up; use a smaller time step",
                      b, time_));
    e.bodies[b].external = external_work_[b];
    e.sum.external += external_work_[b];
  }
  // Each particle's figures are finite: a sum that is not overflowed.
  const BodyEnergy& sum = e.sum;
  if (!std::isfinite(sum.kinetic) || !std::isfinite(sum.strain) || !std::isfinite(sum.dissipated) ||
      !std::isfinite(sum.external) || !sum.momentum.allFinite())
    throw NumericalError(
        fmt::format("MPM: the energies summed over the particles overflow at t = {:.6g} s (kinetic {}, "
                    "strain {}, work of the body forces {}): the motion blew up; use a smaller time step or "
                    "lower velocities",
                    time_, finite_text(sum.kinetic), finite_text(sum.strain), finite_text(sum.external)));
  return e;
}

}  // namespace mfree

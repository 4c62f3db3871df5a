#include "mfree/mpm/mpm_solver.hpp"

#include <cmath>
#include <fmt/format.h>

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

}  // namespace

MPMSolver::MPMSolver(MPMProblem problem, MPMSettings settings)
    : MPMSolver(problem, settings,
                seed_bodies(problem.bodies, problem.materials, problem.box,
                            problem.box.size().x() / std::max(settings.cells, 1), settings.particles_per_side,
                            uses_domains(settings.method))) {}

MPMSolver::MPMSolver(MPMProblem problem, MPMSettings settings, Particles particles)
    : problem_(std::move(problem)),
      settings_(checked(settings, problem_)),
      grid_(problem_.box, settings_.cells, is_bspline(settings_.method) ? settings_.degree : 1,
            grid_padding(settings_.method)),
      basis_(settings_.method, grid_),
      particles_(std::move(particles)) {
  if (uses_domains(settings_.method) && particles_.half_size.size() != particles_.mass.size())
    throw InputError(fmt::format("MPM: method {} needs the particle domains", to_string(settings_.method)));
  if (particles_.size() == 0) throw InputError("MPM: the problem has no particles");
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
    const MaterialUpdate u = update(law, particles_.deformation[p], particles_.state[p], false);
    particles_.stress[p] = cauchy_stress(law, u.stress, particles_.deformation[p]);
    particles_.stress_zz[p] = u.stress_zz;
  }
  external_work_.assign(static_cast<std::size_t>(bodies_), 0.0);
  walls_ = grid_.wall_mask(settings_.walls);
  for (double m : particles_.mass) particle_mass_ += m;
  body_.assign(particles_.mass.size(), Vec2::Zero());
  if (settings_.method == MPMMethod::bspline_mls)
    mls_ = std::make_unique<MLSReconstruction>(grid_, basis_, settings_.mls_basis, settings_.mls_support);

  // Time step (seed 002, "Theory: MPM Time Step"): dt = C h / c with C < 1, or a fixed step,
  // whichever is smaller; c the fastest of the materials' wave speeds.
  double c = 0.0;
  for (const MPMMaterial& m : problem_.materials) c = std::max(c, wave_speed(m.law, m.density));
  h_over_c_ = grid_.spacing() / c;
  const double wave = c;
  std::string limit = "h / c";
  if (settings_.mapping == GridMapping::pseudo_inverse) {
    const double factor = consistent_mass_courant(settings_.method, settings_.degree);
    h_over_c_ *= factor;
    limit = fmt::format("{} h / c (the pseudo-inverse mapping's consistent mass)", factor);
    mass_matrix_ = std::make_unique<GridMassMatrix>(
        grid_, mass_matrix_radius(settings_.method, settings_.degree), settings_.mass_filter);
  }
  const bool allowed = settings_.allow_unstable_time_step;
  if (settings_.courant > 1.0 && !allowed)
    throw InputError(fmt::format(
        "MPM: Courant factor {} is above 1: the explicit step would exceed {} = {:.4g} s (h = {:.4g}, c = {:.4g} m/s); "
        "use courant <= 1 or set allow_unstable_time_step = true",
        settings_.courant, limit, h_over_c_, grid_.spacing(), wave));
  if (settings_.time_step && *settings_.time_step > h_over_c_ && !allowed)
    throw InputError(fmt::format(
        "MPM: time_step {:.4g} s is above the Courant limit {} = {:.4g} s (h = {:.4g}, c = {:.4g} m/s, Courant number "
        "{:.3g}); use a smaller time_step or set allow_unstable_time_step = true",
        *settings_.time_step, limit, h_over_c_, grid_.spacing(), wave, *settings_.time_step / h_over_c_));
  double dt = settings_.courant * h_over_c_;
  if (settings_.time_step) dt = std::min(dt, *settings_.time_step);
  steps_ = step_count(settings_.end_time, dt, "MPM");
  dt_ = settings_.end_time / steps_;
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
      for (Index p = begin; p < end; ++p) basis_.evaluate(P, p, weights_, p);
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
  parallel_blocks(P.size(), 512, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p) {
      const Mat2 L = velocity_gradient(weights_, p, P.velocity[p], mass, velocity, floor);
      // eq. (35), by columns as well.
      const Mat2 dF = exp_series(L, dt, kmax);
      const Vec2 f0 = dF * P.deformation[p].col(0), f1 = dF * P.deformation[p].col(1);
      const double J = f0.x() * f1.y() - f0.y() * f1.x();
      if (!std::isfinite(J))  // the grid velocities it comes from are not finite: the step before blew up
        throw NumericalError(fmt::format(
            "MPM: particle {} (started at ({:.6g}, {:.6g})) has a non-finite velocity gradient at t = {:.6g} s: the "
            "motion blew up (velocities without bound after an unstable step or a nearly inverted neighbour); use a "
            "smaller time step, a finer grid or another method",
            p, P.reference[p].x(), P.reference[p].y(), time_));
      if (!(J > 0.0))
        throw NumericalError(fmt::format(
            "MPM: particle {} at ({:.6g}, {:.6g}) (started at ({:.6g}, {:.6g})) has J = det F = {:.4g} <= 0 at t = {:.6g} s: "
            "the material is inverted; use a smaller time step, a finer grid or another method",
            p, P.position[p].x(), P.position[p].y(), P.reference[p].x(), P.reference[p].y(), J, time_));
      Mat2& F = P.deformation[p];
      F.col(0) = f0;
      F.col(1) = f1;
      P.volume[p] = J * P.volume0[p];  // eq. (36)
      // eqs. (37) and (41): the law's update from the particle's state, committed at once
      // (an explicit step is always accepted).
      const Material& law = materials[material[p]].law;
      const MaterialUpdate u = update(law, F, P.state[p], false);
      P.state[p] = u.state;
      P.stress[p] = cauchy_stress(law, u.stress, F);
      P.stress_zz[p] = u.stress_zz;
      if (!P.stress[p].allFinite())
        throw NumericalError(fmt::format(
            "MPM: particle {} at ({:.6g}, {:.6g}) (started at ({:.6g}, {:.6g})) has a non-finite stress at J = det F = "
            "{:.4g}, t = {:.6g} s: the material is (nearly) inverted; use a smaller time step, a finer grid or another "
            "method",
            p, P.position[p].x(), P.position[p].y(), P.reference[p].x(), P.reference[p].y(), J, time_));
    }
  });
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
        for (Index p = begin; p < end; ++p) body_[p] = body_force(P.reference[p], tb);
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
      if (body_force) body_[p] = body_force(P.reference[p], tb);
      const Vec2 mb = P.mass[p] * body_[p];
      const Mat2 sv = P.volume[p] * P.stress[p];
      return [mb, sv](double S, const Vec2& G) { return Vec2(S * mb - sv * G); };  // eq. (26): f_b + f_int
    });
  }
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
      for (Index p = begin; p < end; ++p) {
        Vec2 v = Vec2::Zero();
        weights_.for_each(p, [&](Index i, double S, const Vec2&) { v += S * velocity[i]; });
        const Vec2 x = P.position[p] + 0.5 * dt_ * v;
        midpoint_positions_[p] = x;
        if (corners) {
          for (int k = 0; k < 4; ++k)
            midpoint_corners_[p][k] = P.corners[p][k] + 0.5 * dt_ * basis_.hat_interpolate(P.corners[p][k], velocity_);
          basis_.evaluate_quadrilateral(midpoint_corners_[p], x, midpoint_weights_, p);
          continue;
        }
        const Vec2 half = P.half_size.empty() ? Vec2::Zero() : P.half_size[p];
        if (!deforms) {
          basis_.evaluate(x, P.deformation[p], half, midpoint_weights_, p);
          continue;
        }
        const Mat2 L = velocity_gradient(weights_, p, P.velocity[p], mass, velocity, floor);
        basis_.evaluate(x, Mat2(exp_series(L, 0.5 * dt_, kmax) * P.deformation[p]), half, midpoint_weights_, p);
      }
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
      P.velocity[p] += kick * a;
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
  parallel_ranges(P.size(), [&](int t, Index begin, Index end) {
    double* w = work.row(t);
    for (Index p = begin; p < end; ++p) {
      Vec2 a = Vec2::Zero(), v = Vec2::Zero();
      weights_.for_each(p, [&](Index i, double S, const Vec2&) {
        if constexpr (kick) a += S * acceleration[i];
        v += S * velocity[i];
      });
      if constexpr (kick) P.velocity[p] += dt_ * a;  // eq. (29)
      const Vec2 dx = dt_ * v;   // eq. (30)
      P.position[p] += dx;
      if constexpr (kick) {
        w[P.body[p]] += P.mass[p] * body_[p].dot(dx - 0.5 * dt_ * dt_ * a);
      } else if (drift_work) {
        w[P.body[p]] += 0.5 * P.mass[p] * body_[p].dot(dx);
        drift_[p] = dx;
      }
      // CPDI2: the corners move with the updated grid velocity at them (Sadeghirad et al.
      // 2013), x_c += dt sum_i N_i(x_c) v_i; they lay on the grid for this step's weights.
      // Verlet reads the velocity at the midpoint corners.
      if (corners)
        for (int k = 0; k < 4; ++k)
          P.corners[p][k] += dt_ * basis_.hat_interpolate(midpoint ? midpoint_corners_[p][k] : P.corners[p][k], velocity_);
    }
  });
  work.add_to(external_work_);
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
    e.bodies[b].external = external_work_[b];
    e.sum.external += external_work_[b];
  }
  return e;
}

}  // namespace mfree

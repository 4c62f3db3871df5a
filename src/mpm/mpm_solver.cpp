#include "mfree/mpm/mpm_solver.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"

namespace mfree {

std::string_view to_string(UpdateScheme s) {
  switch (s) {
    case UpdateScheme::usf: return "usf";
    case UpdateScheme::usl: return "usl";
    case UpdateScheme::szs: return "szs";
    case UpdateScheme::usavg: return "usavg";
  }
  return "?";
}

namespace {

const MPMSettings& checked(const MPMSettings& s, const MPMProblem& p) {
  if (!(p.density > 0.0)) throw InputError(fmt::format("MPM: the density must be positive (got {})", p.density));
  if (!(s.end_time > 0.0)) throw InputError(fmt::format("MPM: end_time must be positive (got {})", s.end_time));
  if (s.cells < 1) throw InputError(fmt::format("MPM: needs at least one cell (got {})", s.cells));
  if (is_bspline(s.method) && (s.degree < 2 || s.degree > 3))
    throw InputError(fmt::format("MPM: B-spline degree must be 2 or 3 (got {})", s.degree));
  if (s.deformation_terms < 1 || s.deformation_terms > 10)
    throw InputError(fmt::format("MPM: deformation_terms (kmax) must lie in [1, 10] (got {})", s.deformation_terms));
  if (!(s.courant > 0.0)) throw InputError(fmt::format("MPM: the Courant factor must be positive (got {})", s.courant));
  if (s.method == MPMMethod::bspline_mls && !(s.mls_support >= 1.0))
    throw InputError(fmt::format("MPM: mls_support must be at least one cell (got {})", s.mls_support));
  return s;
}

Mat2 outer(const Vec2& a, const Vec2& b) { return a * b.transpose(); }

}  // namespace

MPMSolver::MPMSolver(MPMProblem problem, MPMSettings settings)
    : MPMSolver(problem, settings,
                fill_box(problem.domain, problem.domain.size().x() / std::max(settings.cells, 1),
                         settings.particles_per_side, problem.density,
                         settings.method == MPMMethod::ugimp || settings.method == MPMMethod::cpdi)) {
  if (problem_.initial_velocity)
    for (Index p = 0; p < particles_.size(); ++p) particles_.velocity[p] = problem_.initial_velocity(particles_.reference[p]);
}

MPMSolver::MPMSolver(MPMProblem problem, MPMSettings settings, Particles particles)
    : problem_(std::move(problem)),
      settings_(checked(settings, problem_)),
      grid_(problem_.domain, settings_.cells, is_bspline(settings_.method) ? settings_.degree : 1,
            grid_padding(settings_.method)),
      basis_(settings_.method, grid_),
      particles_(std::move(particles)) {
  if ((settings_.method == MPMMethod::ugimp || settings_.method == MPMMethod::cpdi) &&
      particles_.half_size.size() != particles_.mass.size())
    throw InputError(fmt::format("MPM: method {} needs the particle domains", to_string(settings_.method)));
  for (Index p = 0; p < particles_.size(); ++p)
    particles_.stress[p] = cauchy_stress(problem_.material, particles_.deformation[p]);
  walls_ = grid_.wall_mask(settings_.walls);
  if (settings_.method == MPMMethod::bspline_mls)
    mls_ = std::make_unique<MLSReconstruction>(grid_, basis_, settings_.mls_support);

  // Time step (seed 002, "Theory: MPM Time Step"): dt = C h / c with C < 1, or a fixed step,
  // whichever is smaller.
  h_over_c_ = grid_.spacing() / wave_speed(problem_.material, problem_.density);
  const bool allowed = settings_.allow_unstable_time_step;
  if (settings_.courant > 1.0 && !allowed)
    throw InputError(fmt::format(
        "MPM: Courant factor {} is above 1: the explicit step would exceed h / c = {:.4g} s (h = {:.4g}, c = {:.4g} m/s); "
        "use courant <= 1 or set allow_unstable_time_step = true",
        settings_.courant, h_over_c_, grid_.spacing(), grid_.spacing() / h_over_c_));
  if (settings_.time_step && *settings_.time_step > h_over_c_ && !allowed)
    throw InputError(fmt::format(
        "MPM: time_step {:.4g} s is above the Courant limit h / c = {:.4g} s (h = {:.4g}, c = {:.4g} m/s, Courant number "
        "{:.3g}); use a smaller time_step or set allow_unstable_time_step = true",
        *settings_.time_step, h_over_c_, grid_.spacing(), grid_.spacing() / h_over_c_, *settings_.time_step / h_over_c_));
  double dt = settings_.courant * h_over_c_;
  if (settings_.time_step) dt = std::min(dt, *settings_.time_step);
  steps_ = static_cast<int>(std::ceil(settings_.end_time / dt * (1.0 - 1e-12)));
  dt_ = settings_.end_time / steps_;
}

MPMSolver::~MPMSolver() = default;

const WeightTable& MPMSolver::source_weights() const { return mls_ ? mls_->grid_weights() : weights_; }

void MPMSolver::step() {
  const bool first = settings_.update == UpdateScheme::usf || settings_.update == UpdateScheme::usavg;
  const bool again = settings_.update == UpdateScheme::szs || settings_.update == UpdateScheme::usavg;
  const double stress_dt = settings_.update == UpdateScheme::usavg ? 0.5 * dt_ : dt_;
  timer_.time("weights", [&] { compute_weights(); });
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

void MPMSolver::compute_weights() {
  Particles& P = particles_;
  weights_.resize(P.size(), basis_.stride());
  const bool domains = !P.half_size.empty();
  parallel_blocks(P.size(), 512, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
      basis_.evaluate(P.position[p], P.deformation[p], domains ? P.half_size[p] : Vec2::Zero(), weights_.slot(p));
  });
  if (mls_) mls_->update(P.position);
}

void MPMSolver::particles_to_grid() {
  const Particles& P = particles_;
  if (mls_) {  // eqs. (18), (19), (22), (23)
    // rho_p^t: the densities of the step's start serve every reconstruction of the step.
    const double w = mls_->gauss_weight();
    density_.resize(P.mass.size());
    for (Index p = 0; p < P.size(); ++p) density_[p] = w * P.mass[p] / P.volume[p];
    mls_->reconstruct<double>(source_mass_, [&](Index p) { return density_[p]; });
    mls_->reconstruct<Vec2>(source_momentum_, [&](Index p) { return Vec2(density_[p] * P.velocity[p]); });
  } else {
    source_mass_ = P.mass;
    source_momentum_.resize(P.mass.size());
    for (Index p = 0; p < P.size(); ++p) source_momentum_[p] = P.mass[p] * P.velocity[p];
  }
  std::vector<Eigen::Vector3d> grid;
  scatter<Eigen::Vector3d>(source_weights(), grid_.size(), grid, [&](Index q, double S, const Vec2&) {
    return Eigen::Vector3d(S * source_mass_[q], S * source_momentum_[q].x(), S * source_momentum_[q].y());
  });
  mass_.resize(grid.size());
  momentum_.resize(grid.size());
  double grid_total = 0.0, particle_total = 0.0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    mass_[i] = grid[i][0];
    momentum_[i] = grid[i].tail<2>();
    grid_total += mass_[i];
  }
  for (double m : P.mass) particle_total += m;
  mass_defect_ = std::abs(grid_total - particle_total) / particle_total;
  grid_velocities(momentum_);
}

void MPMSolver::grid_velocities(const std::vector<Vec2>& momentum) {
  velocity_.resize(momentum.size());
  const double floor = mass_floor();
  for (std::size_t i = 0; i < momentum.size(); ++i) {
    Vec2 v = mass_[i] > floor ? Vec2(momentum[i] / mass_[i]) : Vec2::Zero();
    if (walls_[i] & 1) v.x() = 0.0;
    if (walls_[i] & 2) v.y() = 0.0;
    velocity_[i] = v;
  }
}

void MPMSolver::update_stress(double dt) {
  Particles& P = particles_;
  const int kmax = settings_.deformation_terms;
  const double floor = mass_floor();
  parallel_blocks(P.size(), 512, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p) {
      const std::size_t o = static_cast<std::size_t>(p) * weights_.stride;
      // eq. (34), relative to v_p; nodes without mass carry no velocity and are left out.
      Mat2 L = Mat2::Zero();
      for (int k = 0; k < weights_.stride; ++k) {
        const Index i = weights_.node[o + k];
        if (mass_[i] > floor) L += outer(velocity_[i] - P.velocity[p], weights_.G[o + k]);
      }
      // dF = exp(dt L) by its series to kmax terms (seed 002, "Incremental Deformation Gradient").
      const Mat2 A = dt * L;
      Mat2 dF = Mat2::Identity(), term = Mat2::Identity();
      for (int k = 1; k <= kmax; ++k) {
        term = term * A / k;
        dF += term;
      }
      const Mat2 F = dF * P.deformation[p];  // eq. (35)
      const double J = F.determinant();
      if (!(J > 0.0))
        throw NumericalError(fmt::format(
            "MPM: particle {} at ({:.6g}, {:.6g}) (started at ({:.6g}, {:.6g})) has J = det F = {:.4g} <= 0 at t = {:.6g} s: "
            "the material is inverted; use a smaller time step, a finer grid or another method",
            p, P.position[p].x(), P.position[p].y(), P.reference[p].x(), P.reference[p].y(), J, time_));
      P.deformation[p] = F;
      P.volume[p] = J * P.volume0[p];                      // eq. (36)
      P.stress[p] = cauchy_stress(problem_.material, F);  // eqs. (37) and (41)
    }
  });
}

void MPMSolver::compute_grid_forces() {
  const Particles& P = particles_;
  // The body force at the instant of the stress it acts with: t + dt after USF's update,
  // t + dt / 2 after USAVG's half update, t for USL and SZS (the stress of the last step's end).
  const double tb = time_ + (settings_.update == UpdateScheme::usf     ? dt_
                             : settings_.update == UpdateScheme::usavg ? 0.5 * dt_
                                                                       : 0.0);
  body_.assign(P.mass.size(), Vec2::Zero());
  if (problem_.body_force)
    parallel_blocks(P.size(), 1024, [&](Index begin, Index end) {
      for (Index p = begin; p < end; ++p) body_[p] = problem_.body_force(P.reference[p], tb);
    });
  if (mls_) {  // eqs. (20), (21), (24), (25), reconstructing rho b (SPEC section 7)
    const double w = mls_->gauss_weight();
    mls_->reconstruct<Vec2>(source_body_, [&](Index p) { return Vec2(density_[p] * body_[p]); });
    mls_->reconstruct<Mat2>(source_stress_, [&](Index p) { return Mat2(w * P.stress[p]); });
  } else {
    source_body_.resize(P.mass.size());
    source_stress_.resize(P.mass.size());
    for (Index p = 0; p < P.size(); ++p) {
      source_body_[p] = P.mass[p] * body_[p];
      source_stress_[p] = P.volume[p] * P.stress[p];
    }
  }
  scatter<Vec2>(source_weights(), grid_.size(), force_, [&](Index q, double S, const Vec2& G) {
    return Vec2(S * source_body_[q] - source_stress_[q] * G);  // eq. (26): f_b + f_int
  });
}

void MPMSolver::update_grid_momentum() {
  for (std::size_t i = 0; i < momentum_.size(); ++i) {
    if (walls_[i] & 1) force_[i].x() = momentum_[i].x() = 0.0;
    if (walls_[i] & 2) force_[i].y() = momentum_[i].y() = 0.0;
    momentum_[i] += dt_ * force_[i];  // eq. (28)
  }
}

void MPMSolver::grid_to_particles() {
  Particles& P = particles_;
  const double floor = mass_floor();
  std::vector<Vec2> acceleration(mass_.size());
  for (std::size_t i = 0; i < mass_.size(); ++i)
    acceleration[i] = mass_[i] > floor ? Vec2(force_[i] / mass_[i]) : Vec2::Zero();
  grid_velocities(momentum_);
  std::vector<double> work(static_cast<std::size_t>(thread_count()), 0.0);
  parallel_ranges(P.size(), [&](int t, Index begin, Index end) {
    double w = 0.0;
    for (Index p = begin; p < end; ++p) {
      const std::size_t o = static_cast<std::size_t>(p) * weights_.stride;
      Vec2 a = Vec2::Zero(), v = Vec2::Zero();
      for (int k = 0; k < weights_.stride; ++k) {
        const Index i = weights_.node[o + k];
        a += weights_.S[o + k] * acceleration[i];
        v += weights_.S[o + k] * velocity_[i];
      }
      P.velocity[p] += dt_ * a;  // eq. (29)
      const Vec2 dx = dt_ * v;   // eq. (30)
      P.position[p] += dx;
      w += P.mass[p] * body_[p].dot(dx);
    }
    work[t] = w;
  });
  for (double w : work) external_work_ += w;
}

void MPMSolver::extrapolate_updated_momenta() {
  const Particles& P = particles_;
  if (mls_) {  // eqs. (31)-(33)
    mls_->reconstruct<Vec2>(source_momentum_, [&](Index p) { return Vec2(density_[p] * P.velocity[p]); });
  } else {
    for (Index p = 0; p < P.size(); ++p) source_momentum_[p] = P.mass[p] * P.velocity[p];
  }
  std::vector<Vec2> momentum;
  scatter<Vec2>(source_weights(), grid_.size(), momentum,
                [&](Index q, double S, const Vec2&) { return Vec2(S * source_momentum_[q]); });
  grid_velocities(momentum);
}

std::vector<Vec2> MPMSolver::interpolated_grid_velocity() const {
  const Particles& P = particles_;
  std::vector<Vec2> out(P.mass.size());
  const bool domains = !P.half_size.empty();
  parallel_blocks(P.size(), 512, [&](Index begin, Index end) {
    WeightTable w;
    w.resize(1, basis_.stride());
    for (Index p = begin; p < end; ++p) {
      basis_.evaluate(P.position[p], P.deformation[p], domains ? P.half_size[p] : Vec2::Zero(), w.slot(0));
      Vec2 v = Vec2::Zero();
      for (int k = 0; k < w.stride; ++k) v += w.S[k] * velocity_[w.node[k]];
      out[p] = v;
    }
  });
  return out;
}

MPMEnergy MPMSolver::energy() const {
  const Particles& P = particles_;
  MPMEnergy e;
  e.time = time_;
  for (Index p = 0; p < P.size(); ++p) {
    e.kinetic += 0.5 * P.mass[p] * P.velocity[p].squaredNorm();
    e.strain += P.volume0[p] * mfree::energy(problem_.material, P.deformation[p]);
  }
  e.external = external_work_;
  return e;
}

}  // namespace mfree

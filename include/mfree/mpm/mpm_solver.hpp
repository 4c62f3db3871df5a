#pragma once
// Explicit MPM time stepping (SPEC section 7; seed 002; seed 000 eqs. 18-37).
//
// One step from t to t + dt, in the stages the papers name:
//
//   1. weights S_ip, G_ip at the particles; for bspline_mls, then the MLS functions phi_gp
//      at the Gauss points (a stage of its own: a scene without MLS never runs it)
//   2. particles to grid: m_i = sum S_ip m_p, (mv)_i = sum S_ip m_p v_p
//        (bspline_mls: m_i = sum_g N_i(x_g) rho_g omega_g, eqs. 18-23)
//   3. USF, USAVG: stress update from v_i = (mv)_i / m_i (USAVG over dt / 2)
//   4. grid forces f_i = -sum sigma_p V_p G_ip + sum S_ip m_p b_p (eqs. 24-26 for MLS, which
//        reconstructs rho b, SPEC section 7)
//   5. grid momentum (mv)_i += dt (f_i - alpha (mv)_i) (eq. 28, with the optional mass-
//      proportional damping alpha); walls zero the components they hold (grid.hpp)
//   6. grid to particles: v_p += dt sum S_ip f_i / m_i, x_p += dt sum S_ip (mv)_i / m_i
//        (eqs. 29-30); CPDI2's corners x_c += dt sum_i N_i(x_c) v_i with the hats N_i and
//        the updated grid velocities v_i (Sadeghirad, Brannon, Guilkey 2013)
//   7. USL: stress update from the updated grid velocities;
//      SZS (MUSL), USAVG: the updated particle momenta extrapolated again (eqs. 31-33), then
//      the stress update from them (USAVG over dt / 2)
//
// These four are symplectic Euler in time: the particle velocity that starts a step acts as
// the velocity of its middle, so the motion runs dt / 2 ahead of the initial condition and
// the errors are first order in dt. The velocity Verlet scheme (verlet, kick-drift-kick) is
// second order: with the accelerations a_i^n of the stress and body force at t^n (f_i / m_i,
// or M^-1 f, below) and the grid velocities v_i^n of the particles' velocities,
//   kick      v_p^{n+1/2} = v_p^n + dt/2 sum_i S_ip a_i^n
//   midpoint  x_p* = x_p^n + dt/2 sum_i S_ip v_i^n (F by dF(dt/2 L_p), CPDI2's corners by
//             dt/2 v; bspline_mls with the lumped mapping, its MLS functions there): the
//             weights S*_ip
//   drift     v_i^{n+1/2} from the v_p^{n+1/2} through S*; x_p^{n+1} = x_p^n + dt sum_i S*_ip
//             v_i^{n+1/2}; the stress update with L_p from S* and v_i^{n+1/2}
//   kick      v_p^{n+1} = v_p^{n+1/2} + dt/2 sum_i S_ip(x^{n+1}) a_i^{n+1}
// Without the midpoint the drift is first order: the map from particle velocities to the
// grid changes as the particles move. The second kick's weights, masses and accelerations
// are those that start the next step, computed once. (Not with damping.)
//
// Nodal values from particle data (mapping, mass_matrix.hpp): lumped, v_i = (mv)_i / m_i and
// a_i = f_i / m_i, or pseudo_inverse, v = M^-1 (mv) and a = M^-1 f with the consistent mass
// matrix M, whose walls hold the same components at zero (bspline_mls: M and the momenta
// from the particles, whose data the pseudo-inverse fits; the MLS reconstruction then
// carries the forces alone, the stress and rho b at the Gauss points). Its highest frequency is higher,
// so the Courant limit below is h / c times 0.5 (hats and their averages), 0.35 (quadratic
// B-splines) or 0.22 (cubic).
//
// The stress update (eqs. 34-37): L_p = sum_i (v_i - v_p) G_ip^T (the same as sum v_i G_ip^T,
// since sum_i G_ip = 0, but exactly zero for a uniform velocity), the incremental deformation
// gradient dF = sum_{k=0..kmax} (dt L_p)^k / k! (seed 002), F_p <- dF F_p, V_p = J V_p0 and
// sigma_p from the particle's material (materials/, the laws the Galerkin solver uses).
//
// Failures are caught where they arise, before a NaN can spread: the stress update stops at
// J <= 0 (det F was positive, so the step's own dF inverted: dt |L| of order one), a
// non-finite F or stress; moving the particles, at a velocity or position that is not finite
// or that leaves the grid (CPDI2: a corner); the grid forces, at a body force that is not
// finite; energy(), at an energy that is not. Each names the particle by its index and its
// reference position X_p, the time, the quantity and its value, and the cause it points to
// (a step too long for the particle's speed, for its rate of deformation, an unstable step,
// a body at the edge of the grid). Each loop stops at its first failing particle and the
// parallel loops keep the lowest block's (core/parallel.hpp): the particle named is the
// lowest failing index, in every run.
// V_p = J V_p0 for every method, CPDI2 too: it is the volume of the F the stress comes from
// (the area of CPDI2's quadrilateral equals it for affine motions and drifts from it by
// the corners' own time integration otherwise; the area only normalises CPDI2's weights).
//
// Bodies (body.hpp) share the grid: one velocity field, so bodies that meet stick (the
// usual no-slip contact of MPM). Nodes without mass (empty cells) carry no velocity.
//
// Time step: dt = min(time_step, courant h / c), c the largest dilatational wave speed of the
// materials in the reference state (each with its own density), then shortened so that a
// whole number of steps reaches end_time. A
// Courant number above 1 (a time_step or courant beyond h / c) is refused unless the settings
// allow it (stability studies), and so is an initial velocity that crosses more than a cell
// per step, |v| dt > h (the Courant condition of the velocity). Sizes that overflow or vanish
// in double precision (cell, particle volume and mass, wave speed), a non-finite initial
// state and an initial kinetic energy that overflows are refused always. Every check that
// costs no particle (settings, grid memory, time step, particle count and memory) runs before
// the first particle is seeded, and each initial velocity as its particle is.

#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "mfree/core/stage_timer.hpp"
#include "mfree/materials/material.hpp"
#include "mfree/mpm/body.hpp"
#include "mfree/mpm/grid_transfer.hpp"
#include "mfree/mpm/mass_matrix.hpp"
#include "mfree/mpm/mls_reconstruction.hpp"
#include "mfree/mpm/particle_basis.hpp"
#include "mfree/mpm/particles.hpp"

namespace mfree {

enum class UpdateScheme { usf, usl, szs, usavg, verlet };
/// The schemes by name: usf, usl, szs, usavg, verlet.
const NameTable<UpdateScheme>& update_names();
std::string_view to_string(UpdateScheme s);

struct MPMSettings {
  MPMMethod method = MPMMethod::bspline;
  int degree = 2;  ///< B-spline degree (2 or 3); the other methods use hats
  UpdateScheme update = UpdateScheme::usf;
  GridMapping mapping = GridMapping::lumped;  ///< particle data to nodal values (mass_matrix.hpp)
  double mass_filter = 0.0;  ///< pseudo_inverse: beta of the short-wave filter (mass_matrix.hpp; 0: none)
  int cells = 16;                      ///< cells across the grid box's width
  int particles_per_side = 3;          ///< per cell side (9 per cell), for bodies stating none
  RKOrder mls_basis = RKOrder::linear;  ///< bspline_mls: the MLS basis (seed 000's)
  double mls_support = 1.5;            ///< bspline_mls: kernel half width in cells (seed 000: 3)
  int deformation_terms = 2;           ///< kmax of the dF series
  double end_time = 0.0;
  double courant = 0.5;
  std::optional<double> time_step;     ///< fixed step; dt = min(time_step, courant h / c)
  bool allow_unstable_time_step = false;
  Walls walls{Wall::open, Wall::open, Wall::open, Wall::open};  ///< per side of the grid box
  double damping = 0.0;                ///< alpha [1/s] of the grid force -alpha (mv)_i (0: none)
};

struct MPMProblem {
  Box box;                               ///< the grid box
  std::vector<MPMMaterial> materials;    ///< every one used by some body
  std::vector<MPMBody> bodies;           ///< inside the box, not overlapping
  /// Body force per unit mass [m/s^2], at reference positions X_p and time t; may be empty.
  std::function<Vec2(const Vec2& X, double t)> body_force;
  /// Where the body force is given, for messages ("scene.toml:30:1: key 'mpm.gravity'").
  std::string body_force_where = "the problem's body force";
};

/// Energies [J per unit thickness] and momentum [kg m/s per unit thickness] of a set of
/// particles (one body, or all).
struct BodyEnergy {
  double kinetic = 0.0;   ///< sum 1/2 m_p |v_p|^2
  double strain = 0.0;    ///< sum V_p0 W(F_p), W the stored energy of the particle's material
  double dissipated = 0.0;  ///< plastic work sum V_p0 W_p (plastic laws; 0 for elastic ones)
  double external = 0.0;  ///< work of the body forces over the steps (to the update's order: move_particles)
  Vec2 momentum = Vec2::Zero();  ///< sum m_p v_p
  /// kinetic + strain + dissipated - external: constant for an undamped motion.
  [[nodiscard]] double total() const { return kinetic + strain + dissipated - external; }
};

struct MPMEnergy {
  double time = 0.0;
  std::vector<BodyEnergy> bodies;  ///< per body, in the problem's order
  BodyEnergy sum;                  ///< over every particle
};

class MPMSolver {
 public:
  /// Builds grid, particles (seeded in the bodies) and weights; throws InputError for bad
  /// settings, among them a time step over the Courant limit, bad bodies (body.hpp) and
  /// initial velocities (at the body's velocity key), all but the last before any particle
  /// is seeded.
  MPMSolver(MPMProblem problem, MPMSettings settings);
  /// Tests: start from the given particles (their body and material indices into the
  /// problem's lists; problem.bodies may be empty) instead of seeding the bodies. CPDI2
  /// seeds corners x_p + F_p (+-l_x, +-l_y) where the particles have none.
  MPMSolver(MPMProblem problem, MPMSettings settings, Particles particles);
  ~MPMSolver();

  void step();

  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] double time_step() const { return dt_; }
  [[nodiscard]] int steps() const { return steps_; }  ///< steps to end_time
  /// h / c (times the consistent mass's factor with the pseudo-inverse mapping)
  [[nodiscard]] double courant_limit() const { return h_over_c_; }
  [[nodiscard]] const Particles& particles() const { return particles_; }
  [[nodiscard]] const Grid& grid() const { return grid_; }
  [[nodiscard]] const ParticleBasis& basis() const { return basis_; }
  [[nodiscard]] const MPMSettings& settings() const { return settings_; }
  [[nodiscard]] const std::vector<double>& grid_mass() const { return mass_; }
  /// Grid velocities of the last stress update (after the step: the updated ones).
  [[nodiscard]] const std::vector<Vec2>& grid_velocity() const { return velocity_; }
  /// sum_i S_ip(x) v_i at the particles' current positions (the grid velocity seen by them).
  [[nodiscard]] std::vector<Vec2> interpolated_grid_velocity() const;
  /// |sum_i m_i - sum_p m_p| / sum_p m_p of the last step (0 to round-off, MLS too).
  [[nodiscard]] double mass_defect() const { return mass_defect_; }
  /// bspline_mls: |sum_g rho_g omega_g - sum_p m_p| / sum_p m_p of the reconstruction in the
  /// last step, before the densities are scaled to remove it (0 for the other methods).
  [[nodiscard]] double reconstruction_defect() const { return reconstruction_defect_; }
  /// bspline_mls: interior cells integrated by their particles in the last step (the most of
  /// its reconstructions, Verlet's midpoint one too), as a Gauss point there had too few
  /// particles around it (MLSReconstruction::update; 0 otherwise).
  [[nodiscard]] Index demoted_cells() const { return demoted_cells_; }
  [[nodiscard]] MPMEnergy energy() const;
  [[nodiscard]] int bodies() const { return bodies_; }  ///< bodies the particles belong to
  /// Work of the body forces per body so far [J per unit thickness] (BodyEnergy::external).
  [[nodiscard]] const std::vector<double>& external_work() const { return external_work_; }
  /// Continues from a saved state of this problem and these settings (a checkpoint): a step
  /// starts from the particles (CPDI2: with their corners), the time and the work of the
  /// body forces alone; the grid and the weights are recomputed in it. InputError when the
  /// particles or bodies differ in number from this solver's, or CPDI2's corners are missing.
  void resume(Particles particles, double time, std::vector<double> external_work);
  [[nodiscard]] StageTimer& timer() { return timer_; }

 private:
  /// InputError for a particle whose initial state is not valid: mass, volume, position, F or
  /// velocity not finite, J <= 0, or (unless allow_unstable_time_step) a velocity that crosses
  /// more than a cell per step, |v| dt > h.
  void check_initial_state() const;
  /// InputError unless P has corners for every particle with cpdi2 and none otherwise.
  void check_corners(const Particles& P) const;
  void compute_weights();
  /// bspline_mls: the MLS functions for the particles at `positions` (their current ones or
  /// Verlet's midpoints), counting the cells returned to particle quadrature.
  void update_mls_functions(const std::vector<Vec2>& positions);
  void particles_to_grid();
  void update_stress(double dt);
  /// The message for particle p whose stress update over dt failed (velocity gradient L,
  /// increment dF, new J): which quantity, its value, and the cause (a step too long for the
  /// particle's velocity, or for its rate of deformation, or a blown-up grid).
  [[nodiscard]] std::string deformation_failure(Index p, const Mat2& L, const Mat2& dF, double J,
                                                double dt) const;
  void compute_grid_forces();
  /// b(X_p, t) of particle p; InputError (at body_force_where) when it is not finite.
  [[nodiscard]] Vec2 checked_body_force(Index p, double t) const;
  /// Throws that InputError (out of line: the loops that call the above stay small).
  [[noreturn, gnu::noinline, gnu::cold]] void refuse_body_force(Index p, double t) const;
  void update_grid_momentum();
  void grid_to_particles();
  void extrapolate_updated_momenta();
  /// The velocity Verlet step (update = verlet) and its stages.
  void verlet_step();
  /// Weights, masses, forces and grid accelerations of the particles where they are.
  void accelerations_at_positions();
  void scatter_mass();
  void scatter_momentum();
  /// bspline_mls: rho omega and rho v omega at the Gauss points, scaled to the particles' mass.
  void reconstruct_density();
  /// MLS: the values at the quadrature points times their volumes: gauss(at[g]) at the Gauss
  /// points, own(at[q], p) at the particles that are their own points (densities times
  /// m_p / rho_p, the stress times V_p: exactly plain MPM's m_p v_p, m_p b_p, V_p sigma_p).
  template <class T, class Gauss, class Own>
  void weigh_quadrature(std::vector<T>& at, Gauss&& gauss, Own&& own) const;
  /// Whether mass and momenta reach the grid through the MLS reconstruction (bspline_mls with
  /// the lumped mapping); with the pseudo-inverse they are the particles' own data that it
  /// fits, and MLS reconstructs the forces' stress and rho b alone.
  [[nodiscard]] bool mls_transfers() const { return mls_ && settings_.mapping == GridMapping::lumped; }
  /// (mv)_i of the particles' velocities, through the Gauss points for bspline_mls.
  void momenta_to_grid(std::vector<Vec2>& grid);
  void half_kick_particles();
  /// The weights at the midpoint x_p + dt/2 sum_i S_ip v_i (domains: F and CPDI2's corners
  /// advanced alike) in place of those at x_p.
  void midpoint_weights();
  /// After the masses are scattered: the mass defect and, for the pseudo-inverse, M.
  void grid_mass_ready();
  /// v_i from the grid momenta (either mapping).
  void grid_velocities(const std::vector<Vec2>& momentum);
  /// a_i from the grid forces (either mapping), walls holding their components.
  void grid_accelerations();
  /// x_p += dt sum_i S_ip v_i (eq. 30), CPDI2's corners; with kick, first v_p += dt sum_i
  /// S_ip a_i (eq. 29).
  template <bool kick>
  void move_particles();
  /// The message for particle p whose move failed: the grid acceleration a and velocity v at
  /// it, its new velocity vp and the new position x of it (corner < 0) or of its CPDI2 domain
  /// corner `corner` (a non-finite one, or one off the grid), and the cause (the grid blew up,
  /// a step too long for its velocity, an unstable step, or a body at the edge of the grid).
  [[nodiscard]] std::string motion_failure(Index p, const Vec2& a, const Vec2& v, const Vec2& vp,
                                           const Vec2& x, int corner = -1) const;
  /// verlet: the second half of the body forces' work over the drift, m_p b(t + dt) . dx_p / 2
  /// (move_particles adds the first, with b(t)).
  void complete_drift_work();
  /// Nodes with |m_i| below this have no velocity (1e-12 of a particle's mass). The mass may
  /// be negative: qCPDI's corner weights are, and a node that only corners of the body reach
  /// (beyond a body's corner) gets m_i < 0; p_i / m_i is still the particles' velocity there,
  /// as p_i and m_i carry the same weights.
  [[nodiscard]] double mass_floor() const { return 1e-12 * particles_.mass.front(); }

  MPMProblem problem_;
  MPMSettings settings_;
  Grid grid_;
  ParticleBasis basis_;
  Particles particles_;
  std::unique_ptr<MLSReconstruction> mls_;
  std::unique_ptr<GridMassMatrix> mass_matrix_;  ///< pseudo-inverse mapping only
  std::vector<unsigned char> walls_;
  WeightTable weights_;  ///< at the particles
  WeightTable midpoint_weights_;                  ///< verlet: the other table of the swap
  std::vector<DomainCorners> midpoint_corners_;  ///< verlet, cpdi2: the corners at the midpoint
  std::vector<Vec2> midpoint_positions_;         ///< verlet: x_p + dt/2 sum_i S_ip v_i
  std::vector<double> mass_;
  std::vector<Vec2> momentum_, force_, velocity_;
  std::vector<Eigen::Vector3d> mass_momentum_;  ///< (m_i, (mv)_i) as scattered
  std::vector<Vec2> acceleration_;              ///< f_i / m_i
  std::vector<Vec2> updated_momentum_;          ///< the second extrapolation's (mv)_i
  ScatterBuffers<Eigen::Vector3d> partial3_;
  ScatterBuffers<Vec2> partial2_;
  ScatterBuffers<double> partial1_;
  std::vector<Vec2> body_;       ///< b_p of the step (zero without a body force)
  std::vector<Vec2> drift_;      ///< verlet with a body force: dx_p of the step's drift
  std::vector<double> density_;  ///< MLS: rho_p at the start of the step
  // MLS: the fields the grid integrals need at the quadrature points (reconstructed at the
  // Gauss points, a particle's own elsewhere), times the points' volumes (omega_g, V_p).
  std::vector<Eigen::Vector3d> gauss_mass_momentum_;       ///< (rho, rho v) x volume
  std::vector<Vec2> gauss_momentum_;                       ///< rho v x volume, of the updated velocities
  std::vector<Eigen::Matrix<double, 2, 3>> gauss_forces_;  ///< [rho b | sigma] x volume
  double particle_mass_ = 0.0;  ///< sum_p m_p (constant)
  std::vector<double> external_work_;  ///< per body
  double time_ = 0.0, dt_ = 0.0, h_over_c_ = 0.0, mass_defect_ = 0.0, reconstruction_defect_ = 0.0;
  Index demoted_cells_ = 0;
  double density_scale_ = 1.0;  ///< MLS: the interior cells' sum_p m_p / sum_g rho_g omega_g of the step
  int steps_ = 0, bodies_ = 0;
  bool forces_current_ = false;  ///< verlet: weights, masses and forces are those of the particles' state
  StageTimer timer_;
};

}  // namespace mfree

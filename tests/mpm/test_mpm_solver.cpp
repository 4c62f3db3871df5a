// The MPM stepper: exact rigid translation, uniform-strain motion under every update scheme,
// convergence on the vibration problem, and the Courant limit.

#include <fmt/format.h>
#include <omp.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/mpm/particle_errors.hpp"
#include "mfree/problems/axis_aligned_vibration.hpp"

using namespace mfree;

namespace {

struct Method {
  MPMMethod method;
  int degree;
};
const Method methods[] = {
    {MPMMethod::classic, 1},        {MPMMethod::ugimp, 1},      {MPMMethod::cpgimp, 1},
    {MPMMethod::cpdi, 1},           {MPMMethod::qcpdi, 1},      {MPMMethod::cpdi2, 1},
    {MPMMethod::bspline, 2},        {MPMMethod::bspline, 3},    {MPMMethod::bspline_cpgimp, 2},
    {MPMMethod::bspline_cpgimp, 3}, {MPMMethod::bspline_mls, 2}};
const UpdateScheme schemes[] = {UpdateScheme::usf, UpdateScheme::usl, UpdateScheme::szs, UpdateScheme::usavg,
                                 UpdateScheme::verlet};
const GridMapping mappings[] = {GridMapping::lumped, GridMapping::pseudo_inverse};



const Box unit{Vec2(0.0, 0.0), Vec2(1.0, 1.0)};

MPMProblem block_problem() {
  return {unit, {{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}}, {rectangle_body("block", unit)}, {}};
}

MPMSettings settings_for(const Method& m, UpdateScheme s, int cells, GridMapping g = GridMapping::lumped) {
  MPMSettings st;
  st.method = m.method;
  st.degree = m.degree == 1 ? 2 : m.degree;
  st.update = s;
  st.mapping = g;
  st.cells = cells;
  st.end_time = 1.0;
  return st;
}

/// The uniform-strain motion v = v0 + L x on a free block of 60 x 60 cells (h = 1/64), and
/// which particles see it undisturbed for a step: those far enough from the free edges that
/// nothing of their disturbance reaches them (free-edge stress -> grid forces -> particle
/// velocities -> second extrapolation -> velocity gradient, each a node support (2 h) or, for
/// MLS, a kernel (3 h) further in).
struct AffineBlock {
  double h = 1.0 / 64.0;
  Box block{Vec2(2 * h, 2 * h), Vec2(62 * h, 62 * h)};
  double margin = 18.0 * h;
  Mat2 L = (Mat2() << 0.3, 0.2, -0.1, 0.25).finished();
  Vec2 v0 = Vec2(0.05, -0.02);

  /// 2 x 2 particles per cell moving with v0 + L x (with their domains if asked).
  [[nodiscard]] Particles particles(bool domains) const {
    Particles out = fill_box(block, h, 2, 1000.0, domains);
    for (Index p = 0; p < out.size(); ++p) out.velocity[p] = v0 + L * out.position[p];
    return out;
  }
  /// Whether a particle that started at X sees the motion undisturbed (2304 of them).
  [[nodiscard]] bool interior(const Vec2& X) const {
    return (X - Vec2(0.5, 0.5)).cwiseAbs().maxCoeff() <= 30 * h - margin;
  }
};

}  // namespace

TEST_CASE("a rigid translation leaves the stress exactly zero, particles on cell edges included", "[mpm]") {
  // 2 x 2 particles per cell on a box shifted by a quarter cell: every other particle row and
  // column lies exactly on a cell edge at the start. The velocity is a power of two, so the
  // grid velocities equal it exactly and the velocity gradient is exactly zero.
  const double h = 0.125;
  const Box block{Vec2(7.0 / 32.0, 7.0 / 32.0), Vec2(7.0 / 32.0 + 0.5, 7.0 / 32.0 + 0.5)};
  const Vec2 v(8.0, -4.0);
  for (const Method& m : methods)
    for (UpdateScheme s : schemes)
      for (GridMapping g : mappings) {
      Particles particles = fill_box(block, h, 2, 1000.0, uses_domains(m.method));
      CHECK(particles.position[0].x() == 0.25);  // on an edge
      particles.velocity.assign(particles.mass.size(), v);
      MPMSolver solver(block_problem(), settings_for(m, s, 8, g), std::move(particles));
      const int steps = 40;  // about 0.17 m: across a cell edge
      for (int n = 0; n < steps; ++n) solver.step();
      const Particles& P = solver.particles();
      double stress = 0.0, strain = 0.0, velocity = 0.0, position = 0.0;
      for (Index p = 0; p < P.size(); ++p) {
        stress = std::max(stress, P.stress[p].cwiseAbs().maxCoeff());
        strain = std::max(strain, (P.deformation[p] - Mat2::Identity()).cwiseAbs().maxCoeff());
        velocity = std::max(velocity, (P.velocity[p] - v).norm());
        position = std::max(position, (P.position[p] - P.reference[p] - solver.time() * v).norm());
        if (m.method == MPMMethod::cpdi2) {  // the corners translate with the particle
          const DomainCorners start = parallelogram_corners(P.reference[p], Mat2::Identity(), P.half_size[p]);
          for (int k = 0; k < 4; ++k)
            position = std::max(position, (P.corners[p][k] - start[k] - solver.time() * v).norm());
        }
      }
      CHECK(P.corners.size() == (m.method == MPMMethod::cpdi2 ? P.mass.size() : 0));
      INFO(to_string(m.method) << " degree " << m.degree << " " << to_string(s) << " " << grid_mapping_names().name(g));
      CHECK(stress == 0.0);
      CHECK(strain == 0.0);
      CHECK(velocity == 0.0);
      CHECK(position <= 1e-13);
      // The grid carries the particles' mass. MLS: the Gauss points stand for the 2 x 2
      // particles of each filled cell, those of the block's edge cells are their own points,
      // and a uniform density is reconstructed exactly.
      CHECK(solver.mass_defect() <= 1e-14);
      CHECK(solver.reconstruction_defect() <= 1e-13);
    }
}

namespace {

// Every method under update scheme s and both mappings, one step of a uniform-strain motion.
void check_uniform_strain_motion(UpdateScheme s) {
  // Particles whose every grid node is surrounded by the symmetric particle layout must see
  // the velocity gradient L exactly, so F = dF(dt L) = I + dt L + (dt L)^2 / 2 (USAVG:
  // dF(dt L / 2)^2), their velocities stay and x moves by dt (v0 + L x). Verlet reads the
  // gradient at the midpoint x + dt/2 (v0 + L x), where the particles' unchanged velocities
  // have the gradient L (I + dt L / 2)^-1, and moves them by exactly dt (v0 + L x). The
  // pseudo-inverse mapping fits the linear field exactly at every node, but spreads the
  // block's edge forces over all of it (M^-1 is not compactly supported), and Verlet's second
  // kick reads the forces of the new stress on the moved particle lattice, whose quadrature
  // of int grad N_i is not exact: both change the interior velocities by up to ~1e-7. The
  // block's edge nodes, half covered, keep their lumped values (mass_matrix.hpp), which the
  // pseudo-inverse's interior values feel at 1e-13 to 1e-11. Verlet's domains at the
  // midpoint come from F advanced by dF(dt/2 L) (CPDI2: the corners by dt/2 v), O(dt^2) from
  // the motion's own: F and x within ~1e-10 and 1e-11.
  const AffineBlock motion;
  const Mat2& L = motion.L;
  for (const Method& m : methods)
    for (GridMapping g : mappings) {
      const Particles start = motion.particles(uses_domains(m.method));
      MPMSolver solver(block_problem(), settings_for(m, s, 64, g), start);
      solver.step();
      const double dt = solver.time_step();
      auto series = [](const Mat2& A) { return Mat2(Mat2::Identity() + A + 0.5 * A * A); };
      const Mat2 midpoint = L * Mat2(Mat2::Identity() + 0.5 * dt * L).inverse();
      const Mat2 F = s == UpdateScheme::usavg    ? Mat2(series(0.5 * dt * L) * series(0.5 * dt * L))
                     : s == UpdateScheme::verlet ? series(dt * midpoint)
                                                 : series(dt * L);
      const Particles& P = solver.particles();
      double worst_F = 0.0, worst_v = 0.0, worst_x = 0.0;
      int interior = 0;
      for (Index p = 0; p < P.size(); ++p) {
        const Vec2 X = start.position[p];
        if (!motion.interior(X)) continue;
        ++interior;
        worst_F = std::max(worst_F, (P.deformation[p] - F).cwiseAbs().maxCoeff());
        worst_v = std::max(worst_v, (P.velocity[p] - start.velocity[p]).norm());
        worst_x = std::max(worst_x, (P.position[p] - X - dt * start.velocity[p]).norm());
      }
      INFO(to_string(m.method) << " degree " << m.degree << " " << to_string(s) << " " << grid_mapping_names().name(g)
                               << ": F " << worst_F << ", v " << worst_v << ", x " << worst_x);
      CHECK(interior == 2304);
      const bool exact = g == GridMapping::lumped && s != UpdateScheme::verlet;
      CHECK(worst_F <= (exact ? 1e-13 : 1e-10));
      CHECK(worst_v <= (exact ? 1e-12 : 2e-7));
      CHECK(worst_x <= (exact ? 1e-14 : 1e-11));
    }
}

}  // namespace

// One case per scheme, so that they run side by side (each takes minutes under the sanitizers).
TEST_CASE("USF reproduces a uniform-strain motion with every method and either mapping", "[mpm]") {
  check_uniform_strain_motion(UpdateScheme::usf);
}
TEST_CASE("USL reproduces a uniform-strain motion with every method and either mapping", "[mpm]") {
  check_uniform_strain_motion(UpdateScheme::usl);
}
TEST_CASE("SZS reproduces a uniform-strain motion with every method and either mapping", "[mpm]") {
  check_uniform_strain_motion(UpdateScheme::szs);
}
TEST_CASE("USAVG reproduces a uniform-strain motion with every method and either mapping", "[mpm]") {
  check_uniform_strain_motion(UpdateScheme::usavg);
}
TEST_CASE("Verlet reproduces a uniform-strain motion with every method and either mapping", "[mpm]") {
  check_uniform_strain_motion(UpdateScheme::verlet);
}

TEST_CASE("CPDI2: corners follow an affine velocity field exactly, the domain area stays J V0", "[mpm]") {
  // The uniform-strain motion above with the one-term update dF = I + dt L, which is what
  // moving the corners by dt v(x_c) does to the domain: interior corners land on
  // x_c + dt (v0 + L x_c), and the quadrilateral's area is det(I + dt L) V0 = J V0 (Verlet
  // too: the velocity at the midpoint corner is the corner's own, v0 + L x_c).
  const AffineBlock motion;
  const Mat2& L = motion.L;
  const Vec2& v0 = motion.v0;
  for (UpdateScheme s : schemes) {
    const Particles start = motion.particles(true);
    MPMSettings settings = settings_for({MPMMethod::cpdi2, 1}, s, 64);
    settings.deformation_terms = 1;
    MPMSolver solver(block_problem(), settings, start);
    const double dt = solver.time_step();
    // USAVG updates F twice by dt / 2, F = (I + dt L / 2)^2, and Verlet once by the midpoint's
    // gradient, F = I + dt L (I + dt L / 2)^-1: J differs from the corners' det(I + dt L) at
    // O(dt^2), and the area is compared with the affine map's alone.
    const bool verlet = s == UpdateScheme::verlet;
    solver.step();
    const Particles& P = solver.particles();
    double worst_corner = 0.0, worst_area = 0.0, worst_affine = 0.0;
    int interior = 0;
    for (Index p = 0; p < P.size(); ++p) {
      if (!motion.interior(start.position[p])) continue;
      ++interior;
      const DomainCorners c0 = parallelogram_corners(start.position[p], Mat2::Identity(), start.half_size[p]);
      for (int k = 0; k < 4; ++k)
        worst_corner = std::max(worst_corner, (P.corners[p][k] - c0[k] - dt * (v0 + L * c0[k])).norm());
      const double area = bilinear_nodes(P.corners[p], P.position[p], "test").volume;
      worst_affine = std::max(worst_affine, std::abs(area - (Mat2::Identity() + dt * L).determinant() * P.volume0[p]) / P.volume0[p]);
      if (s != UpdateScheme::usavg && !verlet)
        worst_area = std::max(worst_area, std::abs(area - P.deformation[p].determinant() * P.volume0[p]) / P.volume0[p]);
    }
    INFO(to_string(s) << ": corners " << worst_corner << ", area against J V0 " << worst_area << ", against det(I + dt L) V0 "
                      << worst_affine);
    CHECK(interior == 2304);
    CHECK(worst_corner <= (verlet ? 1e-11 : 1e-14));
    CHECK(worst_area <= 1e-12);
    CHECK(worst_affine <= (verlet ? 1e-10 : 1e-12));
  }
}

namespace {

/// RMS displacement error at t = T/4, where u peaks, of the vibration problem (SPEC section 6).
ParticleErrors quarter_period_errors(const Method& m, int cells, UpdateScheme update = UpdateScheme::usf,
                                     GridMapping mapping = GridMapping::lumped, RKOrder basis = RKOrder::linear) {
  const AxisAlignedVibration v{0.05, 1.0, 1e7, 0.3, 1000.0};
  MPMProblem problem{unit, {{"rubber", v.material(), v.density}}, {rectangle_body("block", unit)},
                     [v](const Vec2& X, double t) { return v.body_force(X, t); }};
  problem.bodies.front().initial_velocity = [v](const Vec2& X) { return v.velocity(X, 0.0); };
  MPMSettings s = settings_for(m, update, cells, mapping);
  s.mls_basis = basis;
  s.particles_per_side = 3;
  s.end_time = 0.25 * v.period();
  s.time_step = 1e-5;  // seed 000's step: the time error stays well below the space error
  s.walls = {Wall::slip, Wall::slip, Wall::slip, Wall::slip};
  MPMSolver solver(problem, s);
  for (int n = 0; n < solver.steps(); ++n) solver.step();
  return particle_errors(solver, v.motion<2>());
}

}  // namespace

TEST_CASE("B-spline and MLS-reconstructed B-spline MPM converge on the vibration problem", "[mpm][study]") {
  // A = 0.05, 9 particles per cell, USF, grids of 16 and 32 cells (from 8 cells the MLS
  // reconstruction with the seed's kernel, 3 cells wide, is pre-asymptotic).
  for (const Method& m : {Method{MPMMethod::bspline, 2}, Method{MPMMethod::bspline_mls, 2}}) {
    const ParticleErrors coarse = quarter_period_errors(m, 16), fine = quarter_period_errors(m, 32);
    const double rate = std::log2(coarse.displacement / fine.displacement);
    std::cout << fmt::format("{} at T/4: u error {:.3e} -> {:.3e} (rate {:.2f})\n", to_string(m.method),
                             coarse.displacement, fine.displacement, rate);
    INFO(to_string(m.method));
    CHECK(rate >= 1.5);
  }
}

TEST_CASE("B-splines averaged over the particle domains keep converging where point values stall",
          "[mpm][study]") {
  // A = 0.05, 9 particles per cell, Verlet and the pseudo-inverse, 16 and 32 cells: with the
  // time and projection errors removed, point-evaluated quadratic B-splines stall at the
  // particles' quadrature of the internal force, and the averages over cpGIMP's rectangles
  // (on this motion the deformed domains themselves) do not.
  double plain_rate = 0.0, averaged_fine = 0.0, plain_fine = 0.0;
  for (const Method& m : {Method{MPMMethod::bspline, 2}, Method{MPMMethod::bspline_cpgimp, 2}}) {
    const ParticleErrors coarse =
        quarter_period_errors(m, 16, UpdateScheme::verlet, GridMapping::pseudo_inverse);
    const ParticleErrors fine =
        quarter_period_errors(m, 32, UpdateScheme::verlet, GridMapping::pseudo_inverse);
    const double rate = std::log2(coarse.displacement / fine.displacement);
    std::cout << fmt::format("{}, Verlet, pseudo-inverse at T/4: u error {:.3e} -> {:.3e} (rate {:.2f})\n",
                             to_string(m.method), coarse.displacement, fine.displacement, rate);
    INFO(to_string(m.method));
    if (m.method == MPMMethod::bspline) {
      plain_rate = rate;
      plain_fine = fine.displacement;
    } else {
      CHECK(rate >= 2.3);
      averaged_fine = fine.displacement;
    }
  }
  CHECK(plain_rate <= 1.0);
  CHECK(averaged_fine <= plain_fine / 10.0);
}

TEST_CASE("velocity Verlet is second order in time, the symplectic Euler schemes first", "[mpm][study]") {
  // The vibration problem on 8 cells (quadratic B-splines, lCPDI) to t = T/4 at time steps
  // 4e-5, 2e-5 and 1e-5 s, each against the same grid at 1.25e-6 s: the RMS difference of
  // the particle positions. Verlet's drift reads the grid at the midpoint positions, without
  // which the particles crossing the grid leave a first-order term.
  const AxisAlignedVibration v{0.05, 1.0, 1e7, 0.3, 1000.0};
  MPMProblem problem{unit, {{"rubber", v.material(), v.density}}, {rectangle_body("block", unit)},
                     [v](const Vec2& X, double t) { return v.body_force(X, t); }};
  problem.bodies.front().initial_velocity = [v](const Vec2& X) { return v.velocity(X, 0.0); };
  for (const Method& m : {Method{MPMMethod::bspline, 2}, Method{MPMMethod::cpdi, 1}})
    for (UpdateScheme s : {UpdateScheme::usf, UpdateScheme::verlet}) {
      const auto positions = [&](double dt) {
        MPMSettings st = settings_for(m, s, 8);
        st.particles_per_side = 3;
        st.end_time = 0.25 * v.period();
        st.time_step = dt;
        st.walls = {Wall::slip, Wall::slip, Wall::slip, Wall::slip};
        MPMSolver solver(problem, st);
        for (int n = 0; n < solver.steps(); ++n) solver.step();
        return solver.particles().position;
      };
      const std::vector<Vec2> reference = positions(1.25e-6);
      std::vector<double> difference;
      for (const double dt : {4e-5, 2e-5, 1e-5}) {
        const std::vector<Vec2> x = positions(dt);
        double sum = 0.0;
        for (std::size_t p = 0; p < x.size(); ++p) sum += (x[p] - reference[p]).squaredNorm();
        difference.push_back(std::sqrt(sum / x.size()));
      }
      const double rate = std::log2(difference[1] / difference[2]);
      std::cout << fmt::format("{} {}: position differences {:.3e} {:.3e} {:.3e}, rate {:.2f}\n", to_string(m.method),
                               to_string(s), difference[0], difference[1], difference[2], rate);
      INFO(to_string(m.method) << " " << to_string(s));
      if (s == UpdateScheme::verlet) {
        CHECK(rate >= 1.8);
        CHECK(std::log2(difference[0] / difference[1]) >= 1.8);
      } else {
        CHECK(rate <= 1.3);
      }
    }
}

TEST_CASE("the pseudo-inverse mapping stops a run whose particles do not determine the nodes", "[mpm]") {
  // One particle per cell (seed 004: the pseudo-inverse needs two per cell and direction):
  // with hats, the particle-by-node matrix has more columns than rows, and the nodal values
  // are not determined. The lumped mapping runs the same particles.
  const Box block{Vec2(0.25, 0.25), Vec2(0.75, 0.75)};
  for (GridMapping g : mappings) {
    Particles particles = fill_box(block, 0.125, 1, 1000.0, false);
    for (Index p = 0; p < particles.size(); ++p)
      particles.velocity[p] = Vec2(std::sin(7.0 * particles.position[p].y()), std::cos(5.0 * particles.position[p].x()));
    MPMSolver solver(block_problem(), settings_for({MPMMethod::classic, 1}, UpdateScheme::usf, 8, g), std::move(particles));
    if (g == GridMapping::lumped) {
      for (int n = 0; n < 10; ++n) solver.step();
      CHECK(solver.time() > 0.0);
    } else {
      CHECK_THROWS_WITH(solver.step(), Catch::Contains("pseudo-inverse mapping") && Catch::Contains("use mapping = \"lumped\"") &&
                                           Catch::Contains("at t = "));
    }
  }
}

TEST_CASE(
    "MLS with the quadratic basis, the pseudo-inverse mapping and Verlet converges at 3 and beats plain "
    "B-splines",
    "[mpm][study]") {
  // u at T/4 on 8 and 16 cells (verification/mpm-vibration/README.md: 3.8e-4 and 4.3e-5,
  // against plain quadratic B-splines' 3.5e-3 and 1.2e-3).
  const Method mls{MPMMethod::bspline_mls, 2}, plain{MPMMethod::bspline, 2};
  const ParticleErrors coarse = quarter_period_errors(mls, 8, UpdateScheme::verlet, GridMapping::pseudo_inverse, RKOrder::quadratic);
  const ParticleErrors fine = quarter_period_errors(mls, 16, UpdateScheme::verlet, GridMapping::pseudo_inverse, RKOrder::quadratic);
  const double plain_coarse = quarter_period_errors(plain, 8).displacement, plain_fine = quarter_period_errors(plain, 16).displacement;
  const double rate = std::log2(coarse.displacement / fine.displacement);
  std::cout << fmt::format("quadratic MLS, pseudo-inverse, Verlet at T/4: u error {:.3e} -> {:.3e} (rate {:.2f}); plain "
                           "B-splines {:.3e} -> {:.3e}\n",
                           coarse.displacement, fine.displacement, rate, plain_coarse, plain_fine);
  CHECK(rate >= 2.8);
  CHECK(coarse.displacement < 0.2 * plain_coarse);
  CHECK(fine.displacement < 0.1 * plain_fine);
}

TEST_CASE("a time step over the Courant limit is refused unless allowed", "[mpm]") {
  MPMSettings s = settings_for({MPMMethod::bspline, 2}, UpdateScheme::usf, 16);
  const double limit = (1.0 / 16.0) / wave_speed(block_problem().materials.front().law, 1000.0);
  s.time_step = 1.2 * limit;
  const std::string what = testing::message_of<InputError>([&] { MPMSolver(block_problem(), s); });
  CHECK_THAT(what, Catch::Contains("above the Courant limit h / c"));
  CHECK_THAT(what, Catch::Contains("allow_unstable_time_step"));
  s.courant = 1.5;
  s.time_step.reset();
  CHECK_THAT(testing::message_of<InputError>([&] { MPMSolver(block_problem(), s); }), Catch::Contains("Courant factor 1.5"));
  s.allow_unstable_time_step = true;
  const MPMSolver allowed(block_problem(), s);
  CHECK(allowed.time_step() == Approx(1.5 * limit).epsilon(1e-3));
  s.courant = 0.5;
  s.time_step = 1e-5;
  CHECK(MPMSolver(block_problem(), s).time_step() <= 1e-5);
  // The consistent mass of the pseudo-inverse mapping lowers the limit (quadratic B-splines:
  // 0.35 h / c), and the message says so.
  s.allow_unstable_time_step = false;
  s.mapping = GridMapping::pseudo_inverse;
  s.time_step = 0.5 * limit;
  CHECK_THAT(testing::message_of<InputError>([&] { MPMSolver(block_problem(), s); }),
             Catch::Contains("above the Courant limit") && Catch::Contains("pseudo-inverse"));
  s.time_step.reset();
  CHECK(MPMSolver(block_problem(), s).courant_limit() == Approx(0.35 * limit).epsilon(1e-12));
}

TEST_CASE("a non-finite initial state is refused as an input, never stepped", "[mpm]") {
  const double h = 0.125;
  const Box block{Vec2(0.25, 0.25), Vec2(0.75, 0.75)};
  const Method bspline{MPMMethod::bspline, 2};
  // One particle's velocity is infinite: refused at once, naming it by its index and
  // reference position.
  Particles particles = fill_box(block, h, 2, 1000.0, false);
  particles.velocity[5] = Vec2(std::numeric_limits<double>::infinity(), 0.0);
  const std::string what = testing::message_of<InputError>(
      [&] { MPMSolver(block_problem(), settings_for(bspline, UpdateScheme::usf, 8), particles); });
  CHECK_THAT(what, Catch::Contains(
                       "MPM: particle 5 (started at (0.59375, 0.28125)) starts with a velocity that is not "
                       "finite") &&
                       !Catch::Contains("nan") && !Catch::Contains("inf"));
  // So is a finite one that crosses more than a cell per step (|v| dt / h = 2.4 at dt = 1e-4
  // s), unless the settings allow unstable steps.
  particles.velocity[5] = Vec2(3e3, 0.0);
  MPMSettings s = settings_for(bspline, UpdateScheme::usf, 8);
  s.time_step = 1e-4;
  CHECK_THAT(testing::message_of<InputError>([&] { MPMSolver(block_problem(), s, particles); }),
             Catch::Contains("particle 5 (started at (0.59375, 0.28125))") &&
                 Catch::Contains("|v| dt / h = 2.4 cells") &&
                 Catch::Contains("use time_step <= h / |v| = 4.17e-05 s"));
  s.allow_unstable_time_step = true;
  CHECK(MPMSolver(block_problem(), s, particles).time_step() == 1e-4);
}

TEST_CASE("a seeded body's initial velocity that no step can follow is refused at its key before the run",
          "[mpm]") {
  MPMProblem problem = block_problem();
  MPMBody& body = problem.bodies.front();
  body.bounds = {Vec2(0.25, 0.25), Vec2(0.75, 0.75)};
  body.contains = [b = body.bounds](const Vec2& x) { return b.contains(x); };
  body.velocity_where = "scene.toml:12:1: key 'body[0].velocity'";
  MPMSettings s = settings_for({MPMMethod::bspline, 2}, UpdateScheme::usf, 8);
  s.particles_per_side = 2;
  s.time_step = 1e-4;
  s.end_time = 0.005;
  // 1e200 m/s: h / |v| = 1.25e-201 s would take 4e198 steps: the advice is to lower it, not
  // to shorten the step.
  body.initial_velocity = [](const Vec2&) { return Vec2(1e200, 0.0); };
  std::string what = testing::message_of<InputError>([&] { MPMSolver(problem, s); });
  CHECK_THAT(what, Catch::Contains(
                       "scene.toml:12:1: key 'body[0].velocity': body 'block': the initial velocity at X = "
                       "(0.28125, 0.28125) is (1e+200, 0) m/s") &&
                       Catch::Contains("|v| dt / h = 8e+196 cells") && Catch::Contains("4e+198 steps") &&
                       Catch::EndsWith("lower the velocity") && !Catch::Contains("time_step <="));
  // Allowed unstable steps still refuse an overflowing kinetic energy.
  s.allow_unstable_time_step = true;
  what = testing::message_of<InputError>([&] { MPMSolver(problem, s); });
  CHECK_THAT(what, Catch::Contains("key 'body[0].velocity'") &&
                       Catch::Contains("kinetic energy 1/2 m |v|^2 overflows"));
}

TEST_CASE("the Courant number and the particle count are checked before a particle is seeded", "[mpm]") {
  // 1491 x 1491 cells of 9 particles: 2.0e7 particles, and time_step 5e-5 s is 8.6 times the
  // Courant limit h / c = 5.8e-6 s. The body's shape is never asked about a point: no
  // particle is seeded (nor, before that, any array of them allocated).
  MPMProblem problem = block_problem();
  long long asked = 0;
  problem.bodies.front().contains = [&asked](const Vec2&) {
    ++asked;
    return true;
  };
  MPMSettings s = settings_for({MPMMethod::bspline, 2}, UpdateScheme::usf, 1491);
  s.particles_per_side = 3;
  s.time_step = 5e-5;
  CHECK_THAT(testing::message_of<InputError>([&] { MPMSolver(problem, s); }),
             Catch::Contains("time_step 5e-05 s is above the Courant limit h / c = 5.781e-06 s"));
  CHECK(asked == 0);
  // A step count past the limit, and more particles than an Index holds: refused alike.
  s.time_step.reset();
  s.end_time = 1e6;
  CHECK_THAT(testing::message_of<InputError>([&] { MPMSolver(problem, s); }),
             Catch::Contains("more than the 1e+09"));
  s.end_time = 1.0;
  s.cells = 10000;  // 2.5e9 particles (or, on a small machine, a grid beyond its memory)
  s.particles_per_side = 5;
  CHECK_THAT(testing::message_of<InputError>([&] { MPMSolver(problem, s); }),
             Catch::Contains("a problem may have") || Catch::Contains("GiB of memory"));
  CHECK(asked == 0);
}

TEST_CASE("an inverted particle stops the run with its index, reference position, the time and the cause",
          "[mpm]") {
  // Two halves of a block rushing into each other with the one-term update dF = I + dt L
  // (dt = 1e-4 s, within the Courant limit h / c = 1.08e-3 s): at 1200 m/s each (|v| dt =
  // 0.96 h, within a cell per step) dt |L| = 1.06 > 1 at the interface inverts the particles
  // next to it in the first step. The first of them in index order is named, with every
  // thread count: the particle left of the interface in the bottom row.
  const Box left{Vec2(0.25, 0.25), Vec2(0.5, 0.75)}, right{Vec2(0.5, 0.25), Vec2(0.75, 0.75)};
  MPMProblem problem = block_problem();
  problem.bodies = {rectangle_body("left", left), rectangle_body("right", right)};
  const auto rushing = [&](double speed, double dt) {
    problem.bodies[0].initial_velocity = [speed](const Vec2&) { return Vec2(speed, 0.0); };
    problem.bodies[1].initial_velocity = [speed](const Vec2&) { return Vec2(-speed, 0.0); };
    MPMSettings s = settings_for({MPMMethod::bspline, 2}, UpdateScheme::usf, 8);
    s.particles_per_side = 2;
    s.deformation_terms = 1;
    s.time_step = dt;
    s.allow_unstable_time_step = true;  // lets |v| dt > h through, for the second case
    MPMSolver solver(problem, s);
    return testing::message_of<NumericalError>([&] {
      for (int n = 0; n < 10; ++n) solver.step();
    });
  };
  const int threads = omp_get_max_threads();
  for (int t : {1, std::max(2, threads)}) {
    omp_set_num_threads(t);
    const std::string what = rushing(1200.0, 1e-4);
    INFO(t << " threads: " << what);
    CHECK_THAT(what, Catch::StartsWith("MPM: particle 3 (started at (0.46875, 0.28125)) has J = det F = ") &&
                         Catch::Contains("<= 0 at t = 0 s") && Catch::Contains("dt |L| = 1.0") &&
                         Catch::Contains("the time step is too long for this rate of deformation") &&
                         !Catch::Contains("nan"));
  }
  omp_set_num_threads(threads);
  // At 3000 m/s (2.4 cells per step, allowed) the particle's own speed is named as the cause.
  CHECK_THAT(rushing(3e3, 1e-4), Catch::Contains("(started at (") &&
                                     Catch::Contains("it moves |v| dt / h = 2.4 cells per step") &&
                                     Catch::Contains("too long for its velocity") && !Catch::Contains("nan"));
}

TEST_CASE("a body force that is not finite stops the run at its key, naming the particle", "[mpm]") {
  MPMProblem problem = block_problem();  // 3 x 3 particles per cell of the unit box, 8 x 8 cells
  problem.body_force = [](const Vec2& X, double t) {
    return t > 0.0 && X.y() > 0.5 ? Vec2(std::nan(""), 0.0) : Vec2(0.0, -9.81);
  };
  problem.body_force_where = "scene.toml:20:1: key 'mpm.gravity'";
  MPMSolver solver(problem, settings_for({MPMMethod::bspline, 2}, UpdateScheme::usf, 8));
  const std::string what = testing::message_of<InputError>([&] { solver.step(); });
  // 3 x 3 particles per cell, 24 per row, row by row: the first above y = 0.5 starts row 12.
  CHECK_THAT(what, Catch::StartsWith(
                       "scene.toml:20:1: key 'mpm.gravity': the body force at particle 288 (started at "
                       "(0.0208333, 0.520833)) is not finite at t = ") &&
                       !Catch::Contains("nan"));
}

TEST_CASE("a J2 block carries each particle's history: every method and scheme updates it where the stress is",
          "[mpm][plasticity]") {
  // The uniform-strain motion of the test above on a J2 block that starts with a plastic
  // history (every particle the state of F = diag(1.01, 0.99) from the virgin one, then unloaded
  // to F = I). Interior particles see the velocity gradient L exactly, so their state and stress
  // after one step are those of the material-point update of F = dF(dt L) from that history
  // (USAVG: two updates, at dF(dt L / 2) and at its square; Verlet: of the midpoint gradient
  // L (I + dt L / 2)^-1, as in the uniform-strain test).
  AffineBlock motion;
  motion.v0 = Vec2::Zero();
  const Mat2& L = motion.L;
  J2Plasticity j2;
  j2.lame = lame_constants(1e7, 0.3);
  j2.yield_stress = 1e4;
  j2.isotropic_modulus = 1e5;
  const Material law = j2;
  const MaterialState<2> history =
      update(law, Mat2(Eigen::Vector2d(1.01, 0.99).asDiagonal()), {}, false).state;
  REQUIRE(history.alpha > 0.0);
  const MPMProblem problem{unit, {{"metal", law, 1000.0}}, {rectangle_body("block", unit)}, {}};
  for (const Method& m : methods)
    for (UpdateScheme s : schemes) {
      Particles start = motion.particles(uses_domains(m.method));
      for (MaterialState<2>& state : start.state) state = history;
      MPMSolver solver(problem, settings_for(m, s, 64), start);
      solver.step();
      const double dt = solver.time_step();
      auto series = [](const Mat2& A) { return Mat2(Mat2::Identity() + A + 0.5 * A * A); };
      MaterialState<2> state = history;
      Mat2 f = s == UpdateScheme::verlet ? series(dt * L * Mat2(Mat2::Identity() + 0.5 * dt * L).inverse()) : series(dt * L);
      if (s == UpdateScheme::usavg) {
        state = update(law, series(0.5 * dt * L), state, false).state;
        f = series(0.5 * dt * L) * series(0.5 * dt * L);
      }
      const MaterialUpdate<2> expected = update(law, f, state, false);
      const Mat2 sigma = cauchy_stress(law, expected.stress, f);
      const Particles& P = solver.particles();
      double worst_stress = 0.0, worst_state = 0.0;
      for (Index p = 0; p < P.size(); ++p) {
        if (!motion.interior(start.position[p])) continue;
        worst_stress = std::max(worst_stress, (P.stress[p] - sigma).norm() / sigma.norm());
        worst_state = std::max({worst_state, std::abs(P.state[p].alpha - expected.state.alpha) / expected.state.alpha,
                                (P.state[p].plastic_strain - expected.state.plastic_strain).norm() /
                                    expected.state.plastic_strain.norm()});
      }
      INFO(to_string(m.method) << " degree " << m.degree << " " << to_string(s) << ": stress " << worst_stress
                               << ", state " << worst_state);
      CHECK(worst_stress <= 1e-10);
      CHECK(worst_state <= 1e-10);
    }
}

TEST_CASE("CPDI2's corners: seeded from the domains, required on resume, a corner leaving the grid named with the time",
          "[mpm]") {
  const double h = 0.125;
  const Box block{Vec2(0.25, 0.25), Vec2(0.75, 0.75)};
  const MPMSettings cpdi2 = settings_for({MPMMethod::cpdi2, 1}, UpdateScheme::usf, 8);
  MPMSolver solver(block_problem(), cpdi2, fill_box(block, h, 2, 1000.0, true));
  const Particles& P = solver.particles();
  REQUIRE(P.corners.size() == P.mass.size());
  CHECK(P.corners[0][0] == Vec2(0.25, 0.25));  // the corner (-l_x, -l_y) of the first particle
  CHECK(P.corners[0][2] == Vec2(0.3125, 0.3125));
  // A saved state without corners, and corners for a method that does not track them.
  Particles without = P;
  without.corners.clear();
  CHECK_THROWS_WITH(solver.resume(without, 0.0, {0.0}), Catch::Contains("cpdi2 needs the domain corners of all 64 particles"));
  Particles with = fill_box(block, h, 2, 1000.0, true);
  with.corners.assign(with.mass.size(), DomainCorners{});
  CHECK_THROWS_WITH(MPMSolver(block_problem(), settings_for({MPMMethod::cpdi, 1}, UpdateScheme::usf, 8), with),
                    Catch::Contains("method cpdi does not track domain corners"));
  // A block flying right across the open wall: a corner leaves the padded grid first (at
  // x > 1.125), before any particle position does.
  Particles flying = fill_box(Box{Vec2(0.75, 0.25), Vec2(1.0, 0.75)}, h, 2, 1000.0, true);
  flying.velocity.assign(flying.mass.size(), Vec2(100.0, 0.0));
  MPMSolver away(block_problem(), cpdi2, std::move(flying));
  std::string what;
  try {
    for (int n = 0; n < 1000; ++n) away.step();
  } catch (const NumericalError& e) {
    what = e.what();
  }
  CHECK_THAT(what,
             Catch::StartsWith("MPM: particle ") && Catch::Contains("): its CPDI2 domain corner ") &&
                 Catch::Contains("left the grid [-0.125, 1.125] x [-0.125, 1.125] in the step to t = ") &&
                 Catch::Contains("to (1.1") && Catch::Contains("the body reached the edge of the grid"));
}

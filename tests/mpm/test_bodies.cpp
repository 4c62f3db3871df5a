// Bodies in the grid box: seeding (whole cells as fill_box, curved shapes to the sub-cell),
// the errors for bodies that cannot be seeded, per-particle materials in the stress update,
// the time step and the energy; walls per side; grid damping.

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/mpm/body.hpp"
#include "mfree/mpm/mpm_solver.hpp"

using namespace mfree;

namespace {

const Box unit{Vec2(0.0, 0.0), Vec2(1.0, 1.0)};

MPMBody circle(const std::string& name, const Vec2& c, double r) {
  MPMBody b;
  b.name = name;
  b.shape = Shape::circle;
  b.bounds = {c - Vec2(r, r), c + Vec2(r, r)};
  b.contains = [c, r](const Vec2& x) { return (x - c).squaredNorm() <= r * r; };
  b.where = "key '" + name + "'";
  return b;
}

const std::vector<MPMMaterial> rubber{{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}};

}  // namespace

TEST_CASE("a body of whole cells is seeded as fill_box fills it, particle for particle", "[mpm]") {
  const double h = 0.125;
  const Box block{Vec2(0.25, 0.375), Vec2(0.75, 0.875)};
  const Particles seeded = seed_bodies({rectangle_body("block", block)}, rubber, unit, h, 3, true);
  const Particles filled = fill_box(block, h, 3, 1000.0, true);
  REQUIRE(seeded.size() == filled.size());
  CHECK(seeded.size() == 4 * 4 * 9);
  for (Index p = 0; p < seeded.size(); ++p) {
    CHECK(seeded.reference[p] == filled.reference[p]);
    CHECK(seeded.mass[p] == filled.mass[p]);
    CHECK(seeded.half_size[p] == filled.half_size[p]);
  }
}

TEST_CASE("a disk is seeded at the sub-cell centres inside it, with its material and velocity", "[mpm]") {
  const double h = 0.05, r = 0.2, rho = 1000.0;
  std::vector<MPMMaterial> materials{rubber.front(), {"steel", make_material("plane_strain", 2e11, 0.3), 7800.0}};
  MPMBody lower = circle("lower", Vec2(0.2, 0.2), r), upper = circle("upper", Vec2(0.8, 0.8), r);
  lower.initial_velocity = [](const Vec2& X) { return Vec2(X.y(), -X.x()); };
  upper.material = 1;
  upper.particles_per_side = 3;
  const Particles P = seed_bodies({lower, upper}, materials, unit, h, 2, false);
  double mass[2] = {0.0, 0.0};
  Index count[2] = {0, 0};
  for (Index p = 0; p < P.size(); ++p) {
    const int b = P.body[p];
    CHECK(P.material[p] == b);
    CHECK((P.reference[p] - (b == 0 ? Vec2(0.2, 0.2) : Vec2(0.8, 0.8))).norm() <= r);
    CHECK(P.velocity[p] == (b == 0 ? Vec2(P.reference[p].y(), -P.reference[p].x()) : Vec2::Zero()));
    mass[b] += P.mass[p];
    ++count[b];
  }
  // The seeded area is the disk's to about perimeter x (sub-cell size) / 2.
  const double area = M_PI * r * r, perimeter = 2 * M_PI * r;
  CHECK(std::abs(mass[0] / rho - area) <= perimeter * h / 4);
  CHECK(std::abs(mass[1] / 7800.0 - area) <= perimeter * h / 6);
  CHECK(std::abs(mass[0] / rho - area) >= 1e-6);  // not a whole number of sub-cells: the test can fail
  CHECK(count[1] > count[0]);                      // 9 per cell against 4
}

TEST_CASE("bodies that cannot be seeded are refused naming the body", "[mpm]") {
  const auto error = [](const std::vector<MPMBody>& bodies) {
    return testing::message_of<InputError>([&] { (void)seed_bodies(bodies, rubber, unit, 0.1, 2, false); });
  };
  CHECK_THAT(error({circle("a", Vec2(0.3, 0.3), 0.2), circle("b", Vec2(0.5, 0.5), 0.2)}),
             Catch::Contains("key 'b'") && Catch::Contains("overlaps body 'a'"));
  CHECK(error({circle("a", Vec2(0.25, 0.25), 0.2), circle("b", Vec2(0.75, 0.75), 0.2)}) == "<nothing thrown>");
  CHECK_THAT(error({circle("a", Vec2(0.9, 0.5), 0.2)}),
             Catch::Contains("key 'a'") && Catch::Contains("reaches outside the grid box"));
  // Between the sub-cell centres (spacing 0.05, at 0.025 + 0.05 k): no particle.
  CHECK_THAT(error({circle("tiny", Vec2(0.5, 0.5), 0.01)}),
             Catch::Contains("key 'tiny'") && Catch::Contains("gets no particles"));
  MPMBody dense = circle("dense", Vec2(0.5, 0.5), 0.2);
  dense.particles_per_side = 6;
  CHECK_THAT(error({dense}), Catch::Contains("key 'dense'") && Catch::Contains("1 to 5 particles per cell side"));
}

TEST_CASE("every body is checked before any is seeded; a non-finite initial velocity is refused at its key",
          "[mpm]") {
  // The second body reaches outside the box: refused before the first one's shape is asked
  // about a single point (no particle seeded).
  long long asked = 0;
  MPMBody first = circle("first", Vec2(0.3, 0.3), 0.2);
  first.contains = [&asked](const Vec2& x) {
    ++asked;
    return (x - Vec2(0.3, 0.3)).squaredNorm() <= 0.04;
  };
  const MPMBody outside = circle("outside", Vec2(0.9, 0.9), 0.2);
  CHECK_THAT(testing::message_of<InputError>([&] {
               (void)seed_bodies({first, outside}, rubber, unit, 0.1, 2, false);
             }),
             Catch::Contains("key 'outside'") && Catch::Contains("reaches outside the grid box"));
  CHECK(asked == 0);
  // So are more particles than an Index holds (h = 1e-5: 1e10 sub-cells x 4 in the first).
  CHECK_THAT(
      testing::message_of<InputError>([&] { (void)seed_bodies({first}, rubber, unit, 1e-5, 2, false); }),
      Catch::Contains("key 'first'") && Catch::Contains("more than the 2147483647 a problem may have"));
  CHECK(asked == 0);
  // An initial velocity that is not finite names the velocity's key, the body and X.
  MPMBody fast = circle("fast", Vec2(0.5, 0.5), 0.2);
  fast.velocity_where = "scene.toml:9:1: key 'body[0].velocity'";
  fast.initial_velocity = [](const Vec2& X) {
    return Vec2(X.x() > 0.6 ? std::numeric_limits<double>::infinity() : 1.0, 0.0);
  };
  const std::string what =
      testing::message_of<InputError>([&] { (void)seed_bodies({fast}, rubber, unit, 0.1, 2, false); });
  CHECK_THAT(what, Catch::Contains(
                       "scene.toml:9:1: key 'body[0].velocity': body 'fast': the initial velocity at X = "
                       "(0.625, 0.375)") &&
                       Catch::Contains("not a finite number"));
  // The solver's check sees every particle as it is seeded, in order.
  std::vector<Vec2> seen;
  fast.initial_velocity = [](const Vec2&) { return Vec2(1.0, 2.0); };
  const Particles P =
      seed_bodies({fast}, rubber, unit, 0.1, 2, false, [&](const MPMBody& b, const Vec2& X, const Vec2& v) {
        CHECK(b.name == "fast");
        CHECK(v == Vec2(1.0, 2.0));
        seen.push_back(X);
      });
  REQUIRE(seen.size() == static_cast<std::size_t>(P.size()));
  for (Index p = 0; p < P.size(); ++p) CHECK(seen[p] == P.reference[p]);
}

TEST_CASE("each particle's own material sets its stress, its strain energy and the time step", "[mpm]") {
  // A uniform-strain motion v = L x of a free block, half soft and half stiff (the test of
  // test_mpm_solver.cpp): interior particles see L exactly, so after one step every particle
  // has F = I + dt L + (dt L)^2 / 2 and the stress of its own law.
  const double h = 1.0 / 32.0;
  const std::vector<MPMMaterial> two{{"soft", make_material("neo_hookean", 1e6, 0.3), 1000.0},
                                     {"stiff", make_material("neo_hookean", 1e8, 0.2), 4000.0}};
  Particles P = fill_box(Box{Vec2(2 * h, 2 * h), Vec2(30 * h, 30 * h)}, h, 2, 1000.0, false);
  Mat2 L;
  L << 0.3, 0.2, -0.1, 0.25;
  for (Index p = 0; p < P.size(); ++p) {
    P.velocity[p] = L * P.position[p];
    P.material[p] = P.body[p] = P.position[p].x() < 0.5 ? 0 : 1;
    if (P.material[p] == 1) P.mass[p] *= 4.0;  // the stiff material's density
  }
  MPMSettings s;
  s.method = MPMMethod::bspline;
  s.cells = 32;
  s.end_time = 1.0;
  MPMSolver solver({unit, two, {}, {}}, s, P);
  const double c_stiff = wave_speed(two[1].law, two[1].density);
  CHECK(c_stiff > wave_speed(two[0].law, two[0].density));
  CHECK(solver.courant_limit() == Approx(h / c_stiff).epsilon(1e-14));
  solver.step();
  const double dt = solver.time_step();
  const Mat2 F = Mat2::Identity() + dt * L + 0.5 * dt * dt * L * L;
  int checked[2] = {0, 0};
  for (Index p = 0; p < solver.particles().size(); ++p) {
    const Vec2 X = solver.particles().reference[p];
    // Away from the free edges, and from the interface: there the grid velocity, a mass-
    // weighted average, is no longer the linear field (the masses jump by 4).
    if ((X - Vec2(0.5, 0.5)).cwiseAbs().maxCoeff() > 0.25 || std::abs(X.x() - 0.5) < 3 * h) continue;
    const int m = solver.particles().material[p];
    INFO("particle " << p << " of material " << m);
    CHECK((solver.particles().deformation[p] - F).cwiseAbs().maxCoeff() <= 1e-13);
    CHECK((solver.particles().stress[p] - cauchy_stress(two[m].law, F)).norm() <=
          1e-9 * cauchy_stress(two[m].law, F).norm());
    ++checked[m];
  }
  CHECK(checked[0] > 100);
  CHECK(checked[1] > 100);
  // Strain energy per body: each with its own law; the total is their sum.
  const MPMEnergy e = solver.energy();
  REQUIRE(e.bodies.size() == 2);
  double strain[2] = {0.0, 0.0};
  for (Index p = 0; p < solver.particles().size(); ++p)
    strain[solver.particles().body[p]] += solver.particles().volume0[p] *
                                          energy(two[solver.particles().material[p]].law, solver.particles().deformation[p]);
  CHECK(e.bodies[0].strain == Approx(strain[0]).epsilon(1e-12));
  CHECK(e.bodies[1].strain == Approx(strain[1]).epsilon(1e-12));
  CHECK(e.bodies[1].strain > 50 * e.bodies[0].strain);  // E differs by 100
  CHECK(e.sum.strain == Approx(strain[0] + strain[1]).epsilon(1e-12));
}

TEST_CASE("walls hold per side: slip the normal component, fixed both, open none", "[mpm]") {
  const Grid grid(unit, 4, 2, 0);  // 6 x 6 quadratic B-spline nodes, walls at 0 and 1
  const std::vector<unsigned char> mask = grid.wall_mask({Wall::fixed, Wall::slip, Wall::open, Wall::slip});
  int x_held = 0, y_held = 0;
  for (Index n = 0; n < grid.size(); ++n) {
    const Vec2 x = grid.node(n);
    const bool left = x.x() == 0.0, right = x.x() == 1.0, top = x.y() == 1.0;
    CHECK(bool(mask[n] & 1) == (left || right));
    CHECK(bool(mask[n] & 2) == (left || top));
    x_held += mask[n] & 1;
    y_held += (mask[n] & 2) / 2;
  }
  CHECK(x_held == 12);
  CHECK(y_held == 11);
  CHECK(wall_names().value("fixed") == Wall::fixed);
  CHECK(wall_names().name(Wall::open) == "open");
  CHECK(side_names().names() == std::vector<std::string>{"left", "right", "bottom", "top"});
}

TEST_CASE("grid damping slows a rigid translation by exactly (1 - alpha dt) per step", "[mpm]") {
  // Free block, uniform velocity: f_i = 0, so (mv)_i <- (1 - alpha dt)(mv)_i and every
  // particle velocity follows.
  const double h = 0.125;
  Particles P = fill_box(Box{Vec2(0.25, 0.25), Vec2(0.75, 0.75)}, h, 2, 1000.0, false);
  P.velocity.assign(P.mass.size(), Vec2(0.5, -0.25));
  MPMSettings s;
  s.cells = 8;
  s.end_time = 0.01;
  s.damping = 20.0;
  MPMSolver solver({unit, rubber, {}, {}}, s, P);
  const int steps = 10;
  for (int n = 0; n < steps; ++n) solver.step();
  const double factor = std::pow(1.0 - s.damping * solver.time_step(), steps);
  for (const Vec2& v : solver.particles().velocity) CHECK((v - factor * Vec2(0.5, -0.25)).norm() <= 1e-14);
  CHECK(factor < 0.9);
  s.damping = -1.0;
  CHECK_THAT(testing::message_of<InputError>([&] { MPMSolver({unit, rubber, {}, {}}, s, P); }),
             Catch::Contains("damping"));
}

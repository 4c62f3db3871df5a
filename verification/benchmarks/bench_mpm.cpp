// Cost of one explicit MPM step against the method: the vibration problem of SPEC section 6
// (AxisAlignedVibration A = 0.05, L = 1, E = 1e7, nu = 0.3, rho0 = 1000; its body force and
// initial velocity), slip walls on all four sides, 64 x 64 cells, 9 particles per cell
// (36 864 particles), time step 1e-5 s: the setting of tests/mpm/test_mpm_solver.cpp's
// convergence study on a finer grid. The solver (grid, particles, weights) is built outside
// the timed loop; each benchmark iteration is one MPMSolver::step().
//
// One more run, mpm/bspline2/usf/no_body_force, leaves the body force out (same initial
// velocity; the motion is then no longer the manufactured solution): the vibration's body
// force is a closed form of six sines and cosines and a logarithm per particle, two thirds of
// the cost of the rest of a quadratic B-spline step, and this run measures the solver alone.
//
// mpm/bspline2/usf/j2: the same without the body force, the material a J2 law of the same
// elastic constants (logarithmic strain, sigma_y = 2e5 Pa, H_iso = 1e5 Pa: the vibration's
// stresses reach 1e6 Pa, so most steps of most particles are plastic), for the cost of a law
// with history against the Neo-Hookean one.
//
// The velocity Verlet update, the pseudo-inverse mapping (with and without the short-wave mass
// filter) and the quadratic MLS basis (the configuration of
// verification/mpm-vibration/mls.toml: filtered) have runs of their own, and so have the
// B-splines averaged over cpGIMP's domains (quadratic and cubic with USF; quadratic with Verlet
// and the pseudo-inverse, verification/mpm-vibration/bspline_cpgimp.toml).
//
// Counters: particle_steps_per_second (particles x steps / wall time), and the seconds per
// step of each stage of the solver's own StageTimer (weights, particles to grid, stress
// update, grid forces, grid momentum, grid to particles, second extrapolation; a stage the
// scheme does not run reads 0).
//
// Run as  OMP_NUM_THREADS={1,2} build/mfree_bench --benchmark_filter=mpm --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

#include "mfree/core/parallel.hpp"
#include "mfree/problems/axis_aligned_vibration.hpp"
#include "mfree/mpm/mpm_solver.hpp"

namespace {

using namespace mfree;

const char* const stages[] = {"weights",       "MLS functions",     "particles to grid", "stress update", "grid forces",
                              "grid momentum", "grid to particles", "second extrapolation"};

void BM_mpm_step(benchmark::State& state, MPMMethod method, int degree, UpdateScheme update, bool body_force,
                 bool j2 = false, GridMapping mapping = GridMapping::lumped,
                 RKOrder mls_basis = RKOrder::linear, double mass_filter = 0.0) {
  const AxisAlignedVibration v{0.05, 1.0, 1e7, 0.3, 1000.0};
  const Box unit{Vec2(0.0, 0.0), Vec2(1.0, 1.0)};
  MaterialParameters plastic;
  plastic.youngs_modulus = 1e7;
  plastic.poisson_ratio = 0.3;
  plastic.yield_stress = 2e5;
  plastic.isotropic_modulus = 1e5;
  const Material law = j2 ? make_material("j2", plastic) : v.material();
  MPMProblem problem{unit, {{"rubber", law, v.density}}, {rectangle_body("block", unit)}, {}};
  problem.bodies.front().initial_velocity = [v](const Vec2& X) { return v.velocity(X, 0.0); };
  if (body_force) problem.body_force = [v](const Vec2& X, double t) { return v.body_force(X, t); };
  MPMSettings s;
  s.method = method;
  s.degree = degree;
  s.update = update;
  s.mapping = mapping;
  s.mls_basis = mls_basis;
  s.mass_filter = mass_filter;
  s.cells = 64;
  s.particles_per_side = 3;
  // A whole period: dt = T / ceil(T / 1e-5) stays at the test's 1e-5 s, and the run never
  // nears end_time however many iterations the benchmark takes (the solver steps past it anyway).
  s.end_time = v.period();
  s.time_step = 1e-5;
  s.walls = {Wall::slip, Wall::slip, Wall::slip, Wall::slip};
  MPMSolver solver(problem, s);

  for (auto _ : state) solver.step();

  const double particles = solver.particles().size();
  state.counters["particle_steps_per_second"] =
      benchmark::Counter(particles * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  for (const char* stage : stages) {
    const auto& timed = solver.timer().stages();
    const auto it = std::find_if(timed.begin(), timed.end(), [&](const auto& entry) { return entry.first == stage; });
    std::string name(stage);
    std::replace(name.begin(), name.end(), ' ', '_');  // one column per stage in the tabular output
    state.counters[name] = benchmark::Counter(it == timed.end() ? 0.0 : it->second, benchmark::Counter::kAvgIterations);
  }
  state.counters["particles"] = particles;
  state.counters["threads"] = thread_count();
}

}  // namespace

BENCHMARK_CAPTURE(BM_mpm_step, classic, MPMMethod::classic, 2, UpdateScheme::usf, true)
    ->Name("mpm/classic/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, ugimp, MPMMethod::ugimp, 2, UpdateScheme::usf, true)
    ->Name("mpm/ugimp/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, cpgimp, MPMMethod::cpgimp, 2, UpdateScheme::usf, true)
    ->Name("mpm/cpgimp/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, cpdi, MPMMethod::cpdi, 2, UpdateScheme::usf, true)
    ->Name("mpm/cpdi/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, qcpdi, MPMMethod::qcpdi, 2, UpdateScheme::usf, true)
    ->Name("mpm/qcpdi/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, cpdi2, MPMMethod::cpdi2, 2, UpdateScheme::usf, true)
    ->Name("mpm/cpdi2/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_usf, MPMMethod::bspline, 2, UpdateScheme::usf, true)
    ->Name("mpm/bspline2/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_usl, MPMMethod::bspline, 2, UpdateScheme::usl, true)
    ->Name("mpm/bspline2/usl")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_szs, MPMMethod::bspline, 2, UpdateScheme::szs, true)
    ->Name("mpm/bspline2/szs")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_usavg, MPMMethod::bspline, 2, UpdateScheme::usavg, true)
    ->Name("mpm/bspline2/usavg")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_usf_free, MPMMethod::bspline, 2, UpdateScheme::usf, false)
    ->Name("mpm/bspline2/usf/no_body_force")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_usf_j2, MPMMethod::bspline, 2, UpdateScheme::usf, false, true)
    ->Name("mpm/bspline2/usf/j2")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline3, MPMMethod::bspline, 3, UpdateScheme::usf, true)
    ->Name("mpm/bspline3/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline_cpgimp2, MPMMethod::bspline_cpgimp, 2, UpdateScheme::usf, true)
    ->Name("mpm/bspline_cpgimp2/usf")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline_cpgimp3, MPMMethod::bspline_cpgimp, 3, UpdateScheme::usf, true)
    ->Name("mpm/bspline_cpgimp3/usf")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline_mls, MPMMethod::bspline_mls, 2, UpdateScheme::usf, true)
    ->Name("mpm/bspline_mls/usf")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_verlet, MPMMethod::bspline, 2, UpdateScheme::verlet, true)
    ->Name("mpm/bspline2/verlet")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, cpdi_verlet, MPMMethod::cpdi, 2, UpdateScheme::verlet, true)
    ->Name("mpm/cpdi/verlet")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_usf_pinv, MPMMethod::bspline, 2, UpdateScheme::usf, true, false,
                  GridMapping::pseudo_inverse)
    ->Name("mpm/bspline2/usf/pseudo_inverse")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline2_verlet_pinv, MPMMethod::bspline, 2, UpdateScheme::verlet, true, false,
                  GridMapping::pseudo_inverse)
    ->Name("mpm/bspline2/verlet/pseudo_inverse")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, bspline_cpgimp2_verlet_pinv, MPMMethod::bspline_cpgimp, 2,
                  UpdateScheme::verlet, true, false, GridMapping::pseudo_inverse)
    ->Name("mpm/bspline_cpgimp2/verlet/pseudo_inverse")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, cpdi_verlet_pinv, MPMMethod::cpdi, 2, UpdateScheme::verlet, true, false,
                  GridMapping::pseudo_inverse)
    ->Name("mpm/cpdi/verlet/pseudo_inverse")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, mls_quadratic, MPMMethod::bspline_mls, 2, UpdateScheme::verlet, true, false,
                  GridMapping::pseudo_inverse, RKOrder::quadratic)
    ->Name("mpm/bspline_mls_quadratic/verlet/pseudo_inverse")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_mpm_step, mls_quadratic_filtered, MPMMethod::bspline_mls, 2, UpdateScheme::verlet, true,
                  false, GridMapping::pseudo_inverse, RKOrder::quadratic, 0.3)
    ->Name("mpm/bspline_mls_quadratic/verlet/pseudo_inverse_filtered")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Stages of one elasticity solve at growing size: the Timoshenko cantilever (SPEC section 4,
// L = 48, D = 12, E = 3e7, nu = 0.3, P = 1000, plane stress) with our default scheme
// (linear RK, projected gradients with ratio 4, symmetric consistency correction): exact
// displacement imposed by Nitsche on x = 0, exact traction on x = L. Run as
//
//   OMP_NUM_THREADS=1 build/mfree_bench --benchmark_filter='cantilever/(35|112|250)/' --benchmark_counters_tabular=true
//
// The argument is the number n of node spacings across the depth: h = 12 / n, a vertex
// lattice of (4n + 1)(n + 1) nodes, 2 DOFs each (n = 35, 112, 250: 10^4, 10^5, 5 * 10^5
// DOFs) and n = 353 (10^6 DOFs: ~5 minutes and 19.4 GB peak on our 2-core, 23 GB machine;
// leave it out with --benchmark_filter='cantilever/(35|112|250)/').
//
// Counters: the seconds of every stage of the solver's StageTimer (spaces in the stage names
// become underscores), the DOFs and the relative L2 displacement error when measured. The
// independent error quadrature (6 x 6 Gauss points on cells of h/2, 144 points per node) is
// skipped from 5 * 10^5 DOFs on: at 10^5 DOFs it is already the costliest stage (a third of
// the run).

#include <benchmark/benchmark.h>

#include <algorithm>

#include "mfree/core/parallel.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/problems/timoshenko_beam.hpp"

namespace {

using namespace mfree;

constexpr double length = 48.0, depth = 12.0, load = 1000.0;
constexpr int error_limit = 250;  ///< n from which the error is not measured

void BM_cantilever_stages(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool krylov = state.range(1) == 1;
  const Domain domain = Domain::rectangle(Vec2(0.0, -0.5 * depth), Vec2(length, 0.5 * depth));
  ElasticitySettings s;
  s.scheme = QuadratureScheme::projected;
  s.nodes.spacing = depth / n;
  s.problem.material = LinearElastic{3.0e7, 0.3, PlaneModel::stress};
  const ExactElasticity exact = timoshenko_beam(length, depth, load, s.problem.material);
  s.problem.conditions = {
      {BoundaryCondition::Type::displacement, select_part(domain, "left"),
       [&](const Vec2& x, const Vec2&, double) { return exact.displacement(x); }, "x = 0"},
      {BoundaryCondition::Type::traction, select_part(domain, "right"),
       [&](const Vec2& x, const Vec2& normal, double) { return exact.traction(x, normal); }, "x = L"}};
  // The second argument: 0 direct solvers (CHOLMOD), 1 Krylov (CG + GAMG) for both the
  // stiffness and the node system of the consistency correction.
  if (krylov) s.solver.kind = SolverKind::cg;
  else s.solver.kind = SolverKind::cholmod;
  const bool with_error = n < error_limit;

  StageTimer stages;  // summed over the iterations
  double dofs = 0.0, error = 0.0;
  long iterations = 0, node_iterations = 0;
  for (auto _ : state) {
    const ElasticityResult r = solve_elasticity(domain, s, with_error ? &exact : nullptr);
    for (const auto& [name, seconds] : r.timer.stages()) stages.add(name, seconds);
    dofs = static_cast<double>(r.coefficients.size());
    if (r.errors) error = r.errors->l2_displacement;
    iterations = r.solver.statistics.iterations;
    node_iterations = r.correction_solver ? r.correction_solver->statistics.iterations : 0;
  }
  for (auto [name, seconds] : stages.stages()) {
    std::replace(name.begin(), name.end(), ' ', '_');
    state.counters[name] = benchmark::Counter(seconds, benchmark::Counter::kAvgIterations);
  }
  state.counters["dofs"] = dofs;
  if (with_error) state.counters["l2_error"] = error;
  state.counters["threads"] = thread_count();
  state.counters["iterations"] = static_cast<double>(iterations);
  state.counters["node_system_iterations"] = static_cast<double>(node_iterations);
}

}  // namespace

BENCHMARK(BM_cantilever_stages)->Name("cantilever")->ArgsProduct({{35, 112}, {0, 1}})->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_cantilever_stages)->Name("cantilever")->ArgsProduct({{250, 353}, {0, 1}})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

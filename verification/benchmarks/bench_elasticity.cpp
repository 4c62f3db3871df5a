// Stages of one elasticity solve at growing size: the Timoshenko cantilever (SPEC section 4,
// L = 48, D = 12, E = 3e7, nu = 0.3, P = 1000, plane stress), linear RK: exact displacement
// imposed by Nitsche on x = 0, exact traction on x = L. Run as
//
//   build/mfree_bench --benchmark_filter='cantilever/(35|112|250)/' --benchmark_counters_tabular=true
//
// Arguments n/solver/scheme:
//   n       node spacings across the depth: h = 12 / n, a vertex lattice of (4n + 1)(n + 1)
//           nodes, 2 DOFs each (n = 35, 112, 250, 353: 10^4, 10^5, 5 * 10^5, 10^6 DOFs)
//   solver  0 direct (CHOLMOD, or UMFPACK for VCI's non-symmetric stiffness), 1 Krylov (CG +
//           GAMG, or GMRES + GAMG) for the stiffness and the node system of the correction
//   scheme  0 projected gradients with ratio 4 and the symmetric correction, 1 the default
//           scheme: 3 x 3 Gauss points per cell with VCI
//
// Counters: the seconds of every stage of the solver's StageTimer (spaces in the stage names
// become underscores), the DOFs, the stiffness's nonzeros per row (its stencil: 2 x the nodes
// each node couples with), the Krylov iterations, and the relative L2 displacement error when measured. The
// independent error quadrature (4 x 4 Gauss points on cells of h/2, 64 points per node) is
// skipped from 5 * 10^5 DOFs on.

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
  const bool gauss = state.range(2) == 1;
  const Domain domain = Domain::rectangle(Vec2(0.0, -0.5 * depth), Vec2(length, 0.5 * depth));
  ElasticitySettings s;
  s.scheme = gauss ? QuadratureScheme::gauss_cells : QuadratureScheme::projected;
  s.nodes.spacing = depth / n;
  s.problem.material = LinearElastic{3.0e7, 0.3, PlaneModel::stress};
  const ExactElasticity exact = timoshenko_beam(length, depth, load, s.problem.material);
  s.problem.conditions = {
      {BoundaryCondition<2>::Type::displacement, select_part(domain, "left"),
       [&](const Vec2& x, const Vec2&, double) { return exact.displacement(x); }, "x = 0"},
      {BoundaryCondition<2>::Type::traction, select_part(domain, "right"),
       [&](const Vec2& x, const Vec2& normal, double) { return exact.traction(x, normal); }, "x = L"}};
  if (gauss) {
    s.solver.kind = krylov ? SolverKind::gmres : SolverKind::umfpack;
    s.solver.preconditioner = Preconditioner::gamg;
  } else {
    s.solver.kind = krylov ? SolverKind::cg : SolverKind::cholmod;
  }
  const bool with_error = n < error_limit;

  StageTimer stages;  // summed over the iterations
  double dofs = 0.0, error = 0.0, nonzeros = 0.0;
  long iterations = 0, node_iterations = 0;
  for (auto _ : state) {
    const ElasticityResult r = solve_elasticity(domain, s, with_error ? &exact : nullptr);
    for (const auto& [name, seconds] : r.timer.stages()) stages.add(name, seconds);
    dofs = static_cast<double>(r.coefficients.size());
    nonzeros = static_cast<double>(r.stiffness_nonzeros);
    if (r.errors) error = r.errors->l2_displacement;
    iterations = r.solver.statistics.iterations;
    node_iterations = r.correction_solver ? r.correction_solver->statistics.iterations : 0;
  }
  for (auto [name, seconds] : stages.stages()) {
    std::replace(name.begin(), name.end(), ' ', '_');
    state.counters[name] = benchmark::Counter(seconds, benchmark::Counter::kAvgIterations);
  }
  state.counters["dofs"] = dofs;
  state.counters["nonzeros_per_row"] = nonzeros / dofs;
  if (with_error) state.counters["l2_error"] = error;
  state.counters["threads"] = thread_count();
  state.counters["iterations"] = static_cast<double>(iterations);
  state.counters["node_system_iterations"] = static_cast<double>(node_iterations);
}

}  // namespace

BENCHMARK(BM_cantilever_stages)->Name("cantilever")->ArgsProduct({{35, 112}, {0, 1}, {0, 1}})->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_cantilever_stages)->Name("cantilever")->ArgsProduct({{250, 353}, {0, 1}, {0, 1}})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

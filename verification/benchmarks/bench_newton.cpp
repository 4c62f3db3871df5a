// Cost of one Newton iteration of the total-Lagrangian solver against problem size: the
// Neo-Hookean cantilever of verification/cantilever/large_deformation.toml (L = 48, D = 12,
// E = 3e7, nu = 0.3, plane strain) with Nitsche's clamp and the end shear at load factor 0.5,
// linear RK with projected gradients (ratio 4, symmetric consistency correction). Each
// benchmark iteration times the stages of one Newton iteration at a deformed state:
//
//   tangent    assembly of K(d) on the fixed pattern (domain + Nitsche terms)
//   factorise  UMFPACK numeric factorisation (the symbolic one is done once, outside)
//   solve      K delta = -R
//   residual   f_int(d) + f_c(d) - f_ext
//
// Run as  OMP_NUM_THREADS={1,2} build/mfree_bench --benchmark_filter=newton --benchmark_counters_tabular=true
// The argument n is the number of node spacings across the depth (h = 12 / n, (4n + 1)(n + 1)
// nodes, 2 DOFs each).

#include <benchmark/benchmark.h>

#include <chrono>

#include "mfree/core/parallel.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/problems/timoshenko_beam.hpp"
#include "mfree/galerkin/total_lagrangian.hpp"
#include "mfree/linalg/sparse_solver.hpp"

namespace {

using namespace mfree;

constexpr double length = 48.0, depth = 12.0, load = 3.0e6;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void BM_newton_iteration(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Domain domain = Domain::rectangle(Vec2(0.0, -0.5 * depth), Vec2(length, 0.5 * depth));
  ElasticitySettings s;
  s.scheme = QuadratureScheme::projected;
  s.nodes.spacing = depth / n;
  StageTimer timer;
  const Discretisation<2> disc = discretise(domain, s, timer);
  const LinearElastic linear{3.0e7, 0.3, PlaneModel::strain};
  const ExactElasticity exact = timoshenko_beam(length, depth, load, linear);
  SolidProblem<2> p;
  p.material = make_material("neo_hookean", 3.0e7, 0.3);
  p.spacing = s.nodes.spacing;
  p.conditions = {
      {BoundaryCondition<2>::Type::displacement, select_part(domain, "left"),
       [&](const Vec2& x, const Vec2&, double) { return exact.displacement(x); }, "x = 0"},
      {BoundaryCondition<2>::Type::traction, select_part(domain, "right"),
       [&](const Vec2& x, const Vec2& normal, double) { return exact.traction(x, normal); }, "x = L"}};
  const TotalLagrangian<2> model(p, domain, disc.node_count(), disc.quadrature, nullptr, disc.boundary,
                                 disc.at_boundary);
  // A deformed state: the small-strain solution at load factor 0.5 (rotations of ~0.2 rad).
  const LoadState at{0.5, 0.0};
  Eigen::VectorXd d(model.dofs());
  for (Index i = 0; i < disc.node_count(); ++i) d.segment<2>(2 * i) = 0.5 * exact.displacement(disc.nodes[i]);
  SparseMatrix k = model.zero_matrix();
  model.tangent(d, at, k);
  SparseSolver solver(SolverKind::umfpack);
  solver.analyze(k);

  double tangent = 0, factorise = 0, solve = 0, residual = 0;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    const Eigen::VectorXd r = model.internal_force(d) + model.boundary_force(d, at) - model.external_force(at);
    residual += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    model.tangent(d, at, k);
    tangent += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    solver.factorize(k);
    factorise += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(solver.solve(-r));
    solve += seconds_since(t0);
  }
  const auto avg = benchmark::Counter::kAvgIterations;
  state.counters["tangent"] = benchmark::Counter(tangent, avg);
  state.counters["factorise"] = benchmark::Counter(factorise, avg);
  state.counters["solve"] = benchmark::Counter(solve, avg);
  state.counters["residual"] = benchmark::Counter(residual, avg);
  state.counters["dofs"] = static_cast<double>(model.dofs());
  state.counters["nonzeros"] = static_cast<double>(k.nonZeros());
  state.counters["threads"] = thread_count();
}

}  // namespace

BENCHMARK(BM_newton_iteration)->Name("newton")->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kSecond)->UseRealTime();

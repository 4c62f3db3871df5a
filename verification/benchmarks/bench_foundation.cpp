// Throughput of the foundation stages: neighbour search (cell list against CGAL's
// kd-tree), RK shape function values + gradients (linear and quadratic), background
// lattice and quadrature weights. Run with 1 and 2 threads:
//
//   OMP_NUM_THREADS=1 build/mfree_bench --benchmark_counters_tabular=true
//   OMP_NUM_THREADS=2 build/mfree_bench --benchmark_counters_tabular=true
//
// Sizes: 10^4 to 10^6 points in the 2 x 1 rectangle, lattice spacing h, support radius
// 2 h (linear, ~13 neighbours on a lattice) and 3 h (quadratic, ~29 neighbours).
// Counters: items_per_second is points (searches, evaluations, quadrature points) per second.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Search_traits_2.h>
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>

#include "mfree/clouds/point_cloud.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/geometry/support_obstacles.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/quadrature/background_lattice.hpp"
#include "mfree/quadrature/rk_quadrature.hpp"
#include "mfree/search/cell_list.hpp"

namespace {

using namespace mfree;

const Domain& rectangle() {
  static const Domain d = Domain::rectangle(Vec2(-1.0, -0.5), Vec2(1.0, 0.5));
  return d;
}

/// A cell-centred lattice of about n points and its spacing h. (A struct, not a pair:
/// lambdas capture its members, where clang 14 cannot capture structured bindings.)
struct Cloud {
  std::vector<Vec2> points;
  double h;
};
Cloud cloud(std::int64_t n) {
  CloudSettings s;
  s.spacing = std::sqrt(2.0 / static_cast<double>(n));
  s.cell_centred = true;
  return {make_cloud(rectangle(), s), s.spacing};
}

/// Sum over points of count(i), the number of neighbours a search finds for point i, in parallel.
template <class Count>
std::size_t total_neighbours(Index n, Count&& count) {
  std::size_t found = 0;
  parallel_blocks(n, 4096, [&](Index b, Index e) {
    std::size_t local = 0;
    for (Index i = b; i < e; ++i) local += count(i);
#pragma omp atomic
    found += local;
  });
  return found;
}

void BM_search_cell_list(benchmark::State& state) {
  const Cloud c = cloud(state.range(0));
  const std::vector<Vec2>& points = c.points;
  const double h = c.h;
  for (auto _ : state) {
    const CellList<2> cells(points, 2.0 * h);
    const std::size_t found = total_neighbours(static_cast<Index>(points.size()), [&](Index i) {
      thread_local std::vector<Index> out;
      cells.within(points[i], 2.0 * h, out);
      return out.size();
    });
    benchmark::DoNotOptimize(found);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["threads"] = thread_count();
}

void BM_search_cgal_kdtree(benchmark::State& state) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Traits = CGAL::Search_traits_2<K>;
  using Tree = CGAL::Kd_tree<Traits>;
  using Sphere = CGAL::Fuzzy_sphere<Traits>;
  const Cloud c = cloud(state.range(0));
  const std::vector<Vec2>& points = c.points;
  const double h = c.h;
  std::vector<K::Point_2> p;
  for (const Vec2& x : points) p.emplace_back(x.x(), x.y());
  for (auto _ : state) {
    Tree tree(p.begin(), p.end());
    tree.build();
    // CGAL's tree is safe for concurrent queries once built.
    const std::size_t found = total_neighbours(static_cast<Index>(p.size()), [&](Index i) {
      thread_local std::vector<K::Point_2> out;
      out.clear();
      tree.search(std::back_inserter(out), Sphere(p[i], 2.0 * h, 0.0));
      return out.size();
    });
    benchmark::DoNotOptimize(found);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["threads"] = thread_count();
}

void BM_rk_value_gradient(benchmark::State& state) {
  const auto order = state.range(1) == 1 ? RKOrder::linear : RKOrder::quadratic;
  const Cloud c = cloud(state.range(0));
  const std::vector<Vec2>& nodes = c.points;
  const double h = c.h;
  RKSettings s;
  s.order = order;
  s.radius = (order == RKOrder::linear ? 2.0 : 3.0) * h;
  const RKShapeFunctions<2> rk(nodes, s);
  // Evaluation points: a lattice offset from the nodes, as many as nodes.
  std::vector<Vec2> x(nodes.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = nodes[i] + Vec2(0.31 * h, 0.17 * h);
  std::size_t neighbours = 0;
  for (auto _ : state) {
    std::size_t total = 0;
    rk.for_each(x, true, [&](Index, const ShapeValues<2>& v) {
      benchmark::DoNotOptimize(v.grad.data());
      if (v.size() == 0) std::abort();
    });
    ShapeValues<2> v;
    rk.evaluate(x[x.size() / 2], v);
    total = v.size();
    neighbours = total;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(x.size()));
  state.counters["neighbours"] = static_cast<double>(neighbours);
  state.counters["threads"] = thread_count();
}

/// RK values and gradients on a plate [-1, 1] x [-0.5, 0.5] with 12 cracks of length 0.3 in
/// a row, under each support rule (0 plain, 1 visibility, 2 geodesic): the cost of supports
/// that respect the domain. Counter `near` is the share of points with a crack within reach.
void BM_rk_supports_near_cracks(benchmark::State& state) {
  std::string wkt = "GEOMETRYCOLLECTION(POLYGON((-1 -0.5, 1 -0.5, 1 0.5, -1 0.5))";
  for (int c = 0; c < 12; ++c) {
    const double x = -0.9 + c * (1.8 / 11.0);
    wkt += fmt::format(", LINESTRING({} -0.15, {} 0.15)", x + 0.02, x - 0.02);
  }
  const Domain domain = Domain::from_wkt(wkt + ")");
  CloudSettings cs;
  cs.spacing = std::sqrt(2.0 / static_cast<double>(state.range(0)));
  const std::vector<Vec2> nodes = make_cloud(domain, cs);
  const double h = cs.spacing;
  RKSettings s;
  s.radius = 2.0 * h;
  s.rule = static_cast<SupportRule>(state.range(1));
  s.obstacles = std::make_shared<const SupportObstacles>(support_obstacles(domain, s.radius));
  const RKShapeFunctions<2> rk(nodes, s);
  std::vector<Vec2> x(nodes.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = nodes[i] + Vec2(0.31 * h, 0.17 * h);
  for (auto _ : state)
    rk.for_each(x, true, [&](Index, const ShapeValues<2>& v) { benchmark::DoNotOptimize(v.grad.data()); });
  const SupportPaths paths(*s.obstacles, SupportRule::visibility, s.radius);
  PathScratch scratch;
  std::size_t near = 0;
  for (const Vec2& p : x) near += paths.prepare(p, scratch);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(x.size()));
  state.SetLabel(std::string(to_string(s.rule)));
  state.counters["near"] = static_cast<double>(near) / static_cast<double>(x.size());
  state.counters["threads"] = thread_count();
}

void BM_quadrature_weights(benchmark::State& state) {
  const auto order = state.range(1) == 1 ? RKOrder::linear : RKOrder::quadratic;
  const Cloud c = cloud(state.range(0));
  const std::vector<Vec2>& points = c.points;
  const double h = c.h;
  RKSettings s;
  s.order = order;
  s.radius = (order == RKOrder::linear ? 2.0 : 3.0) * h;
  for (auto _ : state) {
    const RKShapeFunctions<2> rk(points, s);
    const BackgroundLattice<2> lattice(rectangle(), h / 2.0, order == RKOrder::linear ? 1 : 2);
    const std::vector<double> w = rk_quadrature_weights(rk, lattice);
    benchmark::DoNotOptimize(w.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["threads"] = thread_count();
}

}  // namespace

BENCHMARK(BM_search_cell_list)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_search_cgal_kdtree)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_rk_value_gradient)->ArgsProduct({{10000, 100000, 1000000}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_rk_supports_near_cracks)
    ->ArgsProduct({{10000, 100000}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_quadrature_weights)->ArgsProduct({{10000, 100000, 1000000}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();

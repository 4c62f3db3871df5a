// Cost of one material update per point: the Neo-Hookean law against J2 plasticity and
// Drucker–Prager (logarithmic strain), each on a batch of 4096 deformation gradients near a
// stretch of 2 % with a shear of 1 %, from virgin states (the J2 and Drucker–Prager steps are
// plastic: E = 1e7, sigma_y = 2e4 Pa; phi = 30 degrees, c = 100 Pa), with and without the
// consistent tangent (dual numbers of 4 derivatives for the plastic laws). One thread: the
// update is per point; the solvers call it from their threads.
//
// Counter: updates_per_second.
//
// Run as  build/mfree_bench --benchmark_filter=material --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "mfree/materials/material.hpp"

namespace {

using namespace mfree;

Material law(const std::string& model) {
  MaterialParameters p;
  p.youngs_modulus = 1e7;
  p.poisson_ratio = 0.3;
  p.yield_stress = 2e4;
  p.isotropic_modulus = 1e5;
  p.friction_angle = 30.0 * 3.14159265358979 / 180.0;
  p.cohesion = 100.0;
  return make_material(model, p);
}

void BM_material_update(benchmark::State& state, const std::string& model, bool with_tangent) {
  const Material m = law(model);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  std::vector<Mat2> f(4096);
  for (Mat2& x : f) x << 1.02 + u(rng), 0.01 + u(rng), u(rng), 0.99 + u(rng);
  const MaterialState<2> virgin;
  double sum = 0.0;
  for (auto _ : state)
    for (const Mat2& x : f) {
      const MaterialUpdate<2> r = update(m, x, virgin, with_tangent);
      sum += r.stress(0, 0) + r.tangent(0, 0);
    }
  benchmark::DoNotOptimize(sum);
  state.counters["updates_per_second"] =
      benchmark::Counter(static_cast<double>(f.size()) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK_CAPTURE(BM_material_update, neo_hookean, std::string("neo_hookean"), false)
    ->Name("material/neo_hookean")->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_material_update, j2, std::string("j2"), false)
    ->Name("material/j2")->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_material_update, drucker_prager, std::string("drucker_prager"), false)
    ->Name("material/drucker_prager")->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_material_update, neo_hookean_tangent, std::string("neo_hookean"), true)
    ->Name("material/neo_hookean/tangent")->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_material_update, j2_tangent, std::string("j2"), true)
    ->Name("material/j2/tangent")->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_material_update, drucker_prager_tangent, std::string("drucker_prager"), true)
    ->Name("material/drucker_prager/tangent")->Unit(benchmark::kMicrosecond)->UseRealTime();

#pragma once
// Meshfree quadrature weights from the RK functions of the quadrature cloud (seed 003):
//
//     w_K = integral over Omega of phi_K,
//
// phi_K built on the quadrature points x_K, the integral taken by the background lattice
// rule (trapezoid for linear RK, Simpson for quadratic; background_lattice.hpp). The
// rule sum_K w_K f(x_K) is then exact for linear functions (quadratic ones with quadratic
// RK) up to round-off, whatever the cloud.
//
// One computation serves the solver and the integration study: for_lattice_terms() takes the
// lattice sums over phi_K, and both rk_quadrature_weights() and the Galerkin solver's projected
// quadrature (galerkin/galerkin_quadrature.hpp: w_K, c_K and the projected gradients, in the
// same pass) add their terms through it.

#include <algorithm>
#include <vector>

#include "mfree/core/parallel.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/quadrature/background_lattice.hpp"

namespace mfree {

/// Lattice points per chunk of for_lattice_terms (bounds the memory of stored evaluations).
inline constexpr Index lattice_chunk = Index{1} << 15;

/// The lattice sums over the quadrature functions: for every point K and every lattice point
/// v with phi_K(v) != 0, in increasing v, term(K, v, local, c_v phi_K(v)). Lattice points are
/// taken in chunks of lattice_chunk; at_vertex(local, v) runs once for each point of a chunk,
/// in parallel, before the chunk's terms (to evaluate other functions there, stored by `local`,
/// the point's index in its chunk). The terms run in parallel over K, each K on one thread:
/// every sum over v is taken in one fixed order, so a run gives the same numbers bit for bit
/// on any number of threads.
template <int dim, class AtVertex, class Term>
void for_lattice_terms(const RKShapeFunctions<dim>& quadrature_functions,
                       const BackgroundLattice<dim>& lattice, AtVertex&& at_vertex, Term&& term) {
  const auto& lp = lattice.points();
  const auto& lc = lattice.weights();
  const Index nl = static_cast<Index>(lp.size());
  const Index nq = static_cast<Index>(quadrature_functions.nodes().size());
  std::vector<ShapeValues<dim>> phik(static_cast<std::size_t>(std::min(lattice_chunk, nl)));
  // K's terms from first[K]: the chunk's lattice point and its coefficient c_v phi_K(v),
  // computed here once and read by `term` from memory (so that no caller's compiler fuses
  // the product into its sums: every caller adds the same rounded coefficients).
  std::vector<Index> first(static_cast<std::size_t>(nq) + 1), term_vertex;
  std::vector<double> term_coefficient;
  for (Index v0 = 0; v0 < nl; v0 += lattice_chunk) {
    const Index v1 = std::min(nl, v0 + lattice_chunk);
    parallel_blocks(v1 - v0, 256, [&](Index b, Index e) {
      for (Index v = b; v < e; ++v) {
        quadrature_functions.evaluate(lp[v0 + v], phik[v], false);
        at_vertex(v, v0 + v);
      }
    });
    std::fill(first.begin(), first.end(), 0);
    for (Index v = 0; v < v1 - v0; ++v)
      for (Index k : phik[v].nodes) ++first[k + 1];
    for (Index k = 0; k < nq; ++k) first[k + 1] += first[k];
    term_vertex.resize(static_cast<std::size_t>(first[nq]));
    term_coefficient.resize(term_vertex.size());
    std::vector<Index> next(first.begin(), first.end() - 1);
    for (Index v = 0; v < v1 - v0; ++v)
      for (std::size_t a = 0; a < phik[v].size(); ++a) {
        const Index at = next[phik[v].nodes[a]]++;
        term_vertex[at] = v;
        term_coefficient[at] = lc[v0 + v] * phik[v].phi[a];
      }
    parallel_blocks(nq, 512, [&](Index b, Index e) {
      for (Index k = b; k < e; ++k)
        for (Index t = first[k]; t < first[k + 1]; ++t)
          term(k, v0 + term_vertex[t], term_vertex[t], term_coefficient[t]);
    });
  }
}

/// w_K for every point of `quadrature_functions` (for_lattice_terms); each lattice vertex is
/// evaluated once.
template <int dim>
std::vector<double> rk_quadrature_weights(const RKShapeFunctions<dim>& quadrature_functions,
                                          const BackgroundLattice<dim>& lattice);

/// Count and most negative value of the negative weights (quadratic RK makes some).
struct NegativeWeights {
  Index count = 0;
  double most_negative = 0.0;
};
NegativeWeights negative_weights(const std::vector<double>& weights);

}  // namespace mfree

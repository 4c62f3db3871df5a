#include "mfree/galerkin/galerkin_quadrature.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <numeric>
#include <optional>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/quadrature/rk_quadrature.hpp"

namespace mfree {

namespace {

/// Fills the CSR rows of q from per-point evaluations of `trial`, each row sorted by node
/// index so that row lookups elsewhere can bisect. Each block of points appends its rows to
/// arrays of its own (no allocation per point); the blocks are then copied into place.
template <int dim>
void fill_rows(const RKShapeFunctions<dim>& trial, GalerkinQuadrature<dim>& q, bool with_gradient) {
  const Index n = q.size();
  constexpr Index block = 1024;
  struct Rows {
    std::vector<Index> nodes;
    std::vector<double> phi;
    std::vector<Point<dim>> grad;
  };
  std::vector<Rows> blocks((n + block - 1) / block);
  q.offsets.assign(n + 1, 0);
  parallel_blocks(n, block, [&](Index begin, Index end) {
    Rows& out = blocks[begin / block];
    ShapeValues<dim> v;
    std::vector<Index> order;
    for (Index k = begin; k < end; ++k) {
      trial.evaluate(q.points[k], v, with_gradient);
      order.resize(v.size());
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](Index a, Index b) { return v.nodes[a] < v.nodes[b]; });
      for (Index a : order) {
        out.nodes.push_back(v.nodes[a]);
        out.phi.push_back(v.phi[a]);
        if (with_gradient) out.grad.push_back(v.grad[a]);
      }
      q.offsets[k + 1] = static_cast<Index>(v.size());
    }
  });
  for (Index k = 0; k < n; ++k) q.offsets[k + 1] += q.offsets[k];
  q.nodes.resize(q.offsets[n]);
  q.phi.resize(q.offsets[n]);
  q.grad.assign(q.offsets[n], Point<dim>::Zero());
  parallel_blocks(static_cast<Index>(blocks.size()), 1, [&](Index b, Index) {
    const Rows& in = blocks[b];
    const Index at = q.offsets[b * block];
    std::copy(in.nodes.begin(), in.nodes.end(), q.nodes.begin() + at);
    std::copy(in.phi.begin(), in.phi.end(), q.phi.begin() + at);
    std::copy(in.grad.begin(), in.grad.end(), q.grad.begin() + at);
  });
}

/// Puts v's entries in increasing node order (insertion sort: a support holds tens of nodes).
template <int dim>
void sort_by_node(ShapeValues<dim>& v) {
  for (std::size_t a = 1; a < v.size(); ++a) {
    const Index node = v.nodes[a];
    const double phi = v.phi[a];
    const Point<dim> grad = v.grad[a];
    std::size_t b = a;
    for (; b > 0 && v.nodes[b - 1] > node; --b) {
      v.nodes[b] = v.nodes[b - 1];
      v.phi[b] = v.phi[b - 1];
      v.grad[b] = v.grad[b - 1];
    }
    v.nodes[b] = node;
    v.phi[b] = phi;
    v.grad[b] = grad;
  }
}

}  // namespace

template <int dim>
GalerkinQuadrature<dim> sample_shape_functions(const RKShapeFunctions<dim>& trial,
                                               const std::vector<Point<dim>>& points, bool with_gradient) {
  GalerkinQuadrature<dim> q;
  q.points = points;
  q.weights.assign(points.size(), 1.0);
  q.centroids = points;
  fill_rows(trial, q, with_gradient);
  return q;
}

template <int dim>
GalerkinQuadrature<dim> direct_quadrature(const RKShapeFunctions<dim>& trial,
                                          const QuadratureRule<dim>& rule) {
  GalerkinQuadrature<dim> q;
  q.points = rule.points;
  q.weights = rule.weights;
  q.centroids = rule.points;
  fill_rows(trial, q, true);
  return q;
}

template <int dim>
GalerkinQuadrature<dim> projected_quadrature(const RKShapeFunctions<dim>& trial,
                                             const RKShapeFunctions<dim>& quadrature_functions,
                                             const BackgroundLattice<dim>& lattice) {
  GalerkinQuadrature<dim> q;
  q.points = quadrature_functions.nodes();
  const Index nq = q.size();

  // Rows: every node whose support can meet supp(phi_K): |x_I - x_K| < a_I + a_K for two
  // circular supports, the same in the max-norm when either is a square (a circle of radius a
  // lies in the square of half-width a). phi_I(x_K) where the node covers x_K, else 0.
  // The rows set the stiffness pattern: the circular test keeps it ~1.6x sparser.
  // Where supports respect the domain the distance is the path's in the domain (a path in
  // the domain joins the nodes of two supports that meet, under either rule): a node across an
  // interface or a crack is not in the row, so the symmetric correction's projector
  // (consistency.hpp) takes the linear fields of the nodes K sees, and a piecewise-linear field
  // stays exact.
  GalerkinQuadrature<dim> at_points = sample_shape_functions(trial, q.points, false);
  const double trial_max = trial.max_support_radius();
  const CellList<dim> node_cells(trial.nodes(), trial_max);
  const bool circular = trial.settings().support == SupportShape::circular &&
                        quadrature_functions.settings().support == SupportShape::circular;
  const std::shared_ptr<const SupportObstacles>& obstacles = trial.settings().obstacles;
  std::optional<SupportPaths> paths;  // plane clouds only (3D supports are plain)
  if (dim == 2 && trial.settings().rule != SupportRule::plain && obstacles && !obstacles->empty())
    paths.emplace(*obstacles, SupportRule::geodesic, trial_max + quadrature_functions.max_support_radius());
  std::vector<std::vector<Index>> row_nodes(nq);
  parallel_blocks(nq, 512, [&](Index b, Index e) {
    PathScratch scratch;
    Vec2 unused;
    for (Index k = b; k < e; ++k) {
      const double ak = quadrature_functions.support_radius(k);
      bool near_obstacles = false;
      if constexpr (dim == 2) near_obstacles = paths && paths->prepare(q.points[k], scratch);
      node_cells.for_each_in_box(q.points[k], ak + trial_max, [&](Index i, const Point<dim>& p) {
        const double reach = ak + trial.support_radius(i);
        const Point<dim> d = p - q.points[k];
        if (circular ? d.squaredNorm() >= reach * reach : d.cwiseAbs().maxCoeff() >= reach) return;
        if constexpr (dim == 2)
          if (near_obstacles && !(paths->distance(p, q.points[k], scratch, unused) < reach)) return;
        row_nodes[k].push_back(i);
      });
      std::sort(row_nodes[k].begin(), row_nodes[k].end());
    }
  });
  q.offsets.assign(nq + 1, 0);
  for (Index k = 0; k < nq; ++k) q.offsets[k + 1] = q.offsets[k] + static_cast<Index>(row_nodes[k].size());
  q.nodes.resize(q.offsets[nq]);
  q.phi.assign(q.offsets[nq], 0.0);
  q.grad.assign(q.offsets[nq], Point<dim>::Zero());
  for (Index k = 0; k < nq; ++k) {
    std::copy(row_nodes[k].begin(), row_nodes[k].end(), q.nodes.begin() + q.offsets[k]);
    for (Index s = at_points.offsets[k]; s < at_points.offsets[k + 1]; ++s) {
      const auto first = q.nodes.begin() + q.offsets[k], last = q.nodes.begin() + q.offsets[k + 1];
      const auto it = std::lower_bound(first, last, at_points.nodes[s]);
      q.phi[it - q.nodes.begin()] = at_points.phi[s];
    }
  }
  row_nodes = {};

  // The lattice sums (quadrature/rk_quadrature.hpp: for_lattice_terms, one fixed order on any
  // number of threads) w_K = sum_v c_v phi_K(v), w_K c_K = sum_v c_v phi_K(v) v and
  // row K = sum_v c_v phi_K(v) grad phi_I(v); grad phi_I evaluated once per lattice point.
  std::vector<double> w(nq, 0.0);
  std::vector<Index> missing(nq, 0);
  // Visibility supports or tied regions in a solid: the rows (found by straight distances) hold
  // nodes across a gap or an interface whose supports never meet K's in the solid; the slots no term reaches
  // are dropped below, so that a correction on the rows holding a node (VCI) stays on its side.
  const bool shadowed =
      (trial.settings().surface_obstacles && !trial.settings().surface_obstacles->empty()) ||
      trial.settings().region_of;
  std::vector<char> reached(shadowed ? q.nodes.size() : 0, 0);
  std::vector<Point<dim>> moment(nq, Point<dim>::Zero());
  const auto& lp = lattice.points();
  std::vector<ShapeValues<dim>> phii(
      static_cast<std::size_t>(std::min(lattice_chunk, static_cast<Index>(lp.size()))));
  // The trial functions at v in increasing node order, as the rows are: each term merges the
  // two lists (a slot of row K receives one term per v, so the sums keep their order).
  for_lattice_terms(
      quadrature_functions, lattice,
      [&](Index local, Index v) {
        trial.evaluate(lp[v], phii[local], true);
        sort_by_node(phii[local]);
      },
      [&](Index k, Index v, Index local, double c) {
        w[k] += c;
        moment[k] += c * lp[v];
        auto it = q.nodes.begin() + q.offsets[k];
        const auto row_last = q.nodes.begin() + q.offsets[k + 1];
        const ShapeValues<dim>& gi = phii[local];
        for (std::size_t i = 0; i < gi.size(); ++i) {
          while (it != row_last && *it < gi.nodes[i]) ++it;
          if (it == row_last || *it != gi.nodes[i]) {  // supports that meet off the row: see below
            ++missing[k];
            continue;
          }
          q.grad[static_cast<std::size_t>(it - q.nodes.begin())] += c * gi.grad[i];
          if (shadowed) reached[static_cast<std::size_t>(it - q.nodes.begin())] = 1;
        }
      });
  if (shadowed) {
    Index kept = 0;
    for (Index k = 0; k < nq; ++k) {
      const Index first = q.offsets[k];
      q.offsets[k] = kept;
      for (Index s = first; s < q.offsets[k + 1]; ++s)
        if (reached[s] || q.phi[s] != 0.0) {
          q.nodes[kept] = q.nodes[s];
          q.phi[kept] = q.phi[s];
          q.grad[kept] = q.grad[s];
          ++kept;
        }
    }
    q.offsets[nq] = kept;
    q.nodes.resize(kept);
    q.phi.resize(kept);
    q.grad.resize(kept);
  }
  for (Index k = 0; k < nq; ++k) {
    if (missing[k] > 0)
      throw NumericalError(fmt::format(
          "quadrature point {} at ({:.6g}): {} gradient term(s) of nodes whose supports meet its own "
          "though no path in the domain joins them within the two radii (the rows of the projected scheme "
          "missed them)",
          k, fmt::join(q.points[k].begin(), q.points[k].end(), ", "), missing[k]));
    if (!(w[k] > 0.0))
      throw NumericalError(
          fmt::format("quadrature point {} at ({:.6g}) has weight {:.3e} <= 0: its projected gradients "
                      "are undefined. Use a linear quadrature cloud, a more regular quadrature cloud, or a "
                      "larger quadrature support.",
                      k, fmt::join(q.points[k].begin(), q.points[k].end(), ", "), w[k]));
    for (Index s = q.offsets[k]; s < q.offsets[k + 1]; ++s) q.grad[s] /= w[k];
    moment[k] /= w[k];
  }
  q.weights = std::move(w);
  q.centroids = std::move(moment);
  return q;
}

template GalerkinQuadrature<2> sample_shape_functions(const RKShapeFunctions<2>&,
                                                      const std::vector<Point<2>>&, bool);
template GalerkinQuadrature<3> sample_shape_functions(const RKShapeFunctions<3>&,
                                                      const std::vector<Point<3>>&, bool);
template GalerkinQuadrature<2> direct_quadrature(const RKShapeFunctions<2>&, const QuadratureRule<2>&);
template GalerkinQuadrature<3> direct_quadrature(const RKShapeFunctions<3>&, const QuadratureRule<3>&);
template GalerkinQuadrature<2> projected_quadrature(const RKShapeFunctions<2>&, const RKShapeFunctions<2>&,
                                                    const BackgroundLattice<2>&);
template GalerkinQuadrature<3> projected_quadrature(const RKShapeFunctions<3>&, const RKShapeFunctions<3>&,
                                                    const BackgroundLattice<3>&);

}  // namespace mfree

#pragma once
// Reproducing-kernel (RK / moving least squares) shape functions on a cloud of nodes in
// dim = 2 or 3 dimensions (explicit instantiations in the .cpp file).
//
//   phi_I(x) = H(0)^T M(x)^-1 H(z_I) w_a(x - x_I),  z_I = (x - x_I) / a,
//   M(x)     = sum_I w_a(x - x_I) H(z_I) H(z_I)^T                      (SPEC section 1)
//
// with H the linear or quadratic basis of polynomial_basis.hpp, the window of
// window_function.hpp on a round support |x - x_I| < a (a disk, a ball) or a square (cubic)
// tensor-product support |x - x_I|_inf < a, where a is the support radius (length units). The basis is
// scaled by the same a, so M is O(1) and its conditioning measures the geometry of the
// neighbours alone. Nodes may carry their own radii a_I >= a (nodal_support_radii()):
// on irregular clouds, nodes next to a gap then reach across it.
//
// Gradients are exact derivatives of phi_I: grad(M^-1) = -M^-1 (grad M) M^-1.
//
// Supports may respect the domain (support_paths.hpp, plane clouds): the window then
// measures the distance d(x_I, x) along paths inside the domain, w(d / a_I), and a node
// whose path is blocked does not reach x. The basis keeps the straight offsets
// z_I = (x - x_I) / a. In three dimensions the rule is visibility (surface_visibility.hpp):
// a node whose segment to x crosses an obstacle triangle does not reach x, the others keep
// their plain windows.
//
// The same construction serves the Galerkin trial functions, the quadrature-cloud functions
// that define quadrature weights, and the MLS reconstruction of the MPM.

#include <cmath>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/core/types.hpp"
#include "mfree/kernels/polynomial_basis.hpp"
#include "mfree/kernels/support_paths.hpp"
#include "mfree/kernels/surface_visibility.hpp"
#include "mfree/kernels/window_function.hpp"
#include "mfree/search/cell_list.hpp"

namespace mfree {

enum class SupportShape {
  circular,  ///< |x - x_I| < a, window w(|x - x_I| / a) (a disk in 2D, a ball in 3D)
  tensor,    ///< |x - x_I|_inf < a, window w(|dx| / a) w(|dy| / a) [w(|dz| / a)]
};

struct RKSettings {
  RKOrder order = RKOrder::linear;
  Window window = Window::cubic_bspline;
  SupportShape support = SupportShape::circular;
  double radius = 0.0;       ///< support radius a > 0 (length units); basis scale
  /// Optional radius per node (empty: every node has `radius`). Each must be >= radius.
  std::vector<double> node_radii;
  double rcond_min = 1e-10;  ///< smallest accepted reciprocal condition number of M
  /// How supports respect the domain, and what they respect (none: every rule is plain).
  /// The geodesic rule needs circular supports; tensor supports take visibility only.
  SupportRule rule = SupportRule::plain;
  std::shared_ptr<const SupportObstacles> obstacles;          ///< plane clouds
  std::shared_ptr<const SurfaceObstacles> surface_obstacles;  ///< clouds in a solid: visibility only
  /// Clouds in a solid of tied regions (geometry/solid.hpp: interfaces()): the region of a
  /// point; the regions are separate bodies, a node reaches the points of its own region only
  /// (whatever the rule). Empty: one body.
  std::function<int(const Vec3&)> region_of;
};

/// The longest segment from a node to a point its support of radius a covers: a for a round
/// support, sqrt(dim) a for a square (cubic) one (the reach a visibility test must serve).
inline double support_reach(SupportShape shape, double radius, int dim) {
  return shape == SupportShape::circular ? radius : std::sqrt(static_cast<double>(dim)) * radius;
}

/// The number of terms of the basis of an order in dim dimensions (3, 6; 4, 10).
int rk_basis_size(int dim, RKOrder order);

/// Shape functions of every node whose support covers one point x.
/// phi[k], grad[k] belong to node nodes[k]; grad is empty when not asked for.
template <int dim>
struct ShapeValues {
  std::vector<Index> nodes;
  std::vector<double> phi;
  std::vector<Point<dim>> grad;
  std::vector<Point<dim>> z;  ///< scratch: scaled offsets (x - x_I) / a, kept to reuse the storage
  PathScratch paths;          ///< scratch of supports that respect the domain (plane clouds)
  VisibilityScratch shadows;  ///< the same in a solid
  [[nodiscard]] std::size_t size() const { return nodes.size(); }
};

template <int dim>
class RKShapeFunctions {
 public:
  using Point = mfree::Point<dim>;
  using Values = ShapeValues<dim>;

  /// Throws InputError for a non-positive radius, an empty cloud, the geodesic rule on
  /// tensor supports or in three dimensions, or obstacles of the other dimension.
  RKShapeFunctions(std::vector<Point> nodes, RKSettings settings);

  [[nodiscard]] const std::vector<Point>& nodes() const { return nodes_; }
  [[nodiscard]] const RKSettings& settings() const { return settings_; }
  [[nodiscard]] Index size() const { return static_cast<Index>(nodes_.size()); }
  /// Support radius a_I of node i (settings.node_radii[i], or settings.radius for all).
  [[nodiscard]] double support_radius(Index i) const {
    return settings_.node_radii.empty() ? settings_.radius : settings_.node_radii[i];
  }
  /// The largest a_I.
  [[nodiscard]] double max_support_radius() const { return max_radius_; }
  /// Number of basis terms (2D 3 or 6, 3D 4 or 10): the fewest neighbours a point can have.
  [[nodiscard]] int basis_size() const { return rk_basis_size(dim, settings_.order); }

  /// phi_I(x) and, if with_gradient, grad phi_I(x) for every node I covering x.
  /// Throws NumericalError naming the point, its neighbour count and what to change when
  /// M(x) is singular or its reciprocal condition number is below settings.rcond_min.
  void evaluate(const Point& x, Values& out, bool with_gradient = true) const;

  /// Evaluates at every point in parallel and calls visit(p, values) from the worker
  /// threads; visit must be safe to call concurrently for different p.
  template <class Visit>
  void for_each(std::span<const Point> points, bool with_gradient, Visit&& visit) const {
    parallel_blocks(static_cast<Index>(points.size()), 1024, [&](Index begin, Index end) {
      Values values;
      for (Index p = begin; p < end; ++p) {
        evaluate(points[p], values, with_gradient);
        visit(p, static_cast<const Values&>(values));
      }
    });
  }

 private:
  /// evaluate() at a point with obstacles near it: windows from the rule's distances.
  void evaluate_along_paths(const Point& x, Values& out, bool with_gradient) const;

  std::vector<Point> nodes_;
  RKSettings settings_;
  double max_radius_ = 0.0;
  CellList<dim> cells_;
  std::shared_ptr<const SupportPaths> paths_;            ///< null: plain supports (plane clouds)
  std::shared_ptr<const SurfaceVisibility> visibility_;  ///< null: plain supports (in a solid)
  std::vector<double> node_clearance_;  ///< per node: the distance to the nearest obstacle (in a solid)
  std::vector<int> node_region_;        ///< per node: its region (settings.region_of; else empty)
};

extern template class RKShapeFunctions<2>;
extern template class RKShapeFunctions<3>;

/// Radii a_I = factor * max(h, d_k(I)), d_k(I) the distance from node I to its k-th nearest
/// other node and h the nominal spacing: on a lattice (k = 4; 4 and 6 nearest
/// nodes at h in 2D and 3D) every a_I = factor * h; on an
/// irregular cloud nodes beside a gap get wider supports that cover it.
template <int dim>
std::vector<double> nodal_support_radii(const std::vector<Point<dim>>& nodes, double h, double factor,
                                        int k = 4);

/// Throws the NumericalError of a point x whose moment matrix is singular (rcond < 0 or NaN)
/// or has a reciprocal condition number below s.rcond_min: its n neighbours, the support and
/// what the user can change.
template <int dim>
[[noreturn]] void throw_moment_failure(const Point<dim>& x, std::size_t n, const RKSettings& s, double rcond);

/// linear, quadratic: the names scenes use.
const NameTable<RKOrder>& order_names();
std::string_view to_string(RKOrder order);
/// circular, tensor: the names scenes use.
const NameTable<SupportShape>& support_names();
std::string_view to_string(SupportShape shape);

}  // namespace mfree

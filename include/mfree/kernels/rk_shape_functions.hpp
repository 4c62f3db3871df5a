#pragma once
// Reproducing-kernel (RK / moving least squares) shape functions on a cloud of nodes.
//
//   phi_I(x) = H(0)^T M(x)^-1 H(z_I) w_a(x - x_I),  z_I = (x - x_I) / a,
//   M(x)     = sum_I w_a(x - x_I) H(z_I) H(z_I)^T                      (SPEC section 1)
//
// with H the linear or quadratic basis of polynomial_basis.hpp, the window of
// window_function.hpp on a circular support |x - x_I| < a or a square (tensor-product)
// support |x - x_I|_inf < a, where a is the support radius (length units). The basis is
// scaled by the same a, so M is O(1) and its conditioning measures the geometry of the
// neighbours alone. Nodes may carry their own radii a_I >= a (nodal_support_radii()):
// on irregular clouds, nodes next to a gap then reach across it.
//
// Gradients are exact derivatives of phi_I: grad(M^-1) = -M^-1 (grad M) M^-1.
//
// Supports may respect the domain (support_paths.hpp): the window then measures the
// distance d(x_I, x) along paths inside the domain, w(d / a_I), and a node whose path is
// blocked does not reach x. The basis keeps the straight offsets z_I = (x - x_I) / a.
//
// The same construction serves the Galerkin trial functions, the quadrature-cloud functions
// that define quadrature weights, and the MLS reconstruction of the MPM.

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
#include "mfree/kernels/window_function.hpp"
#include "mfree/search/cell_list.hpp"

namespace mfree {

enum class SupportShape {
  circular,  ///< |x - x_I| < a, window w(|x - x_I| / a)
  tensor,    ///< |x - x_I|_inf < a, window w(|dx| / a) w(|dy| / a)
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
  std::shared_ptr<const SupportObstacles> obstacles;
};

/// Shape functions of every node whose support covers one point x.
/// phi[k], grad[k] belong to node nodes[k]; grad is empty when not asked for.
struct ShapeValues {
  std::vector<Index> nodes;
  std::vector<double> phi;
  std::vector<Vec2> grad;
  std::vector<Vec2> z;  ///< scratch: scaled offsets (x - x_I) / a, kept to reuse the storage
  PathScratch paths;    ///< scratch of supports that respect the domain
  [[nodiscard]] std::size_t size() const { return nodes.size(); }
};

class RKShapeFunctions {
 public:
  /// Throws InputError for a non-positive radius, an empty cloud, or the geodesic rule on
  /// tensor supports.
  RKShapeFunctions(std::vector<Vec2> nodes, RKSettings settings);

  [[nodiscard]] const std::vector<Vec2>& nodes() const { return nodes_; }
  [[nodiscard]] const RKSettings& settings() const { return settings_; }
  [[nodiscard]] Index size() const { return static_cast<Index>(nodes_.size()); }
  /// Support radius a_I of node i (settings.node_radii[i], or settings.radius for all).
  [[nodiscard]] double support_radius(Index i) const {
    return settings_.node_radii.empty() ? settings_.radius : settings_.node_radii[i];
  }
  /// The largest a_I.
  [[nodiscard]] double max_support_radius() const { return max_radius_; }
  /// Number of basis terms (3 or 6): the fewest neighbours a point can have.
  [[nodiscard]] int basis_size() const { return settings_.order == RKOrder::linear ? 3 : 6; }

  /// phi_I(x) and, if with_gradient, grad phi_I(x) for every node I covering x.
  /// Throws NumericalError naming the point, its neighbour count and what to change when
  /// M(x) is singular or its reciprocal condition number is below settings.rcond_min.
  void evaluate(const Vec2& x, ShapeValues& out, bool with_gradient = true) const;

  /// Evaluates at every point in parallel and calls visit(p, values) from the worker
  /// threads; visit must be safe to call concurrently for different p.
  template <class Visit>
  void for_each(std::span<const Vec2> points, bool with_gradient, Visit&& visit) const {
    parallel_blocks(static_cast<Index>(points.size()), 1024, [&](Index begin, Index end) {
      ShapeValues values;
      for (Index p = begin; p < end; ++p) {
        evaluate(points[p], values, with_gradient);
        visit(p, static_cast<const ShapeValues&>(values));
      }
    });
  }

 private:
  /// evaluate() at a point with obstacles near it: windows from the rule's distances.
  void evaluate_along_paths(const Vec2& x, ShapeValues& out, bool with_gradient) const;

  std::vector<Vec2> nodes_;
  RKSettings settings_;
  double max_radius_ = 0.0;
  CellList<2> cells_;
  std::shared_ptr<const SupportPaths> paths_;  ///< null: plain supports
};

/// Radii a_I = factor * max(h, d_k(I)), d_k(I) the distance from node I to its k-th nearest
/// other node and h the nominal spacing: on a lattice (k = 4) every a_I = factor * h; on an
/// irregular cloud nodes beside a gap get wider supports that cover it.
std::vector<double> nodal_support_radii(const std::vector<Vec2>& nodes, double h, double factor,
                                        int k = 4);

/// Throws the NumericalError of a point x whose moment matrix is singular (rcond < 0 or NaN)
/// or has a reciprocal condition number below s.rcond_min: its n neighbours, the support and
/// what the user can change.
[[noreturn]] void throw_moment_failure(const Vec2& x, std::size_t n, const RKSettings& s, double rcond);

/// linear, quadratic: the names scenes use.
const NameTable<RKOrder>& order_names();
std::string_view to_string(RKOrder order);
/// circular, tensor: the names scenes use.
const NameTable<SupportShape>& support_names();
std::string_view to_string(SupportShape shape);

}  // namespace mfree

#pragma once
// One small-strain elasticity solve on two point clouds, stage by stage:
//
//   clouds -> shape functions -> quadrature (weights, projected gradients) ->
//   consistency -> assembly -> factorisation -> solve
//
// The quadrature schemes compared in verification/cantilever, each with a consistency
// correction (consistency.hpp) that defaults to the scheme's best measured one
// (default_consistency):
//   gauss_cells  n x n Gauss points on background cells of the nodal spacing, direct
//                gradients; VCI by default, which makes it pass the patch test to round-off
//                on every cloud. The default scheme: it reaches every energy and L2 error
//                level of the cantilever soonest among consistent schemes (REPORT.md,
//                work-precision section; verification/cantilever/README.md).
//   projected    quadrature cloud (ratio points per node), w_K = integral of phi_K and
//                projected gradients on the background lattice; symmetric correction by
//                default (a symmetric positive definite stiffness).
//   nodal        direct nodal integration: the nodes as quadrature points, clipped Voronoi
//                weights, direct gradients; no correction by default (with VCI alone it
//                passes the patch test but, unstabilised, does not converge).

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "mfree/core/name_table.hpp"
#include "mfree/clouds/point_cloud.hpp"
#include "mfree/core/stage_timer.hpp"
#include "mfree/galerkin/boundary_quadrature.hpp"
#include "mfree/galerkin/consistency.hpp"
#include "mfree/galerkin/crack_tip_intensity.hpp"
#include "mfree/galerkin/exact_elasticity.hpp"
#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/galerkin/small_strain_elasticity.hpp"

namespace mfree {

enum class QuadratureScheme { projected, gauss_cells, nodal };
/// projected, gauss_cells, nodal: the names scenes use.
const NameTable<QuadratureScheme>& scheme_names();
std::string_view to_string(QuadratureScheme s);
/// The correction a scheme gets when none is named: symmetric (projected), vci
/// (gauss_cells), none (nodal).
Consistency default_consistency(QuadratureScheme s);
/// Gauss points per direction per cell when a scene names none: 3 for linear RK, 4 for
/// quadratic. 3 x 3 leaves quadratic RK a quadrature error in the trial gradients that caps the
/// L2 rate near 2 (cantilever lattice: 1.83 at h = 0.375 with quadratic VCI); 4 x 4 with the
/// quadratic VCI gives 3.3 (verification/cantilever/README.md).
int default_gauss_points(RKOrder order);
/// The projected scheme's quadrature-cloud support / its spacing when a scene names none: 2
/// for a linear quadrature cloud, 3 for a quadratic one, and half a spacing more on a domain
/// with cracks or interfaces. A slanted crack mouth leaves a wedge of the domain where a
/// lattice vertex sees two quadrature points within 2 spacings (the kinked edge crack of the
/// patch tests: its 68-degree mouth); 2.5 passes the patch tests there on every cloud.
double default_quadrature_factor(RKOrder quadrature_order, const Domain& domain);

struct ElasticitySettings {
  CloudSettings nodes;
  RKOrder order = RKOrder::linear;
  Window window = Window::cubic_bspline;
  SupportShape support = SupportShape::circular;
  double support_factor = 2.0;          ///< a = factor * h
  double irregular_factor_scale = 1.25; ///< node radii on irregular clouds (nodal_support_radii)
  /// How supports respect the domain's cracks, slots and re-entrant corners (support_paths.hpp;
  /// in a solid plain or visibility, surface_visibility.hpp).
  SupportRule support_rule = SupportRule::geodesic;
  /// Plain supports are refused where they join material across a gap narrower than the
  /// support (find_bridge, support_paths.hpp; find_gap in a solid) unless this is set.
  bool allow_bridging = false;

  QuadratureScheme scheme = QuadratureScheme::gauss_cells;
  double quadrature_ratio = 4.0;        ///< quadrature points per node
  /// Quadrature cloud a regular lattice whatever the node cloud (default), or of the node
  /// cloud's kind. Irregular quadrature clouds give quadratic RK negative weights (SPEC 3).
  bool quadrature_lattice = true;
  RKOrder quadrature_order = RKOrder::linear;
  /// Quadrature-cloud support / its spacing; nullopt: default_quadrature_factor.
  std::optional<double> quadrature_factor;
  int lattice_refinement = 2;           ///< lattice spacing = quadrature spacing / this
  std::optional<Consistency> consistency;  ///< nullopt: default_consistency(scheme)
  std::optional<int> gauss_points;         ///< per direction per cell; nullopt: default_gauss_points(order)
  SolverSettings solver;                ///< every linear solve ([solver], linear_solver.hpp)

  ElasticityProblem problem;
  /// Independent error quadrature: n x n Gauss points per cell of h/2 (64 points per node; the
  /// cantilever's errors agree with 6 x 6 to 6e-4 relative at h = 3 to 0.375, both RK orders).
  int error_gauss_points = 4;
  std::ostream* progress = nullptr;     ///< where to report each finished stage, if anywhere
};

/// What every solve on the clouds shares: nodes and their RK functions, the domain
/// quadrature with its (corrected) gradients, the boundary Gauss points (dim = 2, 3).
template <int dim>
struct Discretisation {
  std::vector<Point<dim>> nodes;
  std::unique_ptr<RKShapeFunctions<dim>> trial;
  GalerkinQuadrature<dim> quadrature;
  std::vector<Point<dim>> test_gradients;  ///< VCI's test gradients; empty otherwise
  BoundaryQuadrature<dim> boundary;
  GalerkinQuadrature<dim> at_boundary;          ///< trial functions and gradients at boundary's points
  Consistency consistency = Consistency::none;  ///< the correction applied
  /// VCI's test gradients of linear order: the stiffness a small skew correction of a
  /// symmetric one (SystemDescription::nearly_symmetric: GAMG preconditions it).
  bool nearly_symmetric = false;
  double consistency_before = 0.0;      ///< defect of (IC_p), p the RK order (consistency.hpp)
  double consistency_after = 0.0;       ///< the same for the (test) gradients used
  double correction_residual = 0.0;     ///< symmetric correction: |A lambda - r| / |r|
  std::optional<SolverReport> correction_solver;  ///< symmetric correction: the node system's solver

  [[nodiscard]] const std::vector<Point<dim>>* test() const {
    return test_gradients.empty() ? nullptr : &test_gradients;
  }
  [[nodiscard]] Index node_count() const { return static_cast<Index>(nodes.size()); }
  /// u^h = sum phi_I d_I at arbitrary points.
  [[nodiscard]] std::vector<Point<dim>> displacement(const std::vector<Point<dim>>& points,
                                                     const Eigen::VectorXd& d) const;
};

/// The stages clouds, shape functions, weights and projection, consistency, timed on timer.
Discretisation<2> discretise(const Domain& domain, const ElasticitySettings& s, StageTimer& timer);
/// The same on a solid, the boundary points cut at `parts` (the conditions' selections). The
/// projected scheme with VCI or no correction (the symmetric correction and the other
/// schemes are plane only: InputError); with consistency unset, VCI.
Discretisation<3> discretise(const Solid& solid, const ElasticitySettings& s,
                             const std::vector<BoundarySelection<3>>& parts, StageTimer& timer);

struct ElasticityResult : Discretisation<2> {
  Eigen::VectorXd coefficients;         ///< d: u^h = sum phi_I d_I
  StageTimer timer;
  SolverReport solver;                  ///< the stiffness's solver and what it did
  Index stiffness_nonzeros = 0;         ///< stored entries of the stiffness (its stencil)
  std::optional<ElasticErrors> errors;
  std::vector<TipIntensity> tips;       ///< K_I, K_II, J at every crack tip (crack_tip_intensity.hpp)

  /// u^h at arbitrary points.
  [[nodiscard]] std::vector<Vec2> displacement(const std::vector<Vec2>& points) const {
    return Discretisation<2>::displacement(points, coefficients);
  }
};

/// Runs the stages; errors against `exact` when given (independent Gauss cells of h/2).
ElasticityResult solve_elasticity(const Domain& domain, const ElasticitySettings& s,
                                  const ExactElasticity* exact);

}  // namespace mfree

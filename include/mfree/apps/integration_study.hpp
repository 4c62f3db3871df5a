#pragma once
// The integration-accuracy study of seed 003 (SPEC section 2), in the plane and in solids.
//
// The integrands are problems/integration_functions.hpp.
//
// error = |integral f - sum_K w_K f(x_K)| for our scheme (w_K = integral of phi_K by the
// background lattice) and the baselines: Voronoi cells clipped to the domain (plane only),
// Gauss points on background cells (n^dim per cell, cells of side n h: as many points as the
// cloud), equal weights |Omega| / N.
//
// The domain: [domain] lo, hi (a rectangle), or box = [[x0, y0, z0], [x1, y1, z1]] or solid =
// "part.step" (a gmsh file, relative to the scene: geometry/gmsh_solid.hpp). On a meshed solid
// the integrals are those over its tetrahedra Omega_h (each by a collapsed Gauss rule of
// degree 9, independent of the lattice), so the error is the rule's alone; |Omega_h| against
// the part's own volume is the geometric error, printed apart.

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "mfree/clouds/point_cloud.hpp"
#include "mfree/core/name_table.hpp"
#include "mfree/geometry/solid.hpp"
#include "mfree/io/scene_reader.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"

namespace mfree {

/// The weights compared: ours (w_K = integral of phi_K) and the three baselines above.
enum class WeightScheme { rk, voronoi, gauss_cells, equal };
/// rk, voronoi, gauss_cells, equal.
const NameTable<WeightScheme>& weight_scheme_names();

struct IntegrationStudySettings {
  Box rectangle;                      ///< the plane domain (no solid)
  std::optional<Solid> solid;         ///< or a solid: a box or a gmsh part
  std::vector<int> levels;            ///< quadrature points across the short side
  std::vector<CloudKind> clouds;
  double perturbation = 0.3;          ///< for perturbed clouds, fraction of the spacing
  std::vector<RKOrder> orders;
  std::vector<WeightScheme> schemes;
  std::vector<std::string> functions; ///< f1, f2
  std::uint64_t seed = 1;
  Window window = Window::cubic_bspline;
  SupportShape support = SupportShape::circular;
  double factor_linear = 2.0;     ///< support radius / spacing, linear RK
  double factor_quadratic = 3.0;  ///< support radius / spacing, quadratic RK
  double random_factor_scale = 1.25;  ///< support factor multiplier on irregular clouds
  int lattice_refinement = 2;     ///< lattice spacing = spacing / refinement
  int gauss_points = 2;           ///< Gauss points per direction per background cell
};

IntegrationStudySettings read_integration_study(const SceneTable& root);

struct IntegrationRow {
  std::string function, cloud, order, scheme;
  int level = 0;
  Index points = 0;
  double spacing = 0;   ///< sqrt(|Omega| / points)
  double error = 0;     ///< |integral f - sum w f|
  double relative_error = 0;
  double area_error = 0;  ///< |sum w - |Omega|| / |Omega|
  double moment_error = 0;  ///< max_i |sum w x_i - integral x_i| / (|Omega| diameter of its box)
  double seconds = 0;     ///< wall time to build the rule from the cloud
  Index negative = 0;     ///< number of negative weights
  double most_negative = 0;
};

/// Runs every level, cloud, order and scheme; prints progress to `log`.
std::vector<IntegrationRow> run_integration_study(const IntegrationStudySettings& s, std::ostream& log);

/// The CSV of the rows (one header line).
std::string integration_csv(const std::vector<IntegrationRow>& rows);

/// A table of errors and observed rates per series, for the terminal.
std::string integration_report(const std::vector<IntegrationRow>& rows);

}  // namespace mfree

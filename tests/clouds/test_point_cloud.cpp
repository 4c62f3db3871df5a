#include <algorithm>
#include <catch2/catch.hpp>

#include "../test_support.hpp"
#include "mfree/clouds/point_cloud.hpp"
#include "mfree/core/error.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"

using namespace mfree;

namespace {
/// Distance from p to the domain's boundary.
double boundary_distance(const Domain& d, const Vec2& p) {
  double best = 1e300;
  for (const BoundarySegment& s : d.boundary()) {
    const Vec2 t = s.b - s.a;
    const double u = std::clamp((p - s.a).dot(t) / t.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (s.a + u * t - p).norm());
  }
  return best;
}
}  // namespace

TEST_CASE("clouds are reproducible from their seed and lie in the domain", "[clouds]") {
  const Domain d = Domain::from_file(mfree::testing::source_dir() + "/meshes/plate_with_hole.wkt");
  for (CloudKind kind : {CloudKind::lattice, CloudKind::perturbed, CloudKind::random}) {
    CAPTURE(to_string(kind));
    CloudSettings s;
    s.kind = kind;
    s.spacing = 0.1;
    s.perturbation = 0.4;
    s.seed = 42;
    const auto a = make_cloud(d, s), b = make_cloud(d, s);
    REQUIRE(a == b);
    // Inside the closed domain; lattice points meant for the boundary may be round-off off it.
    for (const Vec2& p : a) REQUIRE((d.contains(p) || boundary_distance(d, p) <= 1e-9 * s.spacing));
    // About one point per h^2 of area (the hole and boundary take a few lattice points).
    CHECK(static_cast<double>(a.size()) == Approx(d.area() / 0.01).epsilon(0.06));
    if (kind != CloudKind::lattice) {
      s.seed = 43;
      CHECK(make_cloud(d, s) != a);
    }
  }
}

TEST_CASE("lattice clouds: vertex lattice reaches the boundary, quadrature cloud has the ratio",
          "[clouds]") {
  const Domain d = Domain::rectangle(Vec2(0, 0), Vec2(48, 12));
  CloudSettings s;
  s.spacing = 1.0;
  const auto nodes = make_cloud(d, s);
  CHECK(nodes.size() == 49u * 13u);
  CHECK(nodes.back() == Vec2(48, 12));
  const auto q = make_quadrature_cloud(d, s, 4.0);
  CHECK(q.size() == 4u * 48u * 12u);
  s.perturbation = 1.5;
  CHECK_THROWS_AS(make_cloud(d, s), InputError);
  s.perturbation = 0.0;
  s.spacing = -1.0;
  CHECK_THROWS_AS(make_cloud(d, s), InputError);
}

TEST_CASE(
    "surface support radii: a lattice in a sphere's octant reaches every surface point; a box keeps its "
    "radii",
    "[clouds]") {
  // At h = 0.05 the outer sphere's poles leave caps above the last plane of nodes whose points
  // see one plane only within 2h: uniform radii make a singular moment matrix there.
  const Solid solid = testing::thick_sphere_octant(0.1);
  const double h = 0.05, factor = 2.0;
  const std::vector<Point<3>> nodes = make_cloud(solid, {CloudKind::lattice, h});
  std::vector<Point<3>> surface;
  for (const SurfaceTriangle& t : solid.surface()) {
    surface.push_back(t.vertices[0]);
    surface.push_back((t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0);
  }
  RKSettings plain;
  plain.radius = factor * h;
  const RKShapeFunctions<3> uniform(nodes, plain);
  ShapeValues<3> v;
  std::size_t singular = 0;
  for (const Point<3>& x : surface) try {
      uniform.evaluate(x, v, true);
    } catch (const NumericalError&) {
      ++singular;
    }
  CHECK(singular > 0);

  RKSettings wide = plain;
  wide.node_radii = surface_support_radii(solid, nodes, h, factor, 1);
  REQUIRE(wide.node_radii.size() == nodes.size());
  const auto widened = std::count(wide.node_radii.begin(), wide.node_radii.end(), (factor + 0.5) * h);
  CHECK(widened > 0);
  CHECK(widened < static_cast<long>(nodes.size()) / 20);  // the caps only
  const RKShapeFunctions<3> reaching(nodes, wide);
  for (const Point<3>& x : surface) {
    reaching.evaluate(x, v, true);
    double sum = 0.0;
    Point<3> first = Point<3>::Zero();
    for (std::size_t a = 0; a < v.size(); ++a) {
      sum += v.phi[a];
      first += v.phi[a] * nodes[static_cast<std::size_t>(v.nodes[a])];
    }
    REQUIRE(sum == Approx(1.0).margin(1e-10));
    REQUIRE((first - x).norm() < 1e-10);
  }

  // A box on its own lattice: every face is a lattice plane, nothing is flat.
  const Solid box = Solid::box({0, 0, 0}, {1, 0.6, 0.8});
  const std::vector<Point<3>> box_nodes = make_cloud(box, {CloudKind::lattice, 0.1});
  CHECK(surface_support_radii(box, box_nodes, 0.1, 2.0, 1).empty());
  CHECK(surface_support_radii(box, box_nodes, 0.1, 3.0, 2).empty());
}

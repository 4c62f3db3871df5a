#include <algorithm>
#include <catch2/catch.hpp>

#include "../test_support.hpp"
#include "mfree/clouds/point_cloud.hpp"
#include "mfree/core/error.hpp"

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

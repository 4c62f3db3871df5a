// Tetrahedra: the part inside a box (clip_to_box) against closed forms and partitions, the
// closed-form second moments and the collapsed Gauss rule against exact monomial integrals.
#include <catch2/catch.hpp>
#include <random>

#include "mfree/geometry/tetrahedron.hpp"
#include "mfree/quadrature/tetrahedron_rule.hpp"

using namespace mfree;

namespace {

using P3 = Point<3>;

const Tetrahedron unit{P3(0, 0, 0), P3(1, 0, 0), P3(0, 1, 0), P3(0, 0, 1)};

double volume_of(const std::vector<Tetrahedron>& pieces) {
  double v = 0.0;
  for (const Tetrahedron& t : pieces) v += tetrahedron_volume(t);
  return v;
}

Tetrahedron random_tetrahedron(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Tetrahedron t;
  for (P3& v : t) v = P3(u(rng), u(rng), u(rng));
  return t;
}

}  // namespace

TEST_CASE("Tetrahedron clipped to a box: closed form, partitions of space and moments", "[geometry][3d]") {
  std::vector<Tetrahedron> pieces;
  // x + y + z <= 1 inside [0, 1/2]^3: the cube minus the corner x + y + z > 1, 1/8 - 1/48.
  clip_to_box(unit, AlignedBox<3>(P3(0, 0, 0), P3(0.5, 0.5, 0.5)), pieces);
  CHECK(volume_of(pieces) == Approx(5.0 / 48.0).epsilon(1e-15));
  pieces.clear();
  clip_to_box(unit, AlignedBox<3>(P3(-1, -1, -1), P3(2, 2, 2)), pieces);
  REQUIRE(pieces.size() == 1);
  CHECK(pieces[0] == unit);
  pieces.clear();
  clip_to_box(unit, AlignedBox<3>(P3(0.6, 0.6, 0), P3(1, 1, 1)), pieces);
  CHECK(volume_of(pieces) == 0.0);

  // Random tetrahedra cut by the 4 x 4 x 4 boxes of a lattice: the pieces' volumes and first
  // moments add up to the tetrahedron's, every piece inside its box.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Tetrahedron t = random_tetrahedron(rng);
    double volume = 0.0;
    P3 first = P3::Zero();
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          const P3 lo = P3(-1, -1, -1) + 0.5 * P3(i, j, k);
          const AlignedBox<3> box(lo, P3(lo + P3::Constant(0.5)));
          pieces.clear();
          clip_to_box(t, box, pieces);
          for (const Tetrahedron& p : pieces) {
            volume += tetrahedron_volume(p);
            first += tetrahedron_volume(p) * tetrahedron_centroid(p);
            for (const P3& v : p)
              REQUIRE(
                  (box.min().array() - 1e-15 <= v.array() && v.array() <= box.max().array() + 1e-15).all());
          }
        }
    CHECK(volume == Approx(tetrahedron_volume(t)).epsilon(1e-13));
    CHECK((first - tetrahedron_volume(t) * tetrahedron_centroid(t)).norm() <= 1e-14);
  }
}

TEST_CASE("Tetrahedron: second moments in closed form and the collapsed Gauss rule's degree",
          "[geometry][3d]") {
  // Over the unit tetrahedron, x^a y^b z^c integrates to a! b! c! / (a + b + c + 3)!.
  QuadratureRule<3> rule;
  add_tetrahedron_rule(unit, gauss_legendre(3), rule);  // exact to degree 3
  double xxy = 0.0, z3 = 0.0, one = 0.0;
  for (std::size_t k = 0; k < rule.size(); ++k) {
    const P3& x = rule.points[k];
    one += rule.weights[k];
    xxy += rule.weights[k] * x[0] * x[0] * x[1];
    z3 += rule.weights[k] * x[2] * x[2] * x[2];
  }
  CHECK(one == Approx(1.0 / 6.0).epsilon(1e-15));
  CHECK(xxy == Approx(2.0 / 720.0).epsilon(1e-14));
  CHECK(z3 == Approx(6.0 / 720.0).epsilon(1e-14));
  // A degree-4 term is not exact with 3 points (2 m - 3 = 3): the rule's degree is what it says.
  double x4 = 0.0;
  for (std::size_t k = 0; k < rule.size(); ++k) x4 += rule.weights[k] * std::pow(rule.points[k][0], 4);
  CHECK(std::abs(x4 - 24.0 / 5040.0) > 1e-8);

  // The closed-form second moments of random tetrahedra against the rule.
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Tetrahedron t = random_tetrahedron(rng);
    QuadratureRule<3> r;
    add_tetrahedron_rule(t, gauss_legendre(3), r);
    Tensor2<3> m = Tensor2<3>::Zero();
    for (std::size_t k = 0; k < r.size(); ++k) m += r.weights[k] * r.points[k] * r.points[k].transpose();
    CHECK((m - tetrahedron_second_moments(t)).norm() <= 1e-14);
  }
}

#include <catch2/catch.hpp>

#include "mfree/core/error.hpp"
#include "mfree/galerkin/stiffness_spectrum.hpp"

using namespace mfree;

namespace {

/// Free-stiffness spectrum of a 12 x 4 beam with a lattice of spacing 1 (65 nodes).
StiffnessSpectrum spectrum(QuadratureScheme scheme, double ratio) {
  ElasticitySettings s;
  s.nodes.kind = CloudKind::lattice;
  s.nodes.spacing = 1.0;
  s.scheme = scheme;
  s.quadrature_ratio = ratio;
  s.problem.material = LinearElastic{1.0e3, 0.3, PlaneModel::stress};
  const Domain domain = Domain::rectangle(Vec2(0, 0), Vec2(12, 4));
  StageTimer timer;
  const Discretisation<2> disc = discretise(domain, s, timer);
  return stiffness_spectrum(s.problem, domain, disc, 6);
}

}  // namespace

TEST_CASE("free stiffness: three rigid-body zero modes, no spurious ones with four quadrature points per node",
          "[galerkin]") {
  const StiffnessSpectrum sp = spectrum(QuadratureScheme::projected, 4.0);
  REQUIRE(sp.smallest.size() == 6);
  // Rigid-body motions have zero strain under the projected gradients (linear consistency):
  // their eigenvalues are round-off.
  for (int i = 0; i < 3; ++i) CHECK(std::abs(sp.smallest[i]) < 1e-12);
  CHECK(sp.zero_modes == 3);
  CHECK(sp.smallest[3] > 1e-4);
  CHECK(sp.largest > 0.0);
}

TEST_CASE("free stiffness: one quadrature point per node leaves near-zero-energy modes", "[galerkin]") {
  // The fourth eigenvalue (the softest deformation) falls by orders of magnitude when the
  // quadrature cloud is as coarse as the nodes: the under-integrated scheme barely sees a mode.
  const double stable = spectrum(QuadratureScheme::projected, 4.0).smallest[3];
  const double coarse = spectrum(QuadratureScheme::projected, 1.0).smallest[3];
  CHECK(coarse < 1e-2 * stable);
}

TEST_CASE("free stiffness: too many DOFs for the dense eigenvalue solve is an input error", "[galerkin]") {
  ElasticitySettings s;
  s.nodes.spacing = 0.01;
  const Domain domain = Domain::rectangle(Vec2(0, 0), Vec2(1, 1));
  Discretisation<2> disc;
  disc.nodes.resize(spectrum_max_dofs);  // 2 DOFs per node: twice the limit
  CHECK_THROWS_AS(stiffness_spectrum(s.problem, domain, disc, 4), InputError);
}

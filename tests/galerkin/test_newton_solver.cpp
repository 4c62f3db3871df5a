#include <catch2/catch.hpp>
#include <bit>
#include <cmath>
#include <cstdint>

#include "mfree/galerkin/newton_solver.hpp"
#include "mfree/linalg/sparse_solver.hpp"

using namespace mfree;

namespace {

/// A value in [-1, 1] that changes wholly with every bit of v (splitmix64 of its bits): noise.
double noise(double v) {
  std::uint64_t z = std::bit_cast<std::uint64_t>(v) + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) / static_cast<double>(1ULL << 52) - 1.0;
}

/// R(x) = A x - b + eps (noise(x_0), noise(x_1)): Newton with the tangent A reaches the floor
/// eps and no further, as a stiff problem reaches its round-off.
NonlinearSystem floored(double eps) {
  return {[eps](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            Eigen::VectorXd r(2);
            r << 4.0 * x[0] + x[1] - 1.0 + eps * noise(x[0]),
                x[0] + 3.0 * x[1] - 2.0 + eps * noise(x[1]);
            return r;
          },
          [](const Eigen::VectorXd&, SparseMatrix& k) {
            k.coeffRef(0, 0) = 4.0;
            k.coeffRef(0, 1) = 1.0;
            k.coeffRef(1, 0) = 1.0;
            k.coeffRef(1, 1) = 3.0;
          }};
}

NewtonOutcome solve(const NewtonSettings& s, double eps) {
  SparseMatrix k(2, 2);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) k.insert(i, j) = 1.0;
  SparseSolver solver(SolverKind::umfpack);
  StageTimer timer;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(2);
  return newton(floored(eps), d, k, solver, s, timer);
}

}  // namespace

TEST_CASE("Newton: a residual at its round-off floor is accepted as stagnated, not cut back",
          "[galerkin][newton]") {
  NewtonSettings s;
  s.line_search = false;
  s.tolerance = 1e-14;  // below the floor (1e-10 of |R_0| = sqrt 5)
  const NewtonOutcome o = solve(s, 1e-10);
  CHECK(o.converged);
  CHECK(o.stagnated);
  CHECK(o.history.back().residual < 1e-8 * o.history.front().residual);
  CHECK(o.history.size() <= 5);
  // Without a floor the relative test ends it, and an absolute tolerance above the floor ends
  // it before stagnation is looked for.
  const NewtonOutcome exact = solve(s, 0.0);
  CHECK((exact.converged && !exact.stagnated));
  s.absolute_tolerance = 1e-9;
  const NewtonOutcome absolute = solve(s, 1e-10);
  CHECK((absolute.converged && !absolute.stagnated));
  CHECK(absolute.history.back().residual <= 1e-9);
}

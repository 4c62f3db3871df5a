#include <catch2/catch.hpp>

#include "mfree/core/error.hpp"
#include "mfree/problems/axis_aligned_vibration.hpp"
#include "mfree/problems/builtin_solutions.hpp"
#include "mfree/problems/timoshenko_beam.hpp"

using namespace mfree;

TEST_CASE("built-in solutions: each entry is static or a motion, and builds what its file defines",
          "[problems]") {
  for (const std::string& name : builtin_solutions().names()) {
    INFO(name);
    const BuiltinSolution& s = builtin_solutions().value(name);
    CHECK(static_cast<bool>(s.statics) != static_cast<bool>(s.motion));
    CHECK_FALSE(s.parameters.empty());
  }
  const LinearElastic steel{3e7, 0.3, PlaneModel::stress};
  const SolutionSetting beam_on{{Vec2(0.0, -6.0), Vec2(48.0, 6.0)}, steel, false, 0.0};
  SolutionValues load;
  load.numbers["load"] = 1000.0;
  const ExactElasticity a = builtin_solutions().value("timoshenko_beam").statics(load, beam_on);
  const ExactElasticity b = timoshenko_beam(48.0, 12.0, 1000.0, steel);
  for (const Vec2 x : {Vec2(48.0, 0.0), Vec2(13.0, 2.5)}) {
    CHECK((a.displacement(x) - b.displacement(x)).norm() == 0.0);
    CHECK((a.stress(x) - b.stress(x)).norm() == 0.0);
  }
  // The beam's axis must be y = 0: a shifted body is refused, saying what is needed.
  const SolutionSetting shifted{{Vec2(0.0, 0.0), Vec2(48.0, 12.0)}, steel, false, 0.0};
  CHECK_THROWS_WITH(builtin_solutions().value("timoshenko_beam").statics(load, shifted),
                    Catch::Contains("[0, L] x [-D/2, D/2]"));

  SolutionValues amplitude;
  amplitude.numbers["amplitude"] = 0.05;
  const SolutionSetting square{
      {Vec2(0.0, 0.0), Vec2(1.0, 1.0)}, {1e7, 0.3, PlaneModel::strain}, true, 1000.0};
  const ExactMotion<2> m = builtin_solutions().value("vibration").motion(amplitude, square);
  const AxisAlignedVibration v{0.05, 1.0, 1e7, 0.3, 1000.0};
  const Vec2 x(0.3, 0.8);
  CHECK((m.displacement(x, 0.004) - v.displacement(x, 0.004)).norm() == 0.0);
  CHECK((m.velocity(x, 0.004) - v.velocity(x, 0.004)).norm() == 0.0);
  CHECK((m.cauchy_stress(x, 0.004) - v.cauchy_stress(x, 0.004)).norm() == 0.0);
  CHECK((m.body_force(x, 0.004) - v.body_force(x, 0.004)).norm() == 0.0);
  SolutionSetting linear_law = square;
  linear_law.neo_hookean = false;
  CHECK_THROWS_WITH(builtin_solutions().value("vibration").motion(amplitude, linear_law),
                    Catch::Contains("neo_hookean"));
  // At |A| >= L / (2 pi) the motion itself inverts the material (F_xx = 1 - 2 pi A / L at its
  // extreme), and its body force is not a number: refused; just below, a finite one.
  amplitude.numbers["amplitude"] = -0.16;
  CHECK_THROWS_WITH(builtin_solutions().value("vibration").motion(amplitude, square),
                    Catch::Contains("amplitude of L / (2 pi) = 0.159155 m or more") &&
                        Catch::Contains("amplitude -0.16 m is not below it"));
  amplitude.numbers["amplitude"] = 0.159;
  const ExactMotion<2> near = builtin_solutions().value("vibration").motion(amplitude, square);
  CHECK(near.body_force(Vec2(0.5, 0.5), 0.005).allFinite());
  CHECK(near.body_force(Vec2(0.0, 0.0), 0.005).allFinite());
}

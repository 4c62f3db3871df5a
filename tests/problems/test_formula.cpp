#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/problems/formula.hpp"
#include "../test_support.hpp"

using namespace mfree;
using mfree::testing::message_of;

TEST_CASE("formula: values in x, y, X, Y, t and named constants", "[problems]") {
  const Formula f("-rho * g * (H - y) + x * t + sin(pi * X / 2) * Y", {{"rho", 2.0}, {"g", 9.81}, {"H", 3.0}}, "k");
  const Vec2 p(0.3, 1.7);
  const double t = 0.25;
  CHECK(f(p, t) == Approx(-2.0 * 9.81 * (3.0 - 1.7) + 0.3 * t + std::sin(M_PI * 0.3 / 2) * 1.7).epsilon(1e-15));
  CHECK(f.depends_on_time());
  CHECK_FALSE(f.is_constant());
  const Formula c("2 * pi", {}, "k");
  CHECK(c.is_constant());
  CHECK_FALSE(c.depends_on_time());
  CHECK(c(p) == 2 * M_PI);
  // A number written by the scene reader reads back to the same double.
  CHECK(Formula::constant(0.1, "k")(p) == 0.1);
  CHECK(Formula::constant(-3.0e-7, "k")(p) == -3.0e-7);
}

TEST_CASE("formula: syntax errors, unknown names and non-finite values are errors naming the key", "[problems]") {
  using mfree::testing::message_of;
  CHECK_THAT(message_of<InputError>([] { Formula("x +* y", {}, "scene.toml:3:1: key 'u'"); }),
             Catch::Contains("scene.toml:3:1: key 'u'") && Catch::Contains("x +* y") && Catch::Contains("character"));
  CHECK_THAT(message_of<InputError>([] { Formula("x + z", {}, "key 'u'"); }),
             Catch::Contains("key 'u'") && Catch::Contains("names \"z\" (at character 5)"));
  CHECK_THAT(message_of<InputError>([] { Formula("x", {{"x", 1.0}}, "key 'u'"); }), Catch::Contains("hide the variable x"));
  CHECK_THAT(message_of<InputError>([] { Formula("1", {{"2a", 1.0}}, "key 'u'"); }), Catch::Contains("'2a' is not a name"));
  CHECK_THAT(message_of<InputError>([] { Formula("1 / 0", {}, "key 'u'"); }), Catch::Contains("evaluates to inf"));
  const Formula f("1 / x", {}, "key 'p'");
  CHECK_THAT(message_of<InputError>([&] { (void)f(Vec2(0.0, 2.0), 0.5); }),
             Catch::Contains("key 'p'") && Catch::Contains("inf at (x, y) = (0, 2), t = 0.5"));
  const Formula g("sqrt(y)", {}, "key 'q'");
  CHECK_THAT(message_of<InputError>([&] { (void)g(Vec2(0.0, -1.0)); }), Catch::Contains("nan"));
  // A NUL byte would end the text muParser sees ("1 + x" would be evaluated silently), a tab
  // or a newline is a slip: each is refused with its position.
  const std::string with_nul("1 + x\0* 1e9", 11);
  CHECK_THAT(message_of<InputError>([&] { Formula(with_nul, {}, "key 'n'"); }),
             Catch::Contains("key 'n'") && Catch::Contains("control character 0x00 at character 6"));
  CHECK_THAT(message_of<InputError>([] { Formula("x\t+ 1", {}, "key 'n'"); }),
             Catch::Contains("control character 0x09 at character 2"));
  CHECK(Formula("x + 1", {}, "key 'n'")(Vec2(2.0, 0.0)) == 3.0);
}

TEST_CASE("formula: evaluation from many threads gives the serial values", "[problems]") {
  const Formula f("x^2 - 3 * y + t", {}, "k");
  const int n = 20000;
  std::vector<Vec2> points(n);
  for (int i = 0; i < n; ++i) points[i] = Vec2(0.001 * i, std::sin(0.01 * i));
  std::vector<double> serial;
  f.evaluate(points, 0.5, serial);
  std::vector<double> parallel(n);
  parallel_blocks(n, 64, [&](Index b, Index e) {
    for (Index i = b; i < e; ++i) parallel[i] = f(points[i], 0.5);
  });
  for (int i = 0; i < n; ++i) REQUIRE(parallel[i] == serial[i]);
  CHECK(serial[n - 1] == Approx(std::pow(0.001 * (n - 1), 2) - 3 * std::sin(0.01 * (n - 1)) + 0.5));
}

#include <catch2/catch.hpp>

#include "mfree/kernels/window_function.hpp"

using namespace mfree;

TEST_CASE("windows: values at the break points, compact support, derivative by finite differences",
          "[kernels]") {
  for (Window kind : {Window::cubic_bspline, Window::quadratic_spline}) {
    CAPTURE(to_string(kind));
    CHECK(evaluate_window(kind, 0.0).w == Approx(kind == Window::cubic_bspline ? 2.0 / 3.0 : 0.75));
    CHECK(evaluate_window(kind, 0.0).dw == 0.0);
    CHECK(evaluate_window(kind, 1.0).w == 0.0);
    CHECK(evaluate_window(kind, 1.0).dw == 0.0);
    CHECK(evaluate_window(kind, 1.3).w == 0.0);
    // Continuity across the inner break (r = 1/2 for the cubic, rho = 1/2 i.e. r = 1/3 for eq. 17).
    const double brk = kind == Window::cubic_bspline ? 0.5 : 1.0 / 3.0;
    CHECK(evaluate_window(kind, brk - 1e-12).w == Approx(evaluate_window(kind, brk + 1e-12).w).epsilon(1e-10));
    CHECK(evaluate_window(kind, brk - 1e-12).dw == Approx(evaluate_window(kind, brk + 1e-12).dw).epsilon(1e-9));
    for (double r = 0.01; r < 1.0; r += 0.0173) {
      const double h = 1e-6;
      const double fd = (evaluate_window(kind, r + h).w - evaluate_window(kind, r - h).w) / (2 * h);
      CHECK(evaluate_window(kind, r).dw == Approx(fd).margin(1e-8));
    }
  }
}

TEST_CASE("windows: the quadratic spline is seed 000 eq. (17) with support 3/2 mapped to 1",
          "[kernels]") {
  // eq. (17) at rho = 1: (3/2 - 1)^2 / 2 = 1/8; rho = 1 is r = 2/3.
  CHECK(quadratic_spline(2.0 / 3.0).w == Approx(0.125));
  // The cubic B-spline at r = 1/2 equals 1/6 (SPEC section 1).
  CHECK(cubic_bspline(0.5).w == Approx(1.0 / 6.0));
}

#pragma once
// Polynomial displacement fields of small-strain elasticity: the linear and quadratic patch
// tests. Exact for any method that reproduces polynomials of that degree.

#include "mfree/core/types.hpp"
#include "mfree/galerkin/exact_elasticity.hpp"
#include "mfree/materials/linear_elastic.hpp"

namespace mfree {

/// A linear displacement u = a + G x: constant stress, no body force (the patch test).
ExactElasticity linear_field(const Vec2& a, const Mat2& g, const LinearElastic& material);

/// A quadratic displacement u_c = a_c + (G x)_c + x^T H_c x / 2 (H_0, H_1 symmetric): linear
/// stress and the constant body force b = -div sigma (the quadratic patch test).
ExactElasticity quadratic_field(const Vec2& a, const Mat2& g, const Mat2& h0, const Mat2& h1,
                                const LinearElastic& material);

}  // namespace mfree

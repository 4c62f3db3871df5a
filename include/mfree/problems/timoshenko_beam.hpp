#pragma once
// The Timoshenko cantilever (SPEC section 4): the exact small-strain solution of a beam
// 0 <= x <= L, -D/2 <= y <= D/2, clamped as the exact field prescribes on x = 0 and loaded
// by a parabolic shear traction of resultant P on x = L. No body force. Units as given
// (consistent set, e.g. m, N, Pa).

#include "mfree/galerkin/exact_elasticity.hpp"
#include "mfree/materials/linear_elastic.hpp"

namespace mfree {

/// Plane stress with E, nu of `material` (plane strain: E and nu are replaced by
/// E / (1 - nu^2) and nu / (1 - nu)).
ExactElasticity timoshenko_beam(double length, double depth, double load, const LinearElastic& material);

}  // namespace mfree

#pragma once
// A quadrature rule on a cracked domain: a point on a crack (or an interface) integrates
// both faces, as two copies (geometry/crack_faces.hpp) with half its weight each. The sum of
// the weights and their first moments are unchanged to the copies' offset.

#include "mfree/geometry/domain.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

/// `rule` with each point on a crack of `domain` split into its two face copies, each with
/// half the weight; h is the length the copies' offset is a fraction of. The rule itself when
/// the domain has no crack.
QuadratureRule<2> split_rule_on_cracks(const Domain& domain, QuadratureRule<2> rule, double h);

}  // namespace mfree

#pragma once
// The domain type of a dimension: the plane Domain (polygons with holes, cracks, regions) in
// two dimensions, the Solid in three.

#include <type_traits>

#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/solid.hpp"

namespace mfree {

template <int dim>
using DomainOf = std::conditional_t<dim == 2, Domain, Solid>;

}  // namespace mfree

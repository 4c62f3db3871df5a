// The 3D update of Drucker–Prager (drucker_prager_return.hpp), in a translation unit of its own.
#include "drucker_prager_return.hpp"

namespace mfree {

template double DruckerPrager::energy(const Tensor2<3>&, const MaterialState<3>&) const;
template MaterialUpdate<3> DruckerPrager::update(const Tensor2<3>&, const MaterialState<3>&, bool) const;

}  // namespace mfree

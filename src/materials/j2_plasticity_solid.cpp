// The 3D update of J2 plasticity (j2_return.hpp), in a translation unit of its own.
#include "j2_return.hpp"

namespace mfree {

template double J2Plasticity::energy(const Tensor2<3>&, const MaterialState<3>&) const;
template MaterialUpdate<3> J2Plasticity::update(const Tensor2<3>&, const MaterialState<3>&, bool) const;

}  // namespace mfree

#include "mfree/core/parallel.hpp"

#include <omp.h>

namespace mfree {

int thread_count() { return omp_get_max_threads(); }

}  // namespace mfree

// The one test source compiled with the source tree's path (MFREE_SOURCE_DIR).
#include "test_support.hpp"

namespace mfree::testing {

std::string source_dir() { return MFREE_SOURCE_DIR; }

}  // namespace mfree::testing

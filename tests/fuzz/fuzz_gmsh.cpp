// libFuzzer target: the gmsh domain reader (geometry/gmsh_domain.cpp, through libgmsh in a
// child process). The first byte picks the format (.geo or .msh), the rest is the file; a
// refusal is an mfree::Error, a crash of libgmsh among them (the child's signal). The reader's
// limits are 5 s and 512 MiB here, well inside libFuzzer's -timeout (.ci/fuzz: 20 s), so that an
// input that never ends (For i In {1:1e12}) is a refusal, not a finding.
#include "fuzz_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/gmsh_domain.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::filesystem::path file = mfree::fuzz::input_file(data + 1, size - 1, data[0] % 2 ? "domain.msh" : "domain.geo");
  try {
    const mfree::Domain d = mfree::read_gmsh_domain(file, {std::chrono::seconds(5), std::size_t{512} << 20});
    (void)d.area();
  } catch (const mfree::Error&) {
  }
  return 0;
}

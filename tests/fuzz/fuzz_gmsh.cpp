// libFuzzer target: the gmsh domain reader (geometry/gmsh_domain.cpp, through libgmsh in a
// child process). The first byte picks the format (.geo or .msh), the rest is the file; a
// refusal is an mfree::Error, a crash of libgmsh among them (the child's signal).
#include "fuzz_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/domain.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::filesystem::path file = mfree::fuzz::input_file(data + 1, size - 1, data[0] % 2 ? "domain.msh" : "domain.geo");
  try {
    const mfree::Domain d = mfree::Domain::from_file(file);
    (void)d.area();
  } catch (const mfree::Error&) {
  }
  return 0;
}

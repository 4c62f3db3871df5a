// libFuzzer target: the domain readers. The first byte picks the format (WKT, gmsh .geo,
// gmsh .msh), the rest is the file; a refusal is an mfree::Error.
#include "fuzz_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/domain.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const names[] = {"domain.wkt", "domain.geo", "domain.msh"};
  const std::filesystem::path file = mfree::fuzz::input_file(data + 1, size - 1, names[data[0] % 3]);
  try {
    const mfree::Domain d = mfree::Domain::from_file(file);
    (void)d.area();
    (void)d.contains(d.bounding_box().lo);
  } catch (const mfree::Error&) {
  }
  return 0;
}

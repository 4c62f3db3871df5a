// libFuzzer target: the WKT domain reader (geometry/domain.cpp). The input is the file; a
// refusal is an mfree::Error.
#include "fuzz_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/domain.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = mfree::fuzz::input_file(data, size, "domain.wkt");
  try {
    const mfree::Domain d = mfree::Domain::from_file(file);
    (void)d.area();
    (void)d.contains(d.bounding_box().lo);
  } catch (const mfree::Error&) {
  }
  return 0;
}

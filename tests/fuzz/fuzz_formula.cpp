// libFuzzer target: the formula parser. The input is a formula; it is parsed with two
// constants and evaluated at a few points and times; a refusal (parse error, unknown name,
// NaN or infinite value) is an mfree::Error.
#include "fuzz_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/problems/formula.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const mfree::Constants constants{{"E", 1e7}, {"rho", 1000.0}};
  try {
    const mfree::Formula f(std::string(mfree::fuzz::text(data, size)), constants, "fuzz: key 'formula'");
    for (const mfree::Vec2 x : {mfree::Vec2(0.0, 0.0), mfree::Vec2(0.5, -2.0), mfree::Vec2(1e300, 1e-300)})
      for (const double t : {0.0, 1.5}) (void)f(x, t);
  } catch (const mfree::Error&) {
  }
  return 0;
}

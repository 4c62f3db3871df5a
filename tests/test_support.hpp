#pragma once
// Helpers shared by the test files.

#include <exception>
#include <string>

namespace mfree::testing {

/// The message of the exception of type E that f throws, or a marker when it throws none.
/// Exceptions of other types propagate (and fail the test case).
template <class E = std::exception, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "<nothing thrown>";
}

}  // namespace mfree::testing

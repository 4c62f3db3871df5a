#pragma once
// Errors mfree reports to its user. Every message names what went wrong and where
// (which file and key, which point and how many neighbours), and what to change.

#include <stdexcept>
#include <string>

namespace mfree {

/// Base of every error mfree throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input from the user: a malformed scene, a missing mesh file, an out-of-range value.
class InputError : public Error {
 public:
  using Error::Error;
};

/// A numerical construction that cannot proceed: a singular moment matrix, J <= 0, ...
class NumericalError : public Error {
 public:
  using Error::Error;
};

}  // namespace mfree

#include "mfree/io/csv.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mfree {

std::string csv_number(double value, std::string_view spec) {
  return std::isfinite(value) ? fmt::format(fmt::runtime(spec), value) : std::string();
}

std::string csv_status(const std::optional<std::string>& failure) {
  if (!failure) return "ok";
  std::string out = "failed: " + *failure;
  for (char& c : out) {
    if (c == ',') c = ';';
    if (c == '"') c = '\'';
    if (c == '\n' || c == '\r') c = ' ';
  }
  return out;
}

}  // namespace mfree

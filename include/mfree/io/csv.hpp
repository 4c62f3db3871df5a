#pragma once
// CSV cells that scripts can trust: a value that is not a finite number is an empty cell,
// never "nan" or "inf", and a run's outcome is a status cell ("ok", or "failed: " and the
// reason) with the CSV's separators and quotes replaced so that it stays one cell.

#include <optional>
#include <string>
#include <string_view>

namespace mfree {

/// `value` formatted by the fmt specification `spec` (e.g. "{:.9e}"); "" when not finite.
std::string csv_number(double value, std::string_view spec);

/// "ok" without a failure, else "failed: " and the failure with ',', '"' and line breaks
/// replaced by ';', '\'' and ' '.
std::string csv_status(const std::optional<std::string>& failure);

}  // namespace mfree

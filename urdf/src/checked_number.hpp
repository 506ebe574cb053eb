#pragma once
// Every number a URDF gives ferret goes through checked_numbers(): decimal, finite,
// in the field's range, with the unit in the message. One function, so the checks
// can move onto core's shared validated number type in one place.

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ferret::internal {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// The values a field accepts: [lo, hi], either end open or unbounded (+-kInf); never
/// inf or nan themselves.
struct NumberRange {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  const char* unit = "";        ///< "metres", "radians", "Hz", "px"; empty: no unit
  bool integer = false;         ///< whole numbers only
  bool nonzero_vector = false;  ///< not all values 0 (an axis)
  bool nonzero = false;         ///< no value 0 (a scale factor)

  [[nodiscard]] bool contains(double v) const;
  /// "a number > 0 and <= 1000 (metres)", "3 finite numbers (radians)".
  [[nodiscard]] std::string describe(std::size_t count) const;
};

/// Parses `text` as `count` whitespace-separated decimal numbers (no hex, inf or nan)
/// and checks each against `range`; throws InputError(at, field, range.describe(),
/// the text) when it is absent (and `required`), malformed, non-finite or out of range.
/// nullopt when absent and not required.
std::optional<std::vector<double>> checked_numbers(const std::string& at, const std::string& field,
                                                   const char* text, std::size_t count,
                                                   const NumberRange& range, bool required);

/// A finite decimal number, or nullopt (the parse alone, for values checked later).
std::optional<double> parse_decimal(std::string_view token);

}  // namespace ferret::internal

#pragma once
// Numbers from user input, read one way everywhere: command-line values, YAML, JSON
// and CSV fields. A number is the whole text as one decimal (no hex, no trailing
// garbage, not empty), finite (NaN and infinities are never a valid length, time or
// gain), and in the field's range, which carries the unit for the message. Failures
// are InputError naming the source, the field, the range and what was got.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace ferret {

/// Where a number must lie: [lo, hi], either end open, with the unit for messages.
struct NumberRange {
  double lo = std::numeric_limits<double>::lowest();
  double hi = std::numeric_limits<double>::max();
  bool lo_open = false;
  bool hi_open = false;
  std::string_view unit;  ///< "m", "s", "m/s", "rad", "" for pure numbers

  [[nodiscard]] bool contains(double v) const;
  /// "a finite number", "a number in (0, 1000] m", "a number >= 0 s".
  [[nodiscard]] std::string describe() const;

  /// Any finite number.
  [[nodiscard]] static constexpr NumberRange finite(std::string_view unit = {}) {
    return {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::max(), false, false,
            unit};
  }
  /// (0, hi], e.g. a length or a time limit.
  [[nodiscard]] static constexpr NumberRange positive(double hi, std::string_view unit = {}) {
    return {0.0, hi, true, false, unit};
  }
  /// [0, hi].
  [[nodiscard]] static constexpr NumberRange non_negative(double hi, std::string_view unit = {}) {
    return {0.0, hi, false, false, unit};
  }
  /// [lo, hi].
  [[nodiscard]] static constexpr NumberRange closed(double lo, double hi,
                                                    std::string_view unit = {}) {
    return {lo, hi, false, false, unit};
  }
};

/// Parses `text` as one finite decimal number in `range`. Leading and trailing blanks
/// are allowed; a leading '+' is allowed. Throws InputError(source, field, ...).
[[nodiscard]] double parse_number(std::string_view text, const NumberRange& range,
                                  const std::string& source, const std::string& field = {});

/// The parse alone, without a range or an exception: the finite number `text` is under
/// parse_number's rules, or nullopt. For parsers that word their own errors.
[[nodiscard]] std::optional<double> parse_finite(std::string_view text);

/// Checks a number already converted by another parser (JSON, URDF): finite, in range.
double check_number(double value, const NumberRange& range, const std::string& source,
                    const std::string& field = {});

/// Parses a whole decimal integer in [lo, hi] (no sign for lo >= 0, no exponent, no
/// overflow: a 20-digit seed is an error, not a wrapped value).
[[nodiscard]] std::int64_t parse_integer(std::string_view text, std::int64_t lo, std::int64_t hi,
                                         const std::string& source, const std::string& field = {});
/// Parses a whole unsigned decimal integer <= hi ("-1" is an error, not 2^64 - 1).
[[nodiscard]] std::uint64_t parse_unsigned(
    std::string_view text, const std::string& source, const std::string& field = {},
    std::uint64_t hi = std::numeric_limits<std::uint64_t>::max());

/// The error text of parse_number without throwing: empty when `text` is valid. For
/// validators that must return a message (CLI11).
[[nodiscard]] std::string number_error(std::string_view text, const NumberRange& range);
/// Likewise for integers: `is_unsigned` selects parse_unsigned's rules.
[[nodiscard]] std::string integer_error(std::string_view text, bool is_unsigned);

}  // namespace ferret

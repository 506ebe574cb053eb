#include "ferret/core/number.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// Up to 40 characters of what the user gave, quoted; longer texts are cut.
std::string got_text(std::string_view text) {
  if (text.empty()) return "an empty value";
  if (text.size() > 40) return fmt::format("'{}...'", text.substr(0, 40));
  return fmt::format("'{}'", text);
}

std::string fmt_bound(double v) {
  if (v == std::numeric_limits<double>::max() || v == std::numeric_limits<double>::lowest())
    return {};
  return fmt::format("{}", v);
}

enum class Parse { kOk, kNotANumber, kNotFinite };

Parse parse_double(std::string_view text, double& value) {
  std::string_view t = trim(text);
  const bool plus = !t.empty() && t.front() == '+';
  if (plus) t.remove_prefix(1);
  if (t.empty() || t.front() == '+' || t.front() == ' ' || (plus && t.front() == '-'))
    return Parse::kNotANumber;
  const auto [end, ec] =
      std::from_chars(t.data(), t.data() + t.size(), value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) {
    // from_chars reports 1e400 as out of range; 1e-400 (underflow) is a tiny number, fine.
    const auto e = t.find_first_of("eE");
    const bool underflow = e != std::string_view::npos && e + 1 < t.size() && t[e + 1] == '-';
    if (!underflow) return Parse::kNotFinite;
    value = 0.0;
    return end == t.data() + t.size() ? Parse::kOk : Parse::kNotANumber;
  }
  if (ec != std::errc() || end != t.data() + t.size()) return Parse::kNotANumber;
  return std::isfinite(value) ? Parse::kOk : Parse::kNotFinite;
}

}  // namespace

bool NumberRange::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string NumberRange::describe() const {
  const std::string l = fmt_bound(lo), h = fmt_bound(hi);
  const std::string u = unit.empty() ? std::string() : fmt::format(" {}", unit);
  if (l.empty() && h.empty()) return fmt::format("a finite number{}", u);
  if (h.empty()) return fmt::format("a number {} {}{}", lo_open ? ">" : ">=", l, u);
  if (l.empty()) return fmt::format("a number {} {}{}", hi_open ? "<" : "<=", h, u);
  return fmt::format("a number in {}{}, {}{}{}", lo_open ? "(" : "[", l, h, hi_open ? ")" : "]", u);
}

std::string number_error(std::string_view text, const NumberRange& range) {
  double v = 0.0;
  switch (parse_double(text, v)) {
    case Parse::kNotANumber:
      return fmt::format("expected {} (got {})", range.describe(), got_text(text));
    case Parse::kNotFinite:
      return fmt::format("expected {} (got {}, not finite)", range.describe(),
                         got_text(trim(text)));
    case Parse::kOk:
      break;
  }
  if (!range.contains(v))
    return fmt::format("expected {} (got {})", range.describe(), got_text(trim(text)));
  return {};
}

double parse_number(std::string_view text, const NumberRange& range, const std::string& source,
                    const std::string& field) {
  double v = 0.0;
  const Parse p = parse_double(text, v);
  if (p == Parse::kOk && range.contains(v)) return v;
  std::string got = got_text(p == Parse::kNotANumber ? text : trim(text));
  if (p == Parse::kNotFinite) got += ", not finite";
  throw InputError(source, field, range.describe(), got);
}

std::optional<double> parse_finite(std::string_view text) {
  double v = 0.0;
  if (parse_double(text, v) != Parse::kOk) return std::nullopt;
  return v;
}

double check_number(double value, const NumberRange& range, const std::string& source,
                    const std::string& field) {
  if (range.contains(value)) return value;
  throw InputError(source, field, range.describe(), fmt::format("{}", value));
}

namespace {
template <class T>
bool parse_int(std::string_view text, T& value) {
  std::string_view t = trim(text);
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  if (t.empty() || t.front() == '+') return false;
  if constexpr (std::is_unsigned_v<T>)
    if (t.front() == '-') return false;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value, 10);
  return ec == std::errc() && end == t.data() + t.size();
}
}  // namespace

std::int64_t parse_integer(std::string_view text, std::int64_t lo, std::int64_t hi,
                           const std::string& source, const std::string& field) {
  std::int64_t v = 0;
  if (!parse_int(text, v) || v < lo || v > hi)
    throw InputError(source, field, fmt::format("an integer in [{}, {}]", lo, hi), got_text(text));
  return v;
}

std::uint64_t parse_unsigned(std::string_view text, const std::string& source,
                             const std::string& field, std::uint64_t hi) {
  std::uint64_t v = 0;
  if (!parse_int(text, v) || v > hi)
    throw InputError(source, field, fmt::format("a whole number in [0, {}]", hi), got_text(text));
  return v;
}

std::string integer_error(std::string_view text, bool is_unsigned) {
  if (is_unsigned) {
    std::uint64_t v = 0;
    if (parse_int(text, v)) return {};
    return fmt::format("expected a whole number in [0, {}] (got {})",
                       std::numeric_limits<std::uint64_t>::max(), got_text(text));
  }
  std::int64_t v = 0;
  if (parse_int(text, v)) return {};
  return fmt::format("expected an integer (got {})", got_text(text));
}

}  // namespace ferret

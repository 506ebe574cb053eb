#include "checked_number.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string_view>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "xml_check.hpp"

namespace ferret::internal {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::string bound(double v) { return fmt::format("{}", v); }

}  // namespace

std::optional<double> parse_decimal(std::string_view token) { return parse_finite(token); }

bool NumberRange::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  if (nonzero && v == 0.0) return false;
  return !integer || std::floor(v) == v;
}

std::string NumberRange::describe(std::size_t count) const {
  const char* kind = integer ? "integer" : nonzero ? "non-zero number" : "number";
  std::string out = count == 1 ? std::string(integer ? "an " : "a ") + kind
                               : std::to_string(count) + " " + kind + "s";
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi && lo_open && hi_open && !integer) {
    out += " in (" + bound(lo) + ", " + bound(hi) + ")";
  } else if (has_lo && has_hi) {
    out += std::string(" ") + (lo_open ? "> " : ">= ") + bound(lo) + " and " +
           (hi_open ? "< " : "<= ") + bound(hi);
  } else if (has_lo) {
    out += std::string(" ") + (lo_open ? "> " : ">= ") + bound(lo);
  } else if (has_hi) {
    out += std::string(" ") + (hi_open ? "< " : "<= ") + bound(hi);
  } else {
    out = count == 1 ? "a finite number" : std::to_string(count) + " finite numbers";
  }
  if (nonzero_vector) out += ", not all 0";
  if (*unit != '\0') out += std::string(" (") + unit + ")";
  return out;
}

std::optional<std::vector<double>> checked_numbers(const std::string& at, const std::string& field,
                                                   const char* text, std::size_t count,
                                                   const NumberRange& range, bool required) {
  if (text == nullptr) {
    if (required) throw InputError(at, field, range.describe(count), "nothing");
    return std::nullopt;
  }
  const std::string_view all(text);
  auto fail = [&]() -> void {
    std::string got = printable(std::string(all.substr(0, 80)));
    if (all.size() > 80) got += "...";
    throw InputError(at, field, range.describe(count), "'" + got + "'");
  };
  std::vector<double> values;
  std::size_t i = 0;
  for (;;) {
    while (i < all.size() && is_space(all[i])) ++i;
    if (i == all.size()) break;
    std::size_t j = i;
    while (j < all.size() && !is_space(all[j])) ++j;
    const auto v = parse_decimal(all.substr(i, j - i));
    if (!v || !range.contains(*v) || values.size() == count) fail();
    values.push_back(*v);
    i = j;
  }
  if (values.size() != count) fail();
  if (range.nonzero_vector) {
    bool any = false;
    for (const double v : values) any = any || v != 0.0;
    if (!any) fail();
  }
  return values;
}

}  // namespace ferret::internal

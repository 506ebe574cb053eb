#include "ferret/core/error.hpp"

#include <cstdio>

namespace ferret {

std::string printable(std::string_view text, std::size_t max_chars) {
  std::string out;
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  auto escape = [&](unsigned char c) {
    char buf[5];
    std::snprintf(buf, sizeof buf, "\\x%02x", c);
    out += buf;
  };
  for (std::size_t i = 0; i < n;) {
    if (out.size() >= max_chars) {
      out += "...";
      break;
    }
    const unsigned char c = s[i];
    if (c == '\t') {
      out += ' ';
      ++i;
    } else if (c < 0x20 || c == 0x7f) {
      escape(c);
      ++i;
    } else if (c < 0x80) {
      out += static_cast<char>(c);
      ++i;
    } else {
      // Keep well-formed UTF-8 (names in other scripts); escape every other byte.
      const std::size_t len = c >= 0xf0 && c < 0xf5 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
      bool ok = len != 0 && i + len <= n;
      for (std::size_t k = 1; ok && k < len; ++k) ok = (s[i + k] & 0xc0) == 0x80;
      if (ok) {
        out.append(text.substr(i, len));
        i += len;
      } else {
        escape(c);
        ++i;
      }
    }
  }
  return out;
}

namespace {
std::string compose(const std::string& source, const std::string& field,
                    const std::string& expected, const std::string& got) {
  // One printable line whatever the input held: sources and values may carry raw bytes
  // of a broken file (a .bt header, a NUL, a newline in a YAML key).
  std::string msg = source.empty() ? std::string("input") : printable(source);
  if (!field.empty()) msg += ": " + printable(field);
  msg += ": expected " + printable(expected);
  if (!got.empty()) msg += " (got " + printable(got, 120) + ")";
  return msg;
}
}  // namespace

InputError::InputError(std::string source, std::string field, std::string expected, std::string got)
    : std::runtime_error(compose(source, field, expected, got)),
      source_(std::move(source)),
      field_(std::move(field)),
      expected_(std::move(expected)) {}

}  // namespace ferret

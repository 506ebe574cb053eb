#include "ferret/core/error.hpp"

#include <cstdio>

namespace ferret {

namespace {
// Length of the well-formed UTF-8 sequence at s[i] (RFC 3629: no overlongs, no
// surrogates, nothing above U+10FFFF), 0 if there is none.
std::size_t utf8_length(const unsigned char* s, std::size_t n, std::size_t i) {
  const unsigned char c = s[i];
  std::size_t len = 0;
  unsigned char lo = 0x80, hi = 0xbf;  // allowed range of the second byte
  if (c >= 0xc2 && c <= 0xdf)
    len = 2;
  else if (c == 0xe0)
    len = 3, lo = 0xa0;
  else if (c == 0xed)
    len = 3, hi = 0x9f;
  else if (c >= 0xe1 && c <= 0xef)
    len = 3;
  else if (c == 0xf0)
    len = 4, lo = 0x90;
  else if (c == 0xf4)
    len = 4, hi = 0x8f;
  else if (c >= 0xf1 && c <= 0xf3)
    len = 4;
  if (len == 0 || i + len > n || s[i + 1] < lo || s[i + 1] > hi) return 0;
  for (std::size_t k = 2; k < len; ++k)
    if ((s[i + k] & 0xc0) != 0x80) return 0;
  return len;
}

std::string printable_impl(std::string_view text, std::size_t max_chars, bool keep_utf8) {
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
    } else if (const std::size_t len = keep_utf8 ? utf8_length(s, n, i) : 0; len > 0) {
      out.append(text.substr(i, len));
      i += len;
    } else {
      escape(c);
      ++i;
    }
  }
  return out;
}
}  // namespace

std::string printable(std::string_view text, std::size_t max_chars) {
  return printable_impl(text, max_chars, /*keep_utf8=*/false);
}

std::string printable_path(std::string_view text) {
  return printable_impl(text, 400, /*keep_utf8=*/true);
}

std::size_t first_invalid_utf8(std::string_view text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  for (std::size_t i = 0; i < text.size();) {
    if (s[i] < 0x80) {
      ++i;
      continue;
    }
    const std::size_t len = utf8_length(s, text.size(), i);
    if (len == 0) return i;
    i += len;
  }
  return std::string_view::npos;
}

namespace {
std::string compose(const std::string& source, const std::string& field,
                    const std::string& expected, const std::string& got) {
  // One printable line whatever the input held: sources and values may carry raw bytes
  // of a broken file (a .bt header, a NUL, a newline in a YAML key).
  std::string msg = source.empty() ? std::string("input") : printable_path(source);
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

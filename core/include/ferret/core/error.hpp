#pragma once
// Errors with context. Every boundary that reads user input (files, command-line
// values, requests) throws InputError naming the file, the field and what was
// expected; the CLI prints it as one line and exits 2.

#include <stdexcept>
#include <string>
#include <string_view>

namespace ferret {

/// `text` as one printable ASCII line: control bytes and every byte above 0x7f as \xNN,
/// tabs as spaces, cut after about `max_chars` characters ("..."). Every message ferret
/// prints about input goes through it (content of a file may be any bytes).
[[nodiscard]] std::string printable(std::string_view text, std::size_t max_chars = 400);
/// As printable(), but well-formed UTF-8 is kept: for paths the user typed.
[[nodiscard]] std::string printable_path(std::string_view text);
/// Offset of the first byte that does not start a well-formed UTF-8 sequence (RFC 3629),
/// npos when the whole text is UTF-8.
[[nodiscard]] std::size_t first_invalid_utf8(std::string_view text);

/// Malformed or inconsistent user input. Exit code 2 at the CLI.
class InputError : public std::runtime_error {
 public:
  /// @param source   file path (or "--option", "request") the input came from
  /// @param field    dotted path of the offending field ("sensors.camera_fov_deg");
  ///                 empty when the whole source is at fault
  /// @param expected what a valid value looks like ("a number > 0")
  /// @param got      what was found, if it helps ("-3"); may be empty
  InputError(std::string source, std::string field, std::string expected, std::string got = {});

  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] const std::string& field() const { return field_; }
  [[nodiscard]] const std::string& expected() const { return expected_; }

 private:
  std::string source_, field_, expected_;
};

/// A check the user asked for failed (an invalid plan, an object not found).
/// Exit code 1 at the CLI.
class CheckFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ferret

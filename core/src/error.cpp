#include "ferret/core/error.hpp"

namespace ferret {
namespace {
std::string compose(const std::string& source, const std::string& field,
                    const std::string& expected, const std::string& got) {
  std::string msg = source.empty() ? std::string("input") : source;
  if (!field.empty()) msg += ": " + field;
  msg += ": expected " + expected;
  if (!got.empty()) msg += " (got " + got + ")";
  return msg;
}
}  // namespace

InputError::InputError(std::string source, std::string field, std::string expected, std::string got)
    : std::runtime_error(compose(source, field, expected, got)),
      source_(std::move(source)),
      field_(std::move(field)),
      expected_(std::move(expected)) {}

}  // namespace ferret

#pragma once
// What a parser said when it refused a text: the field and the whole message, for tests
// that feed broken inputs to a reader that must throw InputError naming `source`.

#include <gtest/gtest.h>

#include <string>

#include "ferret/core/error.hpp"

namespace ferret::test {

struct Refusal {
  std::string field, what;
};

/// Calls `parse(text)`, which must throw InputError with `source` as its file; a text it
/// accepts is a test failure (and an empty Refusal).
template <class Parse>
Refusal refusal_of(const std::string& text, const std::string& source, const Parse& parse) {
  try {
    (void)parse(text);
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), source);
    return {e.field(), e.what()};
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return {};
}

}  // namespace ferret::test

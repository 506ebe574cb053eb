#include "ferret/core/number.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {

InputError error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

TEST(Number, ParsesWholeDecimalsOnly) {
  const auto any = NumberRange::finite();
  EXPECT_DOUBLE_EQ(parse_number("1.5", any, "f"), 1.5);
  EXPECT_DOUBLE_EQ(parse_number(" -2e3 ", any, "f"), -2000.0);
  EXPECT_DOUBLE_EQ(parse_number("+0.25", any, "f"), 0.25);
  EXPECT_DOUBLE_EQ(parse_number("-1e+5", any, "f"), -1e5);
  EXPECT_DOUBLE_EQ(parse_number("1e-400", any, "f"), 0.0);  // underflow is a tiny number
  for (const char* bad : {"", " ", "nan", "NaN", "-nan", "inf", "-inf", "infinity", "1e400",
                          "-1e400", "0x10", "1.5m", "1,5", "++1", "+-1", "1 2", "--1", ".", "e3"})
    EXPECT_THROW((void)parse_number(bad, any, "f"), InputError) << "'" << bad << "'";
}

TEST(Number, RangesAreCheckedWithTheirOpenEnds) {
  const auto len = NumberRange::positive(1000.0, "m");
  EXPECT_DOUBLE_EQ(parse_number("1000", len, "f"), 1000.0);
  EXPECT_THROW((void)parse_number("0", len, "f"), InputError);
  EXPECT_THROW((void)parse_number("1000.0001", len, "f"), InputError);
  EXPECT_DOUBLE_EQ(parse_number("0", NumberRange::non_negative(1.0), "f"), 0.0);
  EXPECT_THROW((void)check_number(std::nan(""), NumberRange::finite(), "f"), InputError);
  EXPECT_THROW(
      (void)check_number(-std::numeric_limits<double>::infinity(), NumberRange::finite(), "f"),
      InputError);
  EXPECT_DOUBLE_EQ(check_number(-3.0, NumberRange::closed(-3.0, 3.0), "f"), -3.0);
}

TEST(Number, MessageNamesSourceFieldRangeAndWhatWasGot) {
  const auto e = error_of([] {
    (void)parse_number("nan", NumberRange::positive(1000.0, "m"), "a.yaml",
                       "tether.total_length_m");
  });
  EXPECT_EQ(e.source(), "a.yaml");
  EXPECT_EQ(e.field(), "tether.total_length_m");
  EXPECT_EQ(
      std::string(e.what()),
      "a.yaml: tether.total_length_m: expected a number in (0, 1000] m (got 'nan', not finite)");
  EXPECT_EQ(NumberRange::finite("s").describe(), "a finite number s");
  EXPECT_EQ((NumberRange{0.0, std::numeric_limits<double>::max(), true, false, "m/s"}).describe(),
            "a number > 0 m/s");
  EXPECT_EQ(number_error("", NumberRange::finite()),
            "expected a finite number (got an empty value)");
  EXPECT_EQ(number_error("2", NumberRange::finite()), "");
}

TEST(Number, IntegersDoNotWrapOrTakeExponents) {
  EXPECT_EQ(parse_unsigned("18446744073709551615", "--seed"), 18446744073709551615ULL);
  for (const char* bad :
       {"-1", "18446744073709551616", "99999999999999999999", "1e3", "1.0", "", "0x1",
        "7 "
        "8"})
    EXPECT_THROW((void)parse_unsigned(bad, "--seed"), InputError) << bad;
  EXPECT_EQ(parse_integer("-5", -10, 10, "--n"), -5);
  EXPECT_THROW((void)parse_integer("11", -10, 10, "--n"), InputError);
  EXPECT_NE(integer_error("-1", true), "");
  EXPECT_EQ(integer_error("-1", false), "");
  EXPECT_EQ(parse_unsigned("42", "f", "", 100), 42u);
  EXPECT_THROW((void)parse_unsigned("101", "f", "", 100), InputError);
}

TEST(Printable, EscapesControlAndInvalidBytesKeepsUtf8) {
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(printable("line1\nline2"), "line1\\x0aline2");
  EXPECT_EQ(printable("\x89PNG\r"), "\\x89PNG\\x0d");
  EXPECT_EQ(printable("Zürich"), "Z\\xc3\\xbcrich");             // file content: ASCII only
  EXPECT_EQ(printable_path("Zürich"), "Zürich");                 // a path the user typed keeps it
  EXPECT_EQ(printable_path("\xc3"), "\\xc3");                    // a cut UTF-8 sequence
  EXPECT_EQ(printable_path("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate is not UTF-8
  EXPECT_EQ(printable_path("\xc0\xaf"), "\\xc0\\xaf");           // nor an overlong '/'
  EXPECT_EQ(first_invalid_utf8("ok ü"), std::string_view::npos);
  EXPECT_EQ(first_invalid_utf8("ab\xed\xa0\x80"), 2u);
  EXPECT_EQ(first_invalid_utf8("\xf4\x90\x80\x80"), 0u);  // above U+10FFFF
  EXPECT_EQ(printable(std::string(500, 'x'), 10), std::string(10, 'x') + "...");
}

TEST(Printable, InputErrorIsOnePrintableLine) {
  const InputError e(std::string("m\nap.bt"), "header", "an OctoMap header",
                     std::string("# Oc\0\x01\xff", 7));
  const std::string msg = e.what();
  EXPECT_EQ(msg.find('\n'), std::string::npos);
  EXPECT_EQ(msg, "m\\x0aap.bt: header: expected an OctoMap header (got # Oc\\x00\\x01\\xff)");
  EXPECT_EQ(e.source(), "m\nap.bt");  // the raw source stays available to callers
}

}  // namespace
}  // namespace ferret

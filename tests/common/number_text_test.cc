// common/number_text.h: what counts as a number written as text, and what is a mistake.
#include "common/number_text.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>

namespace slammtt {
namespace {

TEST(ParseFiniteDoubleTest, AcceptsWholeTextsThatAreFiniteNumbers) {
  EXPECT_EQ(ParseFiniteDouble("2.5"), 2.5);
  EXPECT_EQ(ParseFiniteDouble("-0.125"), -0.125);
  EXPECT_EQ(ParseFiniteDouble("+3"), 3.0);
  EXPECT_EQ(ParseFiniteDouble("1e6"), 1e6);
  EXPECT_EQ(ParseFiniteDouble("0x1p-2"), 0.25);
  EXPECT_EQ(ParseFiniteDouble(" 7"), 7.0);  // strtod skips leading white space
  EXPECT_EQ(ParseFiniteDouble("1.7976931348623157e308"), std::numeric_limits<double>::max());
}

TEST(ParseFiniteDoubleTest, RejectsEverythingElse) {
  for (const std::string text : {"", " ", "2.5x", "2.5 ", "x2", "1,5", "nan", "NaN", "inf",
                                 "-infinity", "1e999", "-1e999", "1e-400", "--1", "0x"}) {
    EXPECT_FALSE(ParseFiniteDouble(text).has_value()) << "'" << text << "'";
  }
  EXPECT_FALSE(ParseFiniteDouble(std::string("5\0x", 3)).has_value());  // a NUL inside
}

TEST(ParseWholeNumberTest, AcceptsWholeTextsThatAreInt64) {
  EXPECT_EQ(ParseWholeNumber("0"), 0);
  EXPECT_EQ(ParseWholeNumber("-42"), -42);
  EXPECT_EQ(ParseWholeNumber("+7"), 7);
  EXPECT_EQ(ParseWholeNumber("9223372036854775807"), std::numeric_limits<int64_t>::max());
  EXPECT_EQ(ParseWholeNumber("-9223372036854775808"), std::numeric_limits<int64_t>::min());
}

TEST(ParseWholeNumberTest, RejectsEverythingElse) {
  for (const std::string text : {"", "2.5", "1e3", "12 ", "x", "0x10", "9223372036854775808",
                                 "-9223372036854775809", "--1"}) {
    EXPECT_FALSE(ParseWholeNumber(text).has_value()) << "'" << text << "'";
  }
}

}  // namespace
}  // namespace slammtt

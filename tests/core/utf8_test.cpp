// first_invalid_utf8 against RFC 3629's table of well-formed byte sequences.
#include <gtest/gtest.h>

#include <string>

#include "avar/core/utf8.hpp"

namespace avar {
namespace {

TEST(Utf8, WellFormedTextOfEveryLength) {
  EXPECT_EQ(first_invalid_utf8(""), std::nullopt);
  EXPECT_EQ(first_invalid_utf8("plain <robot name=\"r\"/>"), std::nullopt);
  EXPECT_EQ(first_invalid_utf8("\xC3\xA9t\xC3\xA9"), std::nullopt);     // été
  EXPECT_EQ(first_invalid_utf8("\xE2\x82\xAC 5"), std::nullopt);        // €
  EXPECT_EQ(first_invalid_utf8("\xF0\x9F\x92\x80"), std::nullopt);      // U+1F480
  EXPECT_EQ(first_invalid_utf8("\xF4\x8F\xBF\xBF"), std::nullopt);      // U+10FFFF
  EXPECT_EQ(first_invalid_utf8(std::string("a\0b", 3)), std::nullopt);  // NUL is a character
}

TEST(Utf8, IllFormedSequencesAreFoundAtTheirFirstByte) {
  EXPECT_EQ(first_invalid_utf8("ab\xE5"), 2U);  // truncated at the end (a fuzzer's find)
  EXPECT_EQ(first_invalid_utf8("ab\xE5\x80"), 2U);
  EXPECT_EQ(first_invalid_utf8("\x80"), 0U);              // a lone continuation byte
  EXPECT_EQ(first_invalid_utf8("x\xC0\xAF"), 1U);         // overlong '/'
  EXPECT_EQ(first_invalid_utf8("\xE0\x80\xAF"), 0U);      // overlong, three bytes
  EXPECT_EQ(first_invalid_utf8("\xED\xA0\x80"), 0U);      // a surrogate
  EXPECT_EQ(first_invalid_utf8("\xF4\x90\x80\x80"), 0U);  // past U+10FFFF
  EXPECT_EQ(first_invalid_utf8("\xF5\x80\x80\x80"), 0U);
  EXPECT_EQ(first_invalid_utf8("\xC3\xA9\xC3("), 2U);  // a continuation byte missing
  EXPECT_EQ(first_invalid_utf8("\xFF"), 0U);
}

}  // namespace
}  // namespace avar

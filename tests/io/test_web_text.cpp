/// Tests of the web text helpers against their standards' own examples: base64 against RFC 4648's
/// test vectors (section 10), JSON string literals that stay inside an HTML script element, JSON
/// numbers (none not finite), HTML text.

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "sonarmap/io/web_text.hpp"

namespace sonarmap::test {
namespace {

std::vector<std::uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

TEST(webText, base64GivesRfc4648sTestVectors) {
  EXPECT_EQ(base64(bytesOf("")), "");
  EXPECT_EQ(base64(bytesOf("f")), "Zg==");
  EXPECT_EQ(base64(bytesOf("fo")), "Zm8=");
  EXPECT_EQ(base64(bytesOf("foo")), "Zm9v");
  EXPECT_EQ(base64(bytesOf("foob")), "Zm9vYg==");
  EXPECT_EQ(base64(bytesOf("fooba")), "Zm9vYmE=");
  EXPECT_EQ(base64(bytesOf("foobar")), "Zm9vYmFy");
  EXPECT_EQ(base64(std::vector<std::uint8_t>{0xFF, 0xFE, 0x00}), "//4A");
}

TEST(webText, jsonStringEscapesWhatWouldEndTheLiteralOrTheScript) {
  EXPECT_EQ(jsonString("pool \"A\" \\ 2"), R"("pool \"A\" \\ 2")");
  EXPECT_EQ(jsonString("a\nb\t"), R"("a\u000ab\u0009")");
  EXPECT_EQ(jsonString("</script>&"), R"("\u003c/script\u003e\u0026")");
  EXPECT_EQ(jsonString("Brest \xc3\xa9t\xc3\xa9"), "\"Brest \xc3\xa9t\xc3\xa9\"");  // UTF-8 passes
}

TEST(webText, jsonNumberHasNineDigitsAndNoNonFiniteValue) {
  EXPECT_EQ(jsonNumber(0.05), "0.05");
  EXPECT_EQ(jsonNumber(-0.0), "0");
  EXPECT_EQ(jsonNumber(1.0 / 3.0), "0.333333333");
  EXPECT_EQ(jsonNumber(1234567890123.0), "1.23456789e+12");
  EXPECT_EQ(jsonNumber(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(jsonNumber(-std::numeric_limits<double>::infinity()), "null");
}

TEST(webText, htmlTextEscapesMarkupAndQuotes) {
  EXPECT_EQ(htmlText("<b>map</b> & \"dive\""), "&lt;b&gt;map&lt;/b&gt; &amp; &quot;dive&quot;");
  EXPECT_EQ(htmlText("plain 5 m"), "plain 5 m");
}

}  // namespace
}  // namespace sonarmap::test

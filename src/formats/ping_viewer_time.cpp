/// @file ping_viewer_time.cpp
/// pingViewerTime_s, pingViewerText, asciiDigits (see ping_viewer_time.hpp).

#include "ping_viewer_time.hpp"

#include <unicode/uchar.h>
#include <unicode/unistr.h>

#include <array>
#include <vector>

namespace sonarmap::detail {
namespace {

icu::UnicodeString decode(std::span<const unsigned char> bytes, bool utf16) {
  if (!utf16) {
    return icu::UnicodeString::fromUTF8(
        icu::StringPiece(reinterpret_cast<const char*>(bytes.data()), static_cast<std::int32_t>(bytes.size())));
  }
  std::vector<char16_t> units(bytes.size() / 2);
  for (std::size_t i = 0; i < units.size(); ++i) {
    units[i] = static_cast<char16_t>((bytes[2 * i] << 8) | bytes[2 * i + 1]);
  }
  icu::UnicodeString text(units.data(), static_cast<std::int32_t>(units.size()));
  if (bytes.size() % 2 != 0) text.append(static_cast<UChar32>(0xFFFD));
  return text;
}

}  // namespace

std::optional<double> pingViewerTime_s(std::span<const unsigned char> bytes, bool utf16) {
  const icu::UnicodeString text = decode(bytes, utf16);
  std::array<long long, 4> value{};
  std::array<int, 4> digits{};
  std::size_t field = 0;
  for (std::int32_t i = 0; i < text.length(); i = text.moveIndex32(i, 1)) {
    const UChar32 c = text.char32At(i);
    if (u_charType(c) == U_FORMAT_CHAR) continue;  // bidirectional marks a right-to-left locale may add
    const std::int32_t digit = u_charDigitValue(c);
    if (digit >= 0 && digit <= 9) {
      if (++digits[field] > 9) return std::nullopt;
      value[field] = value[field] * 10 + digit;
    } else if (digits[field] == 0 || ++field == value.size()) {
      return std::nullopt;  // a separator must follow digits, and three separate the four fields
    }
  }
  if (field != 3 || digits[1] != 2 || digits[2] != 2 || digits[3] != 3) return std::nullopt;
  if (value[1] > 59 || value[2] > 59) return std::nullopt;
  return static_cast<double>(value[0]) * 3600.0 + static_cast<double>(value[1]) * 60.0 +
         static_cast<double>(value[2]) + static_cast<double>(value[3]) / 1000.0;
}

std::string pingViewerText(std::span<const unsigned char> bytes, bool utf16) {
  std::string utf8;
  decode(bytes, utf16).toUTF8String(utf8);
  return utf8;
}

std::string asciiDigits(std::string_view text) {
  const icu::UnicodeString unicode =
      icu::UnicodeString::fromUTF8(icu::StringPiece(text.data(), static_cast<std::int32_t>(text.size())));
  std::string ascii;
  for (std::int32_t i = 0; i < unicode.length(); i = unicode.moveIndex32(i, 1)) {
    const UChar32 c = unicode.char32At(i);
    const std::int32_t digit = u_charDigitValue(c);
    if (digit >= 0 && digit <= 9) {
      ascii.push_back(static_cast<char>('0' + digit));
    } else {
      ascii.push_back(c < 0x80 ? static_cast<char>(c) : '?');
    }
  }
  return ascii;
}

}  // namespace sonarmap::detail

#pragma once
/// @file message_text.hpp
/// Private to the library's readers: text taken from a file, quoted for an error message.

#include <cstddef>
#include <string>
#include <string_view>

namespace sonarmap::detail {

/// `text` between single quotes, safe inside a one-line message: bytes outside printable ASCII
/// (control characters, a line break, UTF-8, binary garbage) are written as `\xNN`, and text
/// longer than `max_chars` bytes is cut after them with "...". So a binary or huge field read
/// from a file can neither break the CLI's one-line error nor make it megabytes long.
inline std::string quotedForMessage(std::string_view text, std::size_t max_chars = 64) {
  constexpr char kHex[] = "0123456789abcdef";
  std::string out = "'";
  for (const char c : text.substr(0, max_chars)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7F) {
      out += c;
    } else {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0x0F];
    }
  }
  out += text.size() > max_chars ? "'..." : "'";
  return out;
}

}  // namespace sonarmap::detail

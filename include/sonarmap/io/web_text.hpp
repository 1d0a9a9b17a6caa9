#pragma once
/// @file web_text.hpp
/// Text for web pages and JSON: bytes as base64, strings as JSON string literals and as HTML text.
/// Used by the static 3D viewer (html_view.hpp) and the live page's server (live/web_server.hpp).

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace sonarmap {

/// `bytes` as standard base64 with padding (RFC 4648, section 4): 4 characters per 3 bytes.
[[nodiscard]] std::string base64(std::span<const std::uint8_t> bytes);

/// `text` as a JSON string literal, quotes included (RFC 8259, section 7). Control characters and
/// '<', '>', '&' are written as \\uXXXX escapes, so the literal is safe inside an HTML script
/// element. Bytes of 0x80 and above pass unchanged (UTF-8 text stays UTF-8).
[[nodiscard]] std::string jsonString(std::string_view text);

/// `value` as a JSON number with 9 significant digits ("%.9g": deterministic, a float's value
/// exactly, a double's to about 1e-9), -0 written as 0; null when not finite (JSON has no NaN or
/// infinity, RFC 8259, section 6).
[[nodiscard]] std::string jsonNumber(double value);

/// `text` safe as HTML element content or a quoted attribute value: '<', '>', '&' and '"' as
/// character references (HTML Living Standard, "Serializing HTML fragments").
[[nodiscard]] std::string htmlText(std::string_view text);

}  // namespace sonarmap

/// @file csv_fields.cpp
/// CSV line reading and exact number writing for the CSV formats (see csv_fields.hpp).

#include "csv_fields.hpp"

#include <charconv>
#include <cmath>
#include <system_error>
#include <utility>

#include "message_text.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::csv {
namespace {

constexpr std::string_view kWhitespace = " \t\r\v\f";
constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

std::string_view trim(std::string_view text) {
  const std::size_t first = text.find_first_not_of(kWhitespace);
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(kWhitespace) - first + 1);
}

std::string quoted(std::string_view text) {
  std::string out = "'";  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "'" + string
  out += text;
  out += "'";
  return out;
}

}  // namespace

LineReader::LineReader(std::istream& in, std::string source) : in_(in), source_(std::move(source)) {}

bool LineReader::next() {
  while (std::getline(in_, line_)) {
    ++line_number_;
    std::string_view rest(line_);
    if (line_number_ == 1 && rest.starts_with(kByteOrderMark)) rest.remove_prefix(kByteOrderMark.size());
    rest = trim(rest);
    if (rest.empty()) continue;
    fields_.clear();
    while (true) {
      const std::size_t comma = rest.find(',');
      fields_.push_back(trim(rest.substr(0, comma)));
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    return true;
  }
  if (in_.bad()) failFile("reading failed after line " + std::to_string(line_number_));
  return false;
}

void LineReader::fail(const std::string& what) const {
  throw FileError(quoted(source_) + ", line " + std::to_string(line_number_) + ": " + what);
}

void LineReader::failField(std::size_t column, std::string_view name, const std::string& what) const {
  fail("field " + quoted(name) + " (column " + std::to_string(column + 1) + "): " + what);
}

void LineReader::failFile(const std::string& what) const { throw FileError(quoted(source_) + ": " + what); }

void LineReader::expectName(std::size_t column, std::string_view name) const {
  if (column >= fields_.size()) {
    fail("header has " + std::to_string(fields_.size()) + " column(s), expected " + quoted(name) + " in column " +
         std::to_string(column + 1));
  }
  if (fields_[column] != name) {
    fail("header column " + std::to_string(column + 1) + " is " + detail::quotedForMessage(fields_[column]) + ", expected " +
         quoted(name));
  }
}

double LineReader::finiteNumber(std::size_t column, std::string_view name, std::string_view expected) const {
  const std::string_view token = fields_.at(column);
  double value = 0.0;
  const char* end = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  if (error == std::errc::result_out_of_range && stop == end) {  // 1e999, 1e-999
    failField(column, name, detail::quotedForMessage(token) + " is out of the range of a double, expected " + std::string(expected));
  }
  if (error != std::errc() || stop != end || token.empty()) {
    failField(column, name, detail::quotedForMessage(token) + " is not a number, expected " + std::string(expected));
  }
  if (!std::isfinite(value)) {
    failField(column, name, detail::quotedForMessage(token) + " is not finite, expected " + std::string(expected));
  }
  return value;
}

std::string formatNumber(double value) {
  char buffer[32];  // the shortest round-trip form of a double needs at most 24 characters
  // Cannot fail: the buffer is large enough.
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof(buffer), value).ptr);
}

void appendNumber(std::string& text, double value) { text += formatNumber(value); }

}  // namespace sonarmap::csv

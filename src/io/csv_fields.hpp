#pragma once
/// @file csv_fields.hpp
/// Private helper of the library's CSV formats (navigation CSV in the nav layer, beam CSV in the sonar layer;
/// docs/formats.md): reading comma-separated numbers line by line with messages that name the
/// file, the line and the field, and writing doubles so that they read back identically.
/// No quoting or escaping: the formats hold names and numbers only.

#include <cstddef>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace sonarmap::csv {

/// The lines of a CSV text, one at a time, split at commas. Blank lines are skipped; every field
/// is trimmed of spaces and tabs, and a line's trailing whitespace and carriage return (CRLF line
/// ends) are dropped; a UTF-8 byte-order mark at the start of the text is ignored.
class LineReader {
 public:
  /// @param source  the file's name, used in every message.
  LineReader(std::istream& in, std::string source);

  /// Moves to the next non-blank line. @return false at the end of the text.
  /// @throws FileError when reading fails.
  bool next();

  std::size_t lineNumber() const { return line_number_; }  ///< 1-based, of the current line
  const std::vector<std::string_view>& fields() const { return fields_; }  ///< the current line's

  /// @throws FileError "'source', line N: what".
  [[noreturn]] void fail(const std::string& what) const;
  /// @throws FileError "'source', line N, field 'name' (column c): what" (c is 1-based). Field
  /// text that the messages of this class quote from the file is escaped and cut
  /// (detail::quotedForMessage), so a binary line cannot break the one-line message.
  [[noreturn]] void failField(std::size_t column, std::string_view name, const std::string& what) const;
  /// @throws FileError "'source': what" (for problems of the whole file).
  [[noreturn]] void failFile(const std::string& what) const;

  /// Checks that header field `column` (0-based) is `name`; fails naming both otherwise.
  void expectName(std::size_t column, std::string_view name) const;

  /// Field `column` (0-based) of the current line as a finite double.
  /// @param name      the column's header name, for the message.
  /// @param expected  what the field holds, for the message ("seconds").
  /// @throws FileError when the field is not exactly one number or not finite.
  double finiteNumber(std::size_t column, std::string_view name, std::string_view expected) const;

 private:
  std::istream& in_;
  std::string source_;
  std::string line_;
  std::size_t line_number_ = 0;
  std::vector<std::string_view> fields_;
};

/// `value` in the shortest decimal form that reads back (std::from_chars) as exactly the same
/// double, e.g. "0.1", "1e-05", "-3.5".
std::string formatNumber(double value);

/// Appends formatNumber(value) to `text`.
void appendNumber(std::string& text, double value);

}  // namespace sonarmap::csv

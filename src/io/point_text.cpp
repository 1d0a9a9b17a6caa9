#include "sonarmap/io/point_text.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>
#include <system_error>

#include "message_text.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Parses a whole token as a double; false when it is not exactly one number.
bool parseNumber(std::string_view token, double& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);  // from_chars rejects '+'
  const char* end = token.data() + token.size();
  const auto [ptr, error] = std::from_chars(token.data(), end, value);
  // Out of range (1e999) is reported as an error by from_chars: treat it as not finite.
  if (error == std::errc::result_out_of_range && ptr == end) {
    value = HUGE_VAL;
    return true;
  }
  return error == std::errc() && ptr == end;
}

}  // namespace

PointCloud readPointText(std::istream& in, const std::string& source) {
  PointCloud points;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::string_view rest(line);
    if (const auto hash = rest.find('#'); hash != std::string_view::npos) rest = rest.substr(0, hash);
    auto fail = [&](const std::string& message) {
      throw FileError(source + ": line " + std::to_string(line_number) + ": " + message);
    };
    double xyz[3];
    int columns = 0;
    while (true) {
      std::size_t start = 0;
      while (start < rest.size() && isSpace(rest[start])) ++start;
      if (start == rest.size()) break;
      std::size_t stop = start;
      while (stop < rest.size() && !isSpace(rest[stop])) ++stop;
      const std::string_view token = rest.substr(start, stop - start);
      rest.remove_prefix(stop);
      if (columns == 3) fail("more than 3 values, expected 'x y z' in metres");
      double value = 0.0;
      const bool parsed = parseNumber(token, value);
      if (!parsed) {  // nan and inf are numbers: a point without a return, skipped at insertion
        fail(detail::quotedForMessage(token) + " is not a number, expected 'x y z' in metres");
      }
      xyz[columns++] = value;
    }
    if (columns == 0) continue;  // blank or comment line
    if (columns != 3) fail(std::to_string(columns) + " value(s), expected 3: 'x y z' in metres");
    points.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
  if (in.bad()) throw FileError(source + ": reading failed after line " + std::to_string(line_number));
  if (points.empty()) throw FileError(source + ": no points, expected lines 'x y z' in metres");
  return points;
}

PointCloud readPointText(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError("cannot open '" + path + "' for reading");
  return readPointText(in, path);
}

}  // namespace sonarmap

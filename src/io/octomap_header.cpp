#include "sonarmap/io/octomap_header.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "message_text.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// Reads `value` from the rest of a header line; false unless it parses and nothing follows it.
template <typename T>
bool readWholeValue(std::istringstream& tokens, T& value) {
  return static_cast<bool>(tokens >> value) && (tokens >> std::ws).eof();
}

}  // namespace

void writeOctomapHeader(std::ostream& out, const std::string& first_line, const OctomapHeader& header) {
  char res[64];
  const auto result = std::to_chars(res, res + sizeof(res), header.resolution_m);  // shortest round-trip
  out << first_line << "\n# (feel free to add / change comments, but leave the first line as it is!)\n";
  for (const std::string& comment : header.comments) {
    if (comment.find_first_of("\r\n") != std::string::npos) {
      throw ValueError("a map file's header comment must be one line, got " + detail::quotedForMessage(comment));
    }
    out << "# " << comment << "\n";
  }
  out << "#\n"
      << "id " << header.id << "\n"
      << "size " << header.size << "\n"
      << "res " << std::string(res, result.ptr) << "\n"
      << "data\n";
}

OctomapHeader readOctomapHeader(std::istream& in, const std::string& first_line, const std::string& source) {
  std::string line;
  if (!std::getline(in, line) || line.compare(0, first_line.size(), first_line) != 0) {
    throw FileError(source + ": not an OctoMap file, expected first line '" + first_line + "'");
  }
  OctomapHeader header;
  bool has_id = false, has_size = false, has_res = false;
  std::string res_line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '#') {
      const std::size_t text = line.find_first_not_of(' ', 1);
      if (text != std::string::npos) header.comments.push_back(line.substr(text));
      continue;
    }
    std::istringstream tokens(line);
    std::string token;
    tokens >> token;
    if (token == "data") {
      if (!has_id || !has_res) throw FileError(source + ": header ends at 'data' without 'id' and 'res'");
      if (!has_size) throw FileError(source + ": header has no 'size' line");
      // Checked only once the header is complete: a file cut inside "res 0.1" is truncated, not
      // a zero resolution.
      if (!std::isfinite(header.resolution_m) || header.resolution_m <= 0.0) {
        throw ValueError(source + ": resolution must be finite and > 0, got " + detail::quotedForMessage(res_line));
      }
      return header;
    }
    if (token == "id") {
      has_id = readWholeValue(tokens, header.id);
    } else if (token == "size") {
      long long size = -1;
      has_size = readWholeValue(tokens, size) && size >= 0;
      if (!has_size) throw FileError(source + ": 'size' must be a node count >= 0, got " + detail::quotedForMessage(line));
      header.size = static_cast<std::size_t>(size);
    } else if (token == "res") {
      has_res = readWholeValue(tokens, header.resolution_m);
      res_line = line;
      if (!has_res) throw FileError(source + ": 'res' must be a number, got " + detail::quotedForMessage(line));
    } else {
      throw FileError(source + ": unknown header line " + detail::quotedForMessage(line) + ", expected id, size, res or data");
    }
  }
  throw FileError(source + ": file ends inside the header, before the 'data' line");
}

}  // namespace sonarmap

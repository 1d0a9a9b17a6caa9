/// @file scene_file.cpp
/// Scene text reader and writer (see scene_file.hpp).

#include "sonarmap/sim/scene_file.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "../io/csv_fields.hpp"
#include "../io/message_text.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/sim/scene_frame.hpp"

namespace sonarmap {
namespace {

constexpr std::string_view kPlaneFields = "px py pz nx ny nz reflectivity";
constexpr std::string_view kBoxFields = "cx cy cz size_x size_y size_z yaw_rad reflectivity";
constexpr std::string_view kCylinderFields = "cx cy radius_m z_min_m z_max_m reflectivity";
constexpr std::string_view kReverberationFields = "level_db";

/// The header line's start; the frame follows: "ENU (x east, …)", or "(x north, …)" in files
/// written before the frame was named, which were NWU.
constexpr std::string_view kHeaderPrefix = "# sonarmap scene: map frame ";

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// The whitespace-separated tokens of `line` before any `#`.
std::vector<std::string_view> tokensOf(std::string_view line) {
  if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSpace(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !isSpace(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

/// One line of the file being read, for messages.
class LineContext {
 public:
  LineContext(const std::string& source, std::size_t line_number) : source_(source), line_number_(line_number) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw FileError(source_ + ": line " + std::to_string(line_number_) + ": " + what);
  }

  /// The numeric fields after the kind; fails unless there are exactly `names`' count, all finite.
  template <std::size_t N>
  std::array<double, N> numbers(const std::vector<std::string_view>& tokens, std::string_view names) const {
    const std::string kind(tokens[0]);
    if (tokens.size() != N + 1) {
      fail(kind + ": " + std::to_string(tokens.size() - 1) + " value(s), expected " + std::to_string(N) + ": " +
           std::string(names));
    }
    std::array<double, N> values{};
    for (std::size_t i = 0; i < N; ++i) {
      const std::string_view token = tokens[i + 1];
      const char* end = token.data() + token.size();
      const auto [stop, error] = std::from_chars(token.data(), end, values[i]);
      const bool out_of_range = error == std::errc::result_out_of_range && stop == end;
      if ((error != std::errc() && !out_of_range) || stop != end) {
        fail(kind + ": value " + std::to_string(i + 1) + " " + detail::quotedForMessage(token) +
             " is not a number (fields: " + std::string(names) + ")");
      }
      if (out_of_range || !std::isfinite(values[i])) {
        fail(kind + ": value " + std::to_string(i + 1) + " " + detail::quotedForMessage(token) +
             " is not finite (fields: " + std::string(names) + ")");
      }
    }
    return values;
  }

 private:
  const std::string& source_;
  std::size_t line_number_;
};

/// The frame a header line (starting kHeaderPrefix) names: "(" opens the axes of the old NWU
/// header; else its first word, up to a space or "(", is the frame's name.
MapFrame headerFrame(std::string_view line, const LineContext& context) {
  const std::string_view rest = line.substr(kHeaderPrefix.size());
  if (rest.starts_with("(")) return MapFrame::kNwu;
  const std::string_view name = rest.substr(0, rest.find_first_of(" \t\r("));
  for (const MapFrame frame : {MapFrame::kEnu, MapFrame::kNed, MapFrame::kNwu}) {
    if (name == mapFrameName(frame)) return frame;
  }
  context.fail("scene frame " + detail::quotedForMessage(name) + " unknown, expected ENU, NED or NWU (" +
               std::string(kHeaderPrefix) + "ENU ...)");
}

Primitive parsePrimitive(const std::vector<std::string_view>& tokens, const LineContext& context) {
  const std::string_view kind = tokens[0];
  if (kind == "plane") {
    const auto v = context.numbers<7>(tokens, kPlaneFields);
    return Plane{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6]};
  }
  if (kind == "box") {
    const auto v = context.numbers<8>(tokens, kBoxFields);
    return Box{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], v[7]};
  }
  if (kind == "cylinder") {
    const auto v = context.numbers<6>(tokens, kCylinderFields);
    return Cylinder{v[0], v[1], v[2], v[3], v[4], v[5]};
  }
  context.fail("unknown primitive " + detail::quotedForMessage(kind) + ", expected plane, box, cylinder or reverberation");
}

void appendNumbers(std::string& line, std::initializer_list<double> values) {
  for (const double value : values) {
    line += ' ';
    csv::appendNumber(line, value);
  }
}

std::string formatPrimitive(const Primitive& primitive) {
  std::string line = primitiveKind(primitive);
  if (const auto* plane = std::get_if<Plane>(&primitive)) {
    appendNumbers(line, {plane->point_m.x(), plane->point_m.y(), plane->point_m.z(), plane->normal.x(),
                         plane->normal.y(), plane->normal.z(), plane->reflectivity});
  } else if (const auto* box = std::get_if<Box>(&primitive)) {
    appendNumbers(line, {box->center_m.x(), box->center_m.y(), box->center_m.z(), box->size_m.x(), box->size_m.y(),
                         box->size_m.z(), box->yaw_rad, box->reflectivity});
  } else {
    const auto& cylinder = std::get<Cylinder>(primitive);
    appendNumbers(line, {cylinder.center_x_m, cylinder.center_y_m, cylinder.radius_m, cylinder.z_min_m,
                         cylinder.z_max_m, cylinder.reflectivity});
  }
  return line;
}

}  // namespace

Scene readScene(std::istream& in, const std::string& source) {
  Scene scene;
  MapFrame frame = MapFrame::kNwu;  // files without a header line were written in NWU
  std::size_t header_line = 0;
  bool data_seen = false;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const LineContext context(source, line_number);
    if (line.starts_with(kHeaderPrefix)) {
      if (header_line != 0) context.fail("scene frame named again (first on line " + std::to_string(header_line) + ")");
      if (data_seen) context.fail("scene frame named after the first primitive; it must come before");
      frame = headerFrame(line, context);
      header_line = line_number;
      continue;
    }
    const std::vector<std::string_view> tokens = tokensOf(line);
    if (tokens.empty()) continue;
    data_seen = true;
    if (tokens[0] == "reverberation") {
      if (scene.reverberation_db) context.fail("reverberation: given twice");
      scene.reverberation_db = context.numbers<1>(tokens, kReverberationFields)[0];
      continue;
    }
    const Primitive primitive = parsePrimitive(tokens, context);
    try {
      validatePrimitive(primitive);  // in the file's frame, so that a message quotes the file's numbers
    } catch (const ValueError& error) {
      context.fail(error.what());
    }
    scene.primitives.push_back(primitiveFromFrame(primitive, frame));
  }
  if (in.bad()) throw FileError(source + ": reading failed after line " + std::to_string(line_number));
  if (scene.primitives.empty()) throw FileError(source + ": no primitive, expected lines 'plane|box|cylinder …'");
  return scene;
}

Scene readScene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError("cannot open scene file '" + path + "' for reading");
  return readScene(in, path);
}

void writeScene(std::ostream& out, const Scene& scene, MapFrame frame) {
  if (scene.primitives.empty()) throw ValueError("scene not written: the scene has no primitive (reading it back would fail)");
  validateScene(scene);
  out << kHeaderPrefix << mapFrameDescription(frame) << ", metres, radians; reflectivity in [0, 1]\n"
      << "# plane    " << kPlaneFields << "\n"
      << "# box      " << kBoxFields << "\n"
      << "# cylinder " << kCylinderFields << "\n";
  for (const Primitive& primitive : scene.primitives) out << formatPrimitive(primitiveInFrame(primitive, frame)) << '\n';
  if (scene.reverberation_db) {
    std::string line = "reverberation";
    appendNumbers(line, {*scene.reverberation_db});
    out << "# an enclosed basin's diffuse reverberation after the TVG, dB: " << kReverberationFields << "\n"
        << line << '\n';
  }
}

void writeScene(const std::string& path, const Scene& scene, MapFrame frame) {
  writeFileAtomically(path, [&](std::ostream& out) { writeScene(out, scene, frame); });
}

}  // namespace sonarmap

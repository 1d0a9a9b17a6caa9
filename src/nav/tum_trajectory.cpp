/// @file tum_trajectory.cpp
/// TUM RGB-D trajectory files (see tum_trajectory.hpp).

#include "sonarmap/nav/tum_trajectory.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "../io/csv_fields.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap {
namespace {

constexpr std::string_view kComment =
    "# time x y z qx qy qz qw: body pose in NED (x north, y east, z down, metres; body FRD), TUM RGB-D format";

/// @throws ValueError when the track is empty, holds a non-finite value or its times do not
///         increase strictly.
void checkTrack(const NavTrack& track) {
  if (track.empty()) throw ValueError("TUM trajectory not written: the track is empty");
  const std::optional<NavTrackFault> fault = findNavTrackFault(track);
  if (!fault) return;
  const std::size_t i = fault->index;
  if (fault->kind == NavTrackFault::Kind::kNotFinite) {
    throw ValueError("TUM trajectory not written: fix " + std::to_string(i) + " holds a non-finite value");
  }
  throw ValueError("TUM trajectory not written: fix " + std::to_string(i) + "'s time is not after fix " +
                   std::to_string(i - 1) + "'s; times must increase strictly");
}

/// `line` without surrounding spaces, tabs and a carriage return.
std::string_view trimmed(std::string_view line) {
  const std::size_t begin = line.find_first_not_of(" \t\r");
  if (begin == std::string_view::npos) return {};
  return line.substr(begin, line.find_last_not_of(" \t\r") - begin + 1);
}

/// `line` split at runs of spaces and tabs.
std::vector<std::string_view> fieldsOf(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t at = 0;
  while (at < line.size()) {
    const std::size_t begin = line.find_first_not_of(" \t", at);
    if (begin == std::string_view::npos) break;
    const std::size_t end = std::min(line.find_first_of(" \t", begin), line.size());
    fields.push_back(line.substr(begin, end - begin));
    at = end;
  }
  return fields;
}

/// Z-Y-X Euler angles (roll, pitch, yaw) of a rotation R = Rz(yaw)·Ry(pitch)·Rx(roll).
NavSample anglesOf(const Eigen::Matrix3d& r) {
  NavSample fix;
  fix.yaw_rad = std::atan2(r(1, 0), r(0, 0));
  fix.pitch_rad = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  fix.roll_rad = std::atan2(r(2, 1), r(2, 2));
  return fix;
}

}  // namespace

void writeTumTrajectory(std::ostream& out, const NavTrack& track) {
  checkTrack(track);
  out << kComment << '\n';
  std::string line;
  for (const NavSample& fix : track) {
    Eigen::Quaterniond q(bodyToNed(fix).linear());
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();
    line.clear();
    for (const double value : {fix.time_s, fix.position_ned_m.x(), fix.position_ned_m.y(), fix.position_ned_m.z(), q.x(),
                               q.y(), q.z(), q.w()}) {
      if (!line.empty()) line += ' ';
      csv::appendNumber(line, value);
    }
    line += '\n';
    out << line;
  }
}

void writeTumTrajectory(const std::string& path, const NavTrack& track) {
  checkTrack(track);  // before the temporary file is made
  writeFileAtomically(path, [&](std::ostream& out) { writeTumTrajectory(out, track); });
}

NavTrack readTumTrajectory(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError("cannot open '" + path + "' for reading");
  NavTrack track;
  std::string raw;
  std::size_t line_number = 0;
  auto fail = [&](const std::string& what) {
    throw FileError("'" + path + "', line " + std::to_string(line_number) + ": " + what);
  };
  while (std::getline(in, raw)) {
    ++line_number;
    std::string_view line = raw;
    if (line_number == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
    line = trimmed(line);
    if (line.empty() || line.front() == '#') continue;
    const std::vector<std::string_view> fields = fieldsOf(line);
    if (fields.size() != 8) {
      fail(std::to_string(fields.size()) + " field(s), expected 8: time x y z qx qy qz qw (TUM RGB-D format)");
    }
    std::array<double, 8> values{};
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const char* end = fields[c].data() + fields[c].size();
      const auto [ptr, ec] = std::from_chars(fields[c].data(), end, values[c]);
      if (ec != std::errc{} || ptr != end || !std::isfinite(values[c])) {
        fail("field " + std::to_string(c + 1) + " is not a finite number");
      }
    }
    Eigen::Quaterniond q(values[7], values[4], values[5], values[6]);
    // Divided by its largest component first: beyond ~1e154 the squared norm overflows to inf and
    // normalize() would give (0, 0, 0, 0), read as the identity attitude.
    const double largest = q.coeffs().cwiseAbs().maxCoeff();
    if (largest > 0.0) q.coeffs() /= largest;
    if (!(largest * q.norm() > 1e-12)) fail("the quaternion has norm 0");
    q.normalize();
    NavSample fix = anglesOf(q.toRotationMatrix());
    fix.time_s = values[0];
    fix.position_ned_m = Eigen::Vector3d(values[1], values[2], values[3]);
    if (!track.empty() && !(fix.time_s > track.back().time_s)) {
      fail("time " + csv::formatNumber(fix.time_s) + " s is not after the previous pose's " +
           csv::formatNumber(track.back().time_s) + " s; times must increase strictly");
    }
    track.push_back(fix);
  }
  if (in.bad()) throw FileError("'" + path + "': read error");
  if (track.empty()) throw FileError("'" + path + "': no poses (TUM RGB-D format: time x y z qx qy qz qw)");
  return track;
}

NavTrack readTrajectory(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError("cannot open '" + path + "' for reading");
  std::string raw;
  bool first = true;
  while (std::getline(in, raw)) {
    std::string_view line = raw;
    if (first && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
    first = false;
    line = trimmed(line);
    if (line.empty() || line.front() == '#') continue;
    if (line.starts_with("time_s")) return readNavCsv(path);
    break;
  }
  return readTumTrajectory(path);
}

}  // namespace sonarmap

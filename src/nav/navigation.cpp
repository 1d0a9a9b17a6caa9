/// @file navigation.cpp
/// Poses from navigation fixes, pose interpolation, and the navigation CSV (see navigation.hpp).

#include "sonarmap/nav/navigation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>

#include "../io/csv_fields.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/text_input.hpp"

namespace sonarmap {
namespace {

constexpr std::string_view kHeader = "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad";
constexpr std::array<std::string_view, 7> kColumns = {"time_s",   "x_m",       "y_m",    "z_m",
                                                      "roll_rad", "pitch_rad", "yaw_rad"};
constexpr std::array<std::string_view, 7> kExpected = {"seconds",         "metres north", "metres east",
                                                       "metres down",     "radians",      "radians",
                                                       "radians"};

Eigen::Quaterniond attitudeOf(const NavSample& sample) {
  return Eigen::AngleAxisd(sample.yaw_rad, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(sample.pitch_rad, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(sample.roll_rad, Eigen::Vector3d::UnitX());
}

/// @throws ValueError (prefixed by `caller`) when the track is empty, holds a non-finite value or
///         its times do not increase strictly.
void checkTrack(const NavTrack& track, const char* caller) {
  if (track.empty()) throw ValueError(std::string(caller) + ": the navigation track is empty");
  const std::optional<NavTrackFault> fault = findNavTrackFault(track);
  if (!fault) return;
  const std::size_t i = fault->index;
  if (fault->kind == NavTrackFault::Kind::kNotFinite) {
    throw ValueError(std::string(caller) + ": navigation fix " + std::to_string(i) + " holds a non-finite value");
  }
  throw ValueError(std::string(caller) + ": navigation fix " + std::to_string(i) + " (time " +
                   csv::formatNumber(track[i].time_s) + " s) is not after fix " + std::to_string(i - 1) + " (time " +
                   csv::formatNumber(track[i - 1].time_s) + " s); times must increase strictly");
}

NavSample readFix(const csv::LineReader& reader) {
  if (reader.fields().size() != kColumns.size()) {
    reader.fail(std::to_string(reader.fields().size()) + " field(s), expected " + std::to_string(kColumns.size()) +
                ": " + std::string(kHeader));
  }
  std::array<double, kColumns.size()> values{};
  for (std::size_t c = 0; c < kColumns.size(); ++c) values[c] = reader.finiteNumber(c, kColumns[c], kExpected[c]);
  NavSample fix;
  fix.time_s = values[0];
  fix.position_ned_m = Eigen::Vector3d(values[1], values[2], values[3]);
  fix.roll_rad = values[4];
  fix.pitch_rad = values[5];
  fix.yaw_rad = values[6];
  return fix;
}

}  // namespace

bool isFinite(const NavSample& sample) {
  return std::isfinite(sample.time_s) && sample.position_ned_m.allFinite() && std::isfinite(sample.roll_rad) &&
         std::isfinite(sample.pitch_rad) && std::isfinite(sample.yaw_rad);
}

std::optional<NavTrackFault> findNavTrackFault(const NavTrack& track) {
  for (std::size_t i = 0; i < track.size(); ++i) {
    if (!isFinite(track[i])) return NavTrackFault{NavTrackFault::Kind::kNotFinite, i};
    if (i > 0 && !(track[i].time_s > track[i - 1].time_s)) return NavTrackFault{NavTrackFault::Kind::kNotAfter, i};
  }
  return std::nullopt;
}

Eigen::Isometry3d bodyToNed(const NavSample& sample) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = attitudeOf(sample).toRotationMatrix();
  pose.translation() = sample.position_ned_m;
  return pose;
}

Eigen::Isometry3d nedToMap() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  return pose;
}

std::optional<Eigen::Isometry3d> interpolateBodyToNed(const NavTrack& track, double time_s) {
  return NavInterpolator(track).bodyToNedAt(time_s);
}

NavInterpolator::NavInterpolator(const NavTrack& track) : track_(track) { checkTrack(track, "interpolateBodyToNed"); }

std::optional<Eigen::Isometry3d> NavInterpolator::bodyToNedAt(double time_s) const {
  const NavTrack& track = track_;
  if (!(time_s >= track.front().time_s && time_s <= track.back().time_s)) return std::nullopt;
  const auto after = std::upper_bound(track.begin(), track.end(), time_s,
                                      [](double t, const NavSample& fix) { return t < fix.time_s; });
  if (after == track.end()) return bodyToNed(track.back());  // time_s is the last fix's time
  const NavSample& a = *(after - 1);
  const NavSample& b = *after;
  const double s = (time_s - a.time_s) / (b.time_s - a.time_s);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = attitudeOf(a).slerp(s, attitudeOf(b)).toRotationMatrix();  // shortest arc
  pose.translation() = (1.0 - s) * a.position_ned_m + s * b.position_ned_m;
  return pose;
}

NavTrack readNavCsv(const std::string& path) {
  const std::unique_ptr<std::istream> in = openTextInput(path);
  csv::LineReader reader(*in, path);
  if (!reader.next()) reader.failFile("empty, expected the header row " + std::string(kHeader));
  for (std::size_t c = 0; c < kColumns.size(); ++c) reader.expectName(c, kColumns[c]);
  if (reader.fields().size() != kColumns.size()) {
    reader.fail("header has " + std::to_string(reader.fields().size()) +
                " columns, expected exactly " + std::string(kHeader));
  }
  NavTrack track;
  std::size_t previous_line = 0;
  while (reader.next()) {
    NavSample fix = readFix(reader);
    if (!track.empty() && !(fix.time_s > track.back().time_s)) {
      reader.failField(0, kColumns[0], csv::formatNumber(fix.time_s) + " s is not after the previous fix's " +
                                           csv::formatNumber(track.back().time_s) + " s (line " +
                                           std::to_string(previous_line) + "); times must increase strictly");
    }
    previous_line = reader.lineNumber();
    track.push_back(std::move(fix));
  }
  if (track.empty()) reader.failFile("no fixes: only the header row");
  return track;
}

void writeNavCsv(std::ostream& out, const NavTrack& track) {
  checkTrack(track, "writeNavCsv");
  out << kHeader << '\n';
  std::string line;
  for (const NavSample& fix : track) {
    line.clear();
    for (const double value : {fix.time_s, fix.position_ned_m.x(), fix.position_ned_m.y(), fix.position_ned_m.z(),
                               fix.roll_rad, fix.pitch_rad, fix.yaw_rad}) {
      if (!line.empty()) line += ',';
      csv::appendNumber(line, value);
    }
    line += '\n';
    out << line;
  }
}

void writeNavCsv(const std::string& path, const NavTrack& track) {
  checkTrack(track, "writeNavCsv");  // before the temporary file is made
  writeFileAtomically(path, [&](std::ostream& out) { writeNavCsv(out, track); });
}

Eigen::Isometry3d defaultSonarToBody() { return Eigen::Isometry3d::Identity(); }

Eigen::Isometry3d staticSonarToMap() { return sonarToMap(NavSample{}, defaultSonarToBody()); }

Eigen::Isometry3d sonarToMap(const NavSample& fix, const Eigen::Isometry3d& sonar_to_body) {
  return nedToMap() * bodyToNed(fix) * sonar_to_body;
}

}  // namespace sonarmap

namespace sonarmap {

NavCsvStream::NavCsvStream(std::string source) : source_(std::move(source)) {}

std::vector<NavSample> NavCsvStream::feed(std::span<const std::uint8_t> bytes) {
  std::vector<NavSample> fixes;
  partial_.append(bytes.begin(), bytes.end());
  std::size_t start = 0;
  for (std::size_t end; (end = partial_.find('\n', start)) != std::string::npos; start = end + 1) {
    std::istringstream line(partial_.substr(start, end - start));
    csv::LineReader reader(line, source_);
    if (!reader.next()) continue;  // a blank line
    ++rows_;
    if (!reader.fields().empty() && reader.fields()[0] == kColumns[0]) continue;  // the header row
    try {
      const NavSample fix = readFix(reader);
      if (last_time_s_ && !(fix.time_s > *last_time_s_)) {
        throw FileError("'" + source_ + "': a fix at " + csv::formatNumber(fix.time_s) +
                        " s is not after the previous one");
      }
      last_time_s_ = fix.time_s;
      fixes.push_back(fix);
    } catch (const FileError& error) {
      ++skipped_;
      last_reason_ = error.what();
    }
  }
  partial_.erase(0, start);
  if (partial_.size() > 4096) {  // no newline in sight: noise, not a row
    ++skipped_;
    last_reason_ = "'" + source_ + "': 4096 bytes without a line end";
    partial_.clear();
  }
  return fixes;
}

}  // namespace sonarmap

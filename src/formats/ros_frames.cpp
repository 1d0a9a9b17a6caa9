/// @file ros_frames.cpp
/// ROS poses and NED fixes (see ros_frames.hpp).

#include "ros_frames.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

/// ENU → NED coordinates (its own inverse): north = y, east = x, down = −z.
Eigen::Matrix3d enuToNed() {
  Eigen::Matrix3d a;
  a << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  return a;
}

/// FRD → FLU body coordinates (its own inverse).
Eigen::Matrix3d frdToFlu() { return Eigen::Vector3d(1, -1, -1).asDiagonal(); }

}  // namespace

bool namesNedFrame(const std::string& frame_id) {
  std::string lower = frame_id;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return lower.find("ned") != std::string::npos;
}

double headerTime(const RosValue& message, double record_time_s) {
  const RosValue* header = message.field("header");
  if (header == nullptr) return record_time_s;
  const double stamp = finiteNumber(header->field("stamp"), "header stamp");
  return stamp > 0.0 ? stamp : record_time_s;
}

std::string tfFrame(const std::string& frame_id) { return frame_id.starts_with('/') ? frame_id.substr(1) : frame_id; }

std::string headerFrame(const RosValue& message) {
  const RosValue* header = message.field("header");
  const RosValue* frame = header != nullptr ? header->field("frame_id") : nullptr;
  const std::string* name = frame != nullptr ? std::get_if<std::string>(&frame->value) : nullptr;
  if (name == nullptr) return {};
  return tfFrame(*name);
}

bool headerNamesNed(const RosValue& message) {
  const RosValue* header = message.field("header");
  const RosValue* frame = header != nullptr ? header->field("frame_id") : nullptr;
  const std::string* name = frame != nullptr ? std::get_if<std::string>(&frame->value) : nullptr;
  return name != nullptr && namesNedFrame(*name);
}

NavSample rosPoseToNed(double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& body_to_world, bool ned) {
  const double norm = body_to_world.norm();
  if (!(std::abs(norm - 1.0) <= 0.1)) throw Error("its orientation is no unit quaternion (norm " + std::to_string(norm) + ")");
  const Eigen::Matrix3d r_world = body_to_world.normalized().toRotationMatrix();
  const Eigen::Matrix3d r = ned ? r_world : Eigen::Matrix3d(enuToNed() * r_world * frdToFlu());
  NavSample fix;
  fix.time_s = time_s;
  fix.position_ned_m = ned ? position_m : Eigen::Vector3d(enuToNed() * position_m);
  // Z-Y-X angles of r = Rz(yaw) · Ry(pitch) · Rx(roll) (navigation.hpp's bodyToNed)
  fix.yaw_rad = std::atan2(r(1, 0), r(0, 0));
  fix.pitch_rad = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  fix.roll_rad = std::atan2(r(2, 1), r(2, 2));
  return fix;
}

double clockwiseDegrees(double bearing_rad) {
  double degrees = std::fmod(bearing_rad * 180.0 / std::numbers::pi, 360.0);
  if (degrees < 0.0) degrees += 360.0;
  return degrees >= 360.0 ? degrees - 360.0 : degrees;
}

void checkWritable(const char* writer, const SonarLog& log, const NavTrack& nav) {
  const std::string who(writer);
  for (const Beam& beam : log.beams) {
    if (!(std::isfinite(beam.time_s) && beam.time_s >= 0.0)) throw ValueError(who + ": a beam's time must be finite and >= 0 s");
    if (!(beam.bin_length_m > 0.0) || !std::isfinite(beam.bin_length_m)) throw ValueError(who + ": a beam's bin length must be > 0 m");
  }
  for (const NavSample& fix : nav) {
    if (!(std::isfinite(fix.time_s) && fix.time_s >= 0.0)) throw ValueError(who + ": a fix's time must be finite and >= 0 s");
    if (!fix.position_ned_m.allFinite() || !std::isfinite(fix.roll_rad + fix.pitch_rad + fix.yaw_rad)) {
      throw ValueError(who + ": a fix holds a value that is not finite");
    }
  }
}

void nedToRosEnu(const NavSample& fix, Eigen::Vector3d& position_enu_m, Eigen::Quaterniond& flu_to_enu) {
  position_enu_m = enuToNed() * fix.position_ned_m;
  flu_to_enu = Eigen::Quaterniond(Eigen::Matrix3d(enuToNed() * bodyToNed(fix).linear() * frdToFlu()));
}

}  // namespace sonarmap::detail

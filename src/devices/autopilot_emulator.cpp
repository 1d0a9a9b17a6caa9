/// @file autopilot_emulator.cpp
/// An ArduSub vehicle's MAVLink navigation from poses (see autopilot_emulator.hpp).

#include "sonarmap/devices/autopilot_emulator.hpp"

#include <cmath>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/mavlink_messages.hpp"

namespace sonarmap {
namespace {

constexpr double kGravity_m_s2 = 9.80665;

float wrapped(double angle_rad) {
  return static_cast<float>(std::remainder(angle_rad, 2.0 * std::numbers::pi));
}

}  // namespace

AutopilotEmulator::AutopilotEmulator(const AutopilotEmulatorOptions& options)
    : options_(options), encoder_(options.system, options.component, options.mavlink_version) {
  if (!(options.water_density_kg_m3 > 0.0) || !(options.surface_pressure_pa > 0.0)) {
    throw ValueError("the emulated autopilot's water density and surface pressure must be > 0");
  }
}

std::vector<std::uint8_t> AutopilotEmulator::frames(const NavSample& fix, double boot_s) {
  std::vector<std::uint8_t> out;
  const auto add = [&](const MavlinkPayload& payload) {
    const std::vector<std::uint8_t> frame = encodeMavlink(encoder_, payload);
    out.insert(out.end(), frame.begin(), frame.end());
  };
  const auto boot_ms = static_cast<std::uint32_t>(std::llround(std::max(0.0, boot_s) * 1000.0));
  if (boot_s >= last_heartbeat_s_ + 1.0) {
    MavlinkHeartbeat heartbeat;
    heartbeat.type = 12;      // MAV_TYPE_SUBMARINE
    heartbeat.autopilot = 3;  // MAV_AUTOPILOT_ARDUPILOTMEGA
    heartbeat.system_status = 4;  // MAV_STATE_ACTIVE
    add(toMavlinkPayload(heartbeat));
    last_heartbeat_s_ = boot_s;
  }
  MavlinkAttitude attitude;
  attitude.time_boot_ms = boot_ms;
  attitude.roll_rad = wrapped(fix.roll_rad);
  attitude.pitch_rad = wrapped(fix.pitch_rad);
  attitude.yaw_rad = wrapped(fix.yaw_rad);
  add(toMavlinkPayload(attitude));
  const Eigen::Vector3d& p = fix.position_ned_m;
  if (options_.position) {
    MavlinkLocalPositionNed local;
    local.time_boot_ms = boot_ms;
    local.x_m = static_cast<float>(p.x());
    local.y_m = static_cast<float>(p.y());
    local.z_m = static_cast<float>(p.z());
    add(toMavlinkPayload(local));
  }
  MavlinkGlobalPositionInt global;
  global.time_boot_ms = boot_ms;
  global.relative_alt_mm = static_cast<std::int32_t>(std::llround(-p.z() * 1000.0));
  global.hdg_cdeg = static_cast<std::uint16_t>(std::llround(std::fmod(std::fmod(fix.yaw_rad * 18000.0 / std::numbers::pi, 36000.0) + 36000.0, 36000.0)) % 36000);
  add(toMavlinkPayload(global));
  MavlinkScaledPressure pressure;
  pressure.message_id = 137;  // SCALED_PRESSURE2: the Bar30
  pressure.time_boot_ms = boot_ms;
  pressure.press_abs_hpa =
      static_cast<float>((options_.surface_pressure_pa + options_.water_density_kg_m3 * kGravity_m_s2 * p.z()) / 100.0);
  pressure.temperature_cdegc = 1500;
  add(toMavlinkPayload(pressure));
  return out;
}

}  // namespace sonarmap

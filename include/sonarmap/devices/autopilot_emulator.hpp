#pragma once
/// @file autopilot_emulator.hpp
/// An ArduSub autopilot's navigation as it streams it over MAVLink (formats/mavlink.hpp), made from
/// a vehicle's pose: what `sonarmap emulate --mavlink` sends so that `live --nav-stream` can be
/// flown without a vehicle. Messages, as ArduSub streams them to a ground station (its SR*
/// stream rates; ArduPilot's GCS_MAVLink): HEARTBEAT once a second (MAV_TYPE_SUBMARINE 12,
/// MAV_AUTOPILOT_ARDUPILOTMEGA 3), and at each fix ATTITUDE, LOCAL_POSITION_NED (when the EKF has a
/// horizontal position: a DVL or a positioning system), GLOBAL_POSITION_INT (relative_alt minus the
/// depth; latitude and longitude 0: no GPS under water) and SCALED_PRESSURE2 (the external pressure
/// sensor, a Bar30 on a BlueROV2: the surface pressure plus ρ g depth).

#include <cstdint>
#include <vector>

#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

struct AutopilotEmulatorOptions {
  std::uint8_t system = 1, component = 1;  ///< ArduSub's own ids
  int mavlink_version = 2;
  /// Whether LOCAL_POSITION_NED is sent: false for a vehicle without a DVL (a compass and a depth
  /// sensor only), whose EKF has no horizontal position.
  bool position = true;
  double water_density_kg_m3 = 1025.0;
  double surface_pressure_pa = 101325.0;
};

/// Turns poses into the MAVLink frames an ArduSub vehicle sends.
class AutopilotEmulator {
 public:
  /// @throws ValueError for a MAVLink version other than 1 or 2, or a density or pressure ≤ 0.
  explicit AutopilotEmulator(const AutopilotEmulatorOptions& options = {});
  /// The frames of one navigation update at `boot_s` seconds since the autopilot's boot (its
  /// time_boot_ms), for the vehicle at `fix` (NED, body FRD; its time is not used), with a
  /// HEARTBEAT first when a second passed since the last. Angles wrapped to −π..π as MAVLink sends them.
  std::vector<std::uint8_t> frames(const NavSample& fix, double boot_s);

 private:
  AutopilotEmulatorOptions options_;
  MavlinkEncoder encoder_;
  double last_heartbeat_s_ = -1e9;
};

}  // namespace sonarmap

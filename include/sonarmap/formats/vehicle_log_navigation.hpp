#pragma once
/// @file vehicle_log_navigation.hpp
/// The navigation a BlueROV2 (or any ArduSub vehicle) records itself, as the NavTrack the mapper
/// and the localizer take: the autopilot's dataflash log (`.BIN`) and the ground station's MAVLink
/// telemetry log (`.tlog`). A Ping360 user flying one has those beside the Ping Viewer log
/// (docs/formats.md, "BlueROV2 logs").
///
/// Both give the vehicle's attitude (roll, pitch, yaw of body FRD in NED: the autopilot's own
/// convention, MAVLink's ATTITUDE and ArduPilot's ATT), its depth (the EKF's down position, which
/// ArduSub fuses from the external pressure sensor) and, when the EKF has a horizontal position
/// (a DVL or a positioning system feeding it), north and east; without one, north and east stay 0
/// and the description says so. A fix is made at each attitude message, its position
/// interpolated linearly between the position (or depth) messages around it; attitude messages
/// outside the position messages' span give no fix.

#include <cstdint>
#include <span>
#include <string>

#include "sonarmap/formats/navigation_source.hpp"

namespace sonarmap {

/// What turns a pressure into a depth where a log gives only pressure (depth = (p − surface) /
/// (ρ g), g = 9.80665 m/s²). MAVLink streams and `.tlog`s use them only where the autopilot gave
/// no calibration of its own (mavlink_navigation.hpp, "Depth").
struct VehicleLogOptions {
  double water_density_kg_m3 = 1025.0;  ///< sea water; fresh water is about 997 (ArduSub's FRESH)
  double surface_pressure_pa = 101325.0;  ///< the atmosphere at the surface, pascals
};

/// Reads a MAVLink telemetry log (`.tlog`, as QGroundControl and MAVProxy write it: before each
/// MAVLink frame, the time it was received as a big-endian uint64 of microseconds since 1970,
/// UTC; pymavlink's mavutil.mavlogfile). Frames are MAVLink 1 (0xFE) or 2 (0xFD, with its
/// optional 13-byte signature; a payload's trailing zeros, truncated by the sender, restored), each
/// checked by its CRC-16/MCRF4XX with the message's CRC_EXTRA (MAVLink's serialization spec,
/// mavlink.io/en/guide/serialization.html; readMavlinkFrame, mavlink.hpp). The frames are made
/// into fixes as the live decoder makes them from the same stream (MavlinkNavigation,
/// mavlink_navigation.hpp: the vehicle is the sender of the first ATTITUDE; a fix per ATTITUDE,
/// roll, pitch, yaw in radians; north, east from LOCAL_POSITION_NED, else VISION_POSITION_DELTA,
/// else 0; depth from one of LOCAL_POSITION_NED, GLOBAL_POSITION_INT.relative_alt, SCALED_PRESSURE2,
/// 3, 1 at a time, with hysteresis, the pressures in the autopilot's calibration (its PARAM_VALUEs,
/// its own depth beside them); each interpolated between the samples around the fix), except the
/// clock: each message's time_boot_ms is put on the log's UTC clock by the smallest difference
/// between a frame's reception and its boot time over the whole boot (the least-delayed frame;
/// again after each reboot), so reception jitter does not move the fixes; `clock_utc_s` = 0.
/// Attitudes at the end of the log after their source's last sample give no fix.
/// A frame with a bad checksum is skipped and counted; a frame cut short or bytes that do not
/// start one end the reading with a note naming the record, its byte and the reason (the fixes
/// before it are kept).
/// @throws FileError naming the file when it cannot be read, or holds no ATTITUDE message (with
///   the reason the reading stopped, if it stopped early).
/// @throws ValueError when an option is not positive and finite.
NavigationSource readMavlinkTlogNavigation(const std::string& path, const VehicleLogOptions& options = {});

/// readMavlinkTlogNavigation on bytes already in memory; `source` names them in messages.
NavigationSource parseMavlinkTlogNavigation(std::span<const std::uint8_t> bytes, const std::string& source,
                                            const VehicleLogOptions& options = {});

/// True when `bytes` start as an ArduPilot dataflash log does (a record header 0xA3 0x95 and the
/// FMT message's type, 128).
bool isDataflashLog(std::span<const std::uint8_t> bytes);

/// Reads an ArduPilot dataflash log (`.BIN`; ArduPilot's libraries/AP_Logger/LogStructure.h and
/// pymavlink's DFReader): records of a 0xA3 0x95 header, a type byte and the fields its FMT record
/// defines (format characters b B h H i I f d n N Z c C e E L M q Q a; c, C, e, E are hundredths,
/// L is 1e-7 degrees). Read: ATT (Roll, Pitch, Yaw in degrees), the EKF's XKF1 (EKF3) or NKF1
/// (EKF2) of core 0 (PN, PE, PD in metres, NED), and, when neither has a record, the depth from
/// BARO (Press, pascals; of the instance with the highest median pressure: the external sensor in
/// the water). Times are TimeUS (microseconds since the autopilot's boot); `clock_utc_s` is set
/// from the first GPS record with a 3D fix (GWk, GMS: GPS time, 18 leap seconds behind since
/// 2017), unset without one. Bytes between records (a log's zero-filled tail, a damaged block) are
/// skipped to the next record header and counted, as DFReader does; a record cut short by the end
/// ends the reading with a note.
/// @throws FileError naming the file when it cannot be read, does not start with a FMT record, or
///   holds no ATT record.
/// @throws ValueError when an option is not positive and finite.
NavigationSource readDataflashNavigation(const std::string& path, const VehicleLogOptions& options = {});

/// readDataflashNavigation on bytes already in memory; `source` names them in messages.
NavigationSource parseDataflashNavigation(std::span<const std::uint8_t> bytes, const std::string& source,
                                          const VehicleLogOptions& options = {});

}  // namespace sonarmap

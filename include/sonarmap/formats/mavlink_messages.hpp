#pragma once
/// @file mavlink_messages.hpp
/// The payloads of the MAVLink messages sonarmap reads and writes, as plain structs in the
/// protocol's own units (named in each field), decoded from a MavlinkFrame and encoded into a
/// payload for MavlinkEncoder (mavlink.hpp).
///
/// Sources: common.xml (PARAM_VALUE, ATTITUDE, LOCAL_POSITION_NED, SCALED_PRESSURE, SCALED_PRESSURE2,
/// SCALED_PRESSURE3), minimal.xml (HEARTBEAT), standard.xml (GLOBAL_POSITION_INT),
/// ardupilotmega.xml (VISION_POSITION_DELTA), in mavlink/mavlink's message_definitions/v1.0; the
/// wire order of the fields is by type size, largest first (serialization spec). Frames: ATTITUDE's
/// angles are Z-Y-X Euler angles of body FRD in NED (sonarmap's NavSample convention);
/// LOCAL_POSITION_NED is the EKF's NED position from its origin; GLOBAL_POSITION_INT's altitudes
/// are up (a submarine's relative_alt is minus its depth); VISION_POSITION_DELTA's deltas are in
/// the current body FRD frame.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sonarmap/formats/mavlink.hpp"

namespace sonarmap {

/// HEARTBEAT (#0): a system or component is present.
struct MavlinkHeartbeat {
  static constexpr std::uint32_t kId = 0;
  std::uint32_t custom_mode = 0;  ///< autopilot-specific (ArduSub: its flight mode number)
  std::uint8_t type = 0;          ///< MAV_TYPE: 12 submarine, 6 ground station
  std::uint8_t autopilot = 0;     ///< MAV_AUTOPILOT: 3 ArduPilot, 8 none (a ground station)
  std::uint8_t base_mode = 0;     ///< MAV_MODE_FLAG bits
  std::uint8_t system_status = 0; ///< MAV_STATE
  std::uint8_t mavlink_version = 3;
};

/// PARAM_VALUE (#22): one of the sender's parameters, sent when a ground station asks for them
/// (QGroundControl reads them all on connecting) and when the autopilot changes one.
struct MavlinkParamValue {
  static constexpr std::uint32_t kId = 22;
  float param_value = 0;           ///< the value, a float whatever param_type says (ArduPilot sends them so)
  std::uint16_t param_count = 0;   ///< the sender's number of parameters
  std::uint16_t param_index = 0;   ///< this one's index; 65535 when sent unasked
  std::string param_id;            ///< its name, up to 16 ASCII characters ("BARO_SPEC_GRAV")
  std::uint8_t param_type = 9;     ///< MAV_PARAM_TYPE: 9 REAL32
};

/// ATTITUDE (#30).
struct MavlinkAttitude {
  static constexpr std::uint32_t kId = 30;
  std::uint32_t time_boot_ms = 0;  ///< milliseconds since the sender's boot
  float roll_rad = 0, pitch_rad = 0, yaw_rad = 0;  ///< −π..π
  float rollspeed_rad_s = 0, pitchspeed_rad_s = 0, yawspeed_rad_s = 0;
};

/// LOCAL_POSITION_NED (#32).
struct MavlinkLocalPositionNed {
  static constexpr std::uint32_t kId = 32;
  std::uint32_t time_boot_ms = 0;
  float x_m = 0, y_m = 0, z_m = 0;        ///< north, east, down
  float vx_m_s = 0, vy_m_s = 0, vz_m_s = 0;
};

/// GLOBAL_POSITION_INT (#33).
struct MavlinkGlobalPositionInt {
  static constexpr std::uint32_t kId = 33;
  std::uint32_t time_boot_ms = 0;
  std::int32_t lat_degE7 = 0, lon_degE7 = 0;  ///< degrees × 1e7
  std::int32_t alt_mm = 0;           ///< above mean sea level
  std::int32_t relative_alt_mm = 0;  ///< above home (ArduSub: minus the depth)
  std::int16_t vx_cm_s = 0, vy_cm_s = 0, vz_cm_s = 0;  ///< north, east, down
  std::uint16_t hdg_cdeg = 0;  ///< heading, centidegrees; 65535 unknown
};

/// SCALED_PRESSURE (#29), SCALED_PRESSURE2 (#137) and SCALED_PRESSURE3 (#143): one layout, the
/// autopilot's barometers 0, 1 and 2.
struct MavlinkScaledPressure {
  std::uint32_t message_id = 29;  ///< 29, 137 or 143
  std::uint32_t time_boot_ms = 0;
  float press_abs_hpa = 0;   ///< absolute pressure, hectopascals
  float press_diff_hpa = 0;  ///< differential pressure, hectopascals
  std::int16_t temperature_cdegc = 0;             ///< centidegrees Celsius
  std::int16_t temperature_press_diff_cdegc = 0;  ///< extension (MAVLink 2 only)
};

/// VISION_POSITION_DELTA (#11011, ardupilotmega.xml): what a DVL or a camera moved since its last
/// report.
struct MavlinkVisionPositionDelta {
  static constexpr std::uint32_t kId = 11011;
  std::uint64_t time_usec = 0;        ///< microseconds, UNIX or the sender's boot (0 when unset)
  std::uint64_t time_delta_usec = 0;  ///< since the last report
  std::array<float, 3> angle_delta_rad{};  ///< roll, pitch, yaw from the previous body FRD to the current
  std::array<float, 3> position_delta_m{};  ///< the displacement, in the current body FRD frame
  float confidence_percent = 0;  ///< 0..100
};

/// A payload ready for MavlinkEncoder::encode: all its fields (max_length bytes), wire order.
struct MavlinkPayload {
  std::uint32_t message_id = 0;
  std::vector<std::uint8_t> bytes;
};

MavlinkPayload toMavlinkPayload(const MavlinkHeartbeat& message);
/// param_id is cut to its first 16 characters (a name of 16 has no NUL on the wire).
MavlinkPayload toMavlinkPayload(const MavlinkParamValue& message);
MavlinkPayload toMavlinkPayload(const MavlinkAttitude& message);
MavlinkPayload toMavlinkPayload(const MavlinkLocalPositionNed& message);
MavlinkPayload toMavlinkPayload(const MavlinkGlobalPositionInt& message);
/// @throws ValueError unless message.message_id is 29, 137 or 143.
MavlinkPayload toMavlinkPayload(const MavlinkScaledPressure& message);
MavlinkPayload toMavlinkPayload(const MavlinkVisionPositionDelta& message);

/// The message in `frame` when it is of type Message (its id; for MavlinkScaledPressure any of the
/// three), else nullopt. The payload is the frame's, zero-extended: fields a sender truncated or
/// left out (MAVLink 1 extensions) read 0. The checksum is not looked at here (frame.checked).
template <class Message>
std::optional<Message> decodeMavlink(const MavlinkFrame& frame);

template <> std::optional<MavlinkHeartbeat> decodeMavlink(const MavlinkFrame& frame);
/// param_id: the characters before the first NUL, at most 16.
template <> std::optional<MavlinkParamValue> decodeMavlink(const MavlinkFrame& frame);
template <> std::optional<MavlinkAttitude> decodeMavlink(const MavlinkFrame& frame);
template <> std::optional<MavlinkLocalPositionNed> decodeMavlink(const MavlinkFrame& frame);
template <> std::optional<MavlinkGlobalPositionInt> decodeMavlink(const MavlinkFrame& frame);
template <> std::optional<MavlinkScaledPressure> decodeMavlink(const MavlinkFrame& frame);
template <> std::optional<MavlinkVisionPositionDelta> decodeMavlink(const MavlinkFrame& frame);

/// encoder.encode(payload.message_id, payload.bytes).
std::vector<std::uint8_t> encodeMavlink(MavlinkEncoder& encoder, const MavlinkPayload& payload);

}  // namespace sonarmap

/// @file mavlink_messages.cpp
/// The known messages' payloads in wire order (see mavlink_messages.hpp).

#include "sonarmap/formats/mavlink_messages.hpp"

#include <cstring>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// Fields written one after another, little-endian (memcpy: MAVLink and every target of this
/// project are little-endian).
class Writer {
 public:
  explicit Writer(std::uint32_t id) { payload_.message_id = id; }
  template <typename T>
  Writer& put(T value) {
    const std::size_t at = payload_.bytes.size();
    payload_.bytes.resize(at + sizeof(T));
    std::memcpy(payload_.bytes.data() + at, &value, sizeof(T));
    return *this;
  }
  MavlinkPayload done() { return std::move(payload_); }

 private:
  MavlinkPayload payload_;
};

template <typename T>
T at(const MavlinkFrame& frame, std::size_t offset) {
  T value;
  std::memcpy(&value, frame.payload.data() + offset, sizeof(T));
  return value;
}

bool isPressure(std::uint32_t id) { return id == 29 || id == 137 || id == 143; }

}  // namespace

MavlinkPayload toMavlinkPayload(const MavlinkHeartbeat& m) {
  return Writer(MavlinkHeartbeat::kId)
      .put(m.custom_mode)
      .put(m.type)
      .put(m.autopilot)
      .put(m.base_mode)
      .put(m.system_status)
      .put(m.mavlink_version)
      .done();
}

MavlinkPayload toMavlinkPayload(const MavlinkParamValue& m) {
  Writer w(MavlinkParamValue::kId);
  w.put(m.param_value).put(m.param_count).put(m.param_index);
  for (std::size_t i = 0; i < 16; ++i) w.put(i < m.param_id.size() ? m.param_id[i] : '\0');
  return w.put(m.param_type).done();
}

MavlinkPayload toMavlinkPayload(const MavlinkAttitude& m) {
  return Writer(MavlinkAttitude::kId)
      .put(m.time_boot_ms)
      .put(m.roll_rad)
      .put(m.pitch_rad)
      .put(m.yaw_rad)
      .put(m.rollspeed_rad_s)
      .put(m.pitchspeed_rad_s)
      .put(m.yawspeed_rad_s)
      .done();
}

MavlinkPayload toMavlinkPayload(const MavlinkLocalPositionNed& m) {
  return Writer(MavlinkLocalPositionNed::kId)
      .put(m.time_boot_ms)
      .put(m.x_m)
      .put(m.y_m)
      .put(m.z_m)
      .put(m.vx_m_s)
      .put(m.vy_m_s)
      .put(m.vz_m_s)
      .done();
}

MavlinkPayload toMavlinkPayload(const MavlinkGlobalPositionInt& m) {
  return Writer(MavlinkGlobalPositionInt::kId)
      .put(m.time_boot_ms)
      .put(m.lat_degE7)
      .put(m.lon_degE7)
      .put(m.alt_mm)
      .put(m.relative_alt_mm)
      .put(m.vx_cm_s)
      .put(m.vy_cm_s)
      .put(m.vz_cm_s)
      .put(m.hdg_cdeg)
      .done();
}

MavlinkPayload toMavlinkPayload(const MavlinkScaledPressure& m) {
  if (!isPressure(m.message_id)) {
    throw ValueError("a scaled pressure message has id " + std::to_string(m.message_id) +
                     ", expected 29 (SCALED_PRESSURE), 137 (SCALED_PRESSURE2) or 143 (SCALED_PRESSURE3)");
  }
  return Writer(m.message_id)
      .put(m.time_boot_ms)
      .put(m.press_abs_hpa)
      .put(m.press_diff_hpa)
      .put(m.temperature_cdegc)
      .put(m.temperature_press_diff_cdegc)
      .done();
}

MavlinkPayload toMavlinkPayload(const MavlinkVisionPositionDelta& m) {
  Writer w(MavlinkVisionPositionDelta::kId);
  w.put(m.time_usec).put(m.time_delta_usec);
  for (const float v : m.angle_delta_rad) w.put(v);
  for (const float v : m.position_delta_m) w.put(v);
  return w.put(m.confidence_percent).done();
}

template <>
std::optional<MavlinkHeartbeat> decodeMavlink(const MavlinkFrame& f) {
  if (f.message_id != MavlinkHeartbeat::kId) return std::nullopt;
  return MavlinkHeartbeat{at<std::uint32_t>(f, 0), f.payload[4], f.payload[5], f.payload[6], f.payload[7], f.payload[8]};
}

template <>
std::optional<MavlinkParamValue> decodeMavlink(const MavlinkFrame& f) {
  if (f.message_id != MavlinkParamValue::kId) return std::nullopt;
  MavlinkParamValue m{at<float>(f, 0), at<std::uint16_t>(f, 4), at<std::uint16_t>(f, 6), {}, f.payload[24]};
  for (std::size_t i = 8; i < 24 && f.payload[i] != 0; ++i) m.param_id.push_back(static_cast<char>(f.payload[i]));
  return m;
}

template <>
std::optional<MavlinkAttitude> decodeMavlink(const MavlinkFrame& f) {
  if (f.message_id != MavlinkAttitude::kId) return std::nullopt;
  return MavlinkAttitude{at<std::uint32_t>(f, 0), at<float>(f, 4),  at<float>(f, 8), at<float>(f, 12),
                         at<float>(f, 16),         at<float>(f, 20), at<float>(f, 24)};
}

template <>
std::optional<MavlinkLocalPositionNed> decodeMavlink(const MavlinkFrame& f) {
  if (f.message_id != MavlinkLocalPositionNed::kId) return std::nullopt;
  return MavlinkLocalPositionNed{at<std::uint32_t>(f, 0), at<float>(f, 4),  at<float>(f, 8), at<float>(f, 12),
                                 at<float>(f, 16),         at<float>(f, 20), at<float>(f, 24)};
}

template <>
std::optional<MavlinkGlobalPositionInt> decodeMavlink(const MavlinkFrame& f) {
  if (f.message_id != MavlinkGlobalPositionInt::kId) return std::nullopt;
  return MavlinkGlobalPositionInt{at<std::uint32_t>(f, 0),  at<std::int32_t>(f, 4),  at<std::int32_t>(f, 8),
                                  at<std::int32_t>(f, 12),  at<std::int32_t>(f, 16), at<std::int16_t>(f, 20),
                                  at<std::int16_t>(f, 22),  at<std::int16_t>(f, 24), at<std::uint16_t>(f, 26)};
}

template <>
std::optional<MavlinkScaledPressure> decodeMavlink(const MavlinkFrame& f) {
  if (!isPressure(f.message_id)) return std::nullopt;
  return MavlinkScaledPressure{f.message_id,      at<std::uint32_t>(f, 0), at<float>(f, 4), at<float>(f, 8),
                               at<std::int16_t>(f, 12), at<std::int16_t>(f, 14)};
}

template <>
std::optional<MavlinkVisionPositionDelta> decodeMavlink(const MavlinkFrame& f) {
  if (f.message_id != MavlinkVisionPositionDelta::kId) return std::nullopt;
  MavlinkVisionPositionDelta m;
  m.time_usec = at<std::uint64_t>(f, 0);
  m.time_delta_usec = at<std::uint64_t>(f, 8);
  for (std::size_t i = 0; i < 3; ++i) {
    m.angle_delta_rad[i] = at<float>(f, 16 + 4 * i);
    m.position_delta_m[i] = at<float>(f, 28 + 4 * i);
  }
  m.confidence_percent = at<float>(f, 40);
  return m;
}

std::vector<std::uint8_t> encodeMavlink(MavlinkEncoder& encoder, const MavlinkPayload& payload) {
  return encoder.encode(payload.message_id, payload.bytes);
}

}  // namespace sonarmap

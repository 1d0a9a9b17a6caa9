/// @file seanet_head_data.cpp
/// decodeSeaNetHeadData: one mtHeadData body → Beam (see seanet_head_data.hpp).

#include "seanet_head_data.hpp"

#include <cstdint>
#include <numbers>
#include <vector>

#include "../io/byte_io.hpp"

namespace sonarmap::detail {
namespace {

/// SeaNet's AD span and low level count 1/255 of 80 dB (rock-drivers SeaNetTypes; tritech_micron).
constexpr double kAdScale_db = 80.0;
constexpr std::uint32_t kBearingUnitsPerTurn = 6400;  // 1/16 gradian
constexpr double kAdIntervalUnit_s = 640e-9;
// HdCtrl bits (Tritech mtHeadCommand/mtHeadData).
constexpr std::uint16_t kHdCtrlAdc8On = 1U << 0;
constexpr std::uint16_t kHdCtrlInvert = 1U << 3;  // the head mounted upside down: its count runs the other way
/// SeaNet's "ahead": the centre of the head's default sector (left limit 2400, right limit 4000).
constexpr std::uint32_t kAheadBearing = 3200;

// Field offsets in the body (from the byte after the message type).
constexpr std::size_t kHeadControlAt = 7;
constexpr std::size_t kGainAt = 15;
constexpr std::size_t kAdSpanAt = 18;
constexpr std::size_t kAdIntervalAt = 22;
constexpr std::size_t kBearingAt = 29;
constexpr std::size_t kDataBytesAt = 31;

/// Unpacks the data bytes of one beam: copied (8-bit) or two 4-bit bins per byte, high nibble
/// first, scaled ×17 onto 0…255.
std::vector<std::uint8_t> unpackBins(std::span<const unsigned char> data, bool eight_bit) {
  if (eight_bit) return {data.begin(), data.end()};
  std::vector<std::uint8_t> bins;
  bins.reserve(2 * data.size());
  for (const unsigned char byte : data) {
    bins.push_back(static_cast<std::uint8_t>((byte >> 4) * 17));
    bins.push_back(static_cast<std::uint8_t>((byte & 0x0F) * 17));
  }
  return bins;
}

/// SeaNet bearing (1/16 gradian, clockwise seen from above for an upright head, ahead at 3200) →
/// beam.hpp's radians in [0, 2π): ahead at 0, clockwise; an inverted head counts the other way.
double bearingRad(std::uint16_t bearing, bool inverted) {
  const std::uint32_t from_ahead = inverted ? (kAheadBearing + kBearingUnitsPerTurn - bearing) % kBearingUnitsPerTurn
                                            : (bearing + kBearingUnitsPerTurn - kAheadBearing) % kBearingUnitsPerTurn;
  // Through degrees, as the beam CSV reads them back (beam_csv.cpp): a converted log maps alike.
  const double degrees = static_cast<double>(from_ahead) * 360.0 / kBearingUnitsPerTurn;
  return degrees * std::numbers::pi / 180.0;
}

SeaNetHeadData defectAt(std::size_t at, std::string message) {
  SeaNetHeadData result;
  result.defect = std::move(message);
  result.defect_at = at;
  return result;
}

}  // namespace

SeaNetHeadData decodeSeaNetHeadData(std::span<const unsigned char> body, std::size_t body_at,
                                    const SeaNetMessageName& name, double sound_speed_m_s) {
  if (body.size() < kSeaNetHeadDataFieldBytes) {
    return defectAt(body_at, "length of " + name.name + " leaves " + std::to_string(body.size()) +
                                 " bytes after the message type, expected at least " +
                                 std::to_string(kSeaNetHeadDataFieldBytes) + " for mtHeadData");
  }
  const std::uint16_t head_control = u16At(body, kHeadControlAt);
  const std::uint8_t ad_span = body[kAdSpanAt];
  const std::uint16_t ad_interval = u16At(body, kAdIntervalAt);
  const std::uint16_t bearing = u16At(body, kBearingAt);
  const std::uint16_t data_bytes = u16At(body, kDataBytesAt);
  const std::size_t left = body.size() - kSeaNetHeadDataFieldBytes;
  if (ad_interval == 0) {
    return defectAt(body_at + kAdIntervalAt,
                    "ADInterval of " + name.name + " is 0, expected > 0 (units of 640 ns; bin length 0 m)");
  }
  if (bearing >= kBearingUnitsPerTurn) {
    return defectAt(body_at + kBearingAt, "bearing of " + name.name + " is " + std::to_string(bearing) +
                                              ", expected 0…6399 (1/16 gradian)");
  }
  if (data_bytes > left) {
    return defectAt(body_at + kDataBytesAt, "data byte count of " + name.name + " is " + std::to_string(data_bytes) +
                                                " but the " + std::string(name.container) + " holds " +
                                                std::to_string(left) + " bytes after its " +
                                                std::to_string(name.header_bytes) + "-byte header");
  }
  SeaNetHeadData result;
  if (data_bytes == 0) {
    result.skip_reason = "mtHeadData with no data bytes";
    return result;
  }
  Beam beam;
  beam.bearing_rad = bearingRad(bearing, (head_control & kHdCtrlInvert) != 0);
  beam.bin_length_m = ad_interval * kAdIntervalUnit_s * sound_speed_m_s / 2.0;
  beam.intensities = unpackBins(body.subspan(kSeaNetHeadDataFieldBytes, data_bytes), (head_control & kHdCtrlAdc8On) != 0);
  beam.gain_setting = body[kGainAt];
  // ADspan counts 80/255 dB (SeaNet's 0…80 dB scale); 0 would be no span at all: leave it unknown.
  if (ad_span > 0) beam.intensity_span_db = ad_span * kAdScale_db / 255.0;
  result.beam = std::move(beam);
  result.trailing_bytes = left - data_bytes;
  return result;
}

}  // namespace sonarmap::detail

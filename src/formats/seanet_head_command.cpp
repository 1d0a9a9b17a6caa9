/// @file seanet_head_command.cpp
/// mtHeadCommand (the V3B "param" command of an imaging head) encoded and decoded, and the
/// frequency words of its TxN and RxN fields (see seanet_protocol.hpp).

#include <cmath>

#include "sonarmap/formats/seanet_protocol.hpp"

namespace sonarmap::seanet {
namespace {

constexpr std::uint8_t kV3BParams = 0x1D;  // the V3B block follows (rock, RobDos, SeaNet Pro)
constexpr std::uint8_t kNoV3BParams = 0x01;  // no block (mcgill: a single-channel head)
constexpr std::size_t kCommandBytes = 52;
constexpr std::size_t kV3BBlockBytes = 16;
constexpr double kSynthesizerClockHz = 32e6;
constexpr double kWordsPerTurn = 4294967296.0;  // 2^32

/// Appends little-endian fields to a payload.
struct Writer {
  std::vector<std::uint8_t> bytes;
  void u8(std::uint8_t value) { bytes.push_back(value); }
  void u16(std::uint16_t value) {
    bytes.push_back(static_cast<std::uint8_t>(value & 0xFF));
    bytes.push_back(static_cast<std::uint8_t>(value >> 8));
  }
  void u32(std::uint32_t value) {
    u16(static_cast<std::uint16_t>(value & 0xFFFF));
    u16(static_cast<std::uint16_t>(value >> 16));
  }
};

/// Reads little-endian fields in order; the caller has checked the size.
struct Reader {
  const std::vector<std::uint8_t>& bytes;
  std::size_t at = 0;
  std::uint8_t u8() { return bytes[at++]; }
  std::uint16_t u16() {
    const std::uint16_t value = static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
    at += 2;
    return value;
  }
  std::uint32_t u32() {
    const std::uint32_t low = u16();
    return low | (static_cast<std::uint32_t>(u16()) << 16);
  }
};

}  // namespace

std::uint32_t frequencyWord(double hz) {
  const double word = std::floor(hz * kWordsPerTurn / kSynthesizerClockHz);
  if (!(word >= 0.0)) return 0;
  return word >= kWordsPerTurn ? 0xFFFFFFFFU : static_cast<std::uint32_t>(word);
}

double frequencyOfWord(std::uint32_t word) { return word * kSynthesizerClockHz / kWordsPerTurn; }

std::vector<std::uint8_t> encodeHeadCommand(const HeadCommand& c, std::uint8_t head_node) {
  Writer w;
  w.u8(c.v3b ? kV3BParams : kNoV3BParams);
  w.u16(c.hd_ctrl);
  w.u8(c.head_type);
  for (const std::uint32_t word : c.tx_n) w.u32(word);
  for (const std::uint32_t word : c.rx_n) w.u32(word);
  w.u16(c.tx_pulse_length);
  w.u16(c.range_scale_dm);
  w.u16(c.left_limit);
  w.u16(c.right_limit);
  w.u8(c.ad_span);
  w.u8(c.ad_low);
  for (const std::uint8_t gain : c.igain) w.u8(gain);
  for (const std::uint16_t slope : c.slope) w.u16(slope);
  w.u8(c.mo_time);
  w.u8(c.step);
  w.u16(c.ad_interval);
  w.u16(c.nbins);
  w.u16(c.max_ad_buf);
  w.u16(c.lockout);
  w.u16(c.minor_axis_dir);
  w.u8(c.major_axis_pan);
  w.u8(c.ctl2);
  w.u16(c.scan_z);
  if (c.v3b) {
    for (const std::uint8_t value : c.ad_span_ch) w.u8(value);
    for (const std::uint8_t value : c.ad_low_ch) w.u8(value);
    for (const std::uint8_t value : c.igain_ch) w.u8(value);
    for (const std::uint8_t value : c.adc_set_point) w.u8(value);
    for (const std::uint16_t value : c.slope_ch) w.u16(value);
    for (const std::uint16_t value : c.slope_delay) w.u16(value);
  }
  return encodePacket(makePacket(MessageType::kHeadCommand, std::move(w.bytes), false, head_node));
}

std::optional<HeadCommand> decodeHeadCommand(const Packet& packet) {
  if (packet.type != static_cast<std::uint8_t>(MessageType::kHeadCommand) || packet.payload.size() < kCommandBytes) {
    return std::nullopt;
  }
  HeadCommand c;
  c.v3b = packet.payload[0] == kV3BParams;
  if (c.v3b && packet.payload.size() < kCommandBytes + kV3BBlockBytes) return std::nullopt;
  Reader r{packet.payload, 1};
  c.hd_ctrl = r.u16();
  c.head_type = r.u8();
  for (std::uint32_t& word : c.tx_n) word = r.u32();
  for (std::uint32_t& word : c.rx_n) word = r.u32();
  c.tx_pulse_length = r.u16();
  c.range_scale_dm = r.u16();
  c.left_limit = r.u16();
  c.right_limit = r.u16();
  c.ad_span = r.u8();
  c.ad_low = r.u8();
  for (std::uint8_t& gain : c.igain) gain = r.u8();
  for (std::uint16_t& slope : c.slope) slope = r.u16();
  c.mo_time = r.u8();
  c.step = r.u8();
  c.ad_interval = r.u16();
  c.nbins = r.u16();
  c.max_ad_buf = r.u16();
  c.lockout = r.u16();
  c.minor_axis_dir = r.u16();
  c.major_axis_pan = r.u8();
  c.ctl2 = r.u8();
  c.scan_z = r.u16();
  if (c.v3b) {
    for (std::uint8_t& value : c.ad_span_ch) value = r.u8();
    for (std::uint8_t& value : c.ad_low_ch) value = r.u8();
    for (std::uint8_t& value : c.igain_ch) value = r.u8();
    for (std::uint8_t& value : c.adc_set_point) value = r.u8();
    for (std::uint16_t& value : c.slope_ch) value = r.u16();
    for (std::uint16_t& value : c.slope_delay) value = r.u16();
  }
  return c;
}

}  // namespace sonarmap::seanet

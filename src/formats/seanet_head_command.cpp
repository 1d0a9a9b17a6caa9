/// @file seanet_head_command.cpp
/// mtHeadCommand (the V3B "param" command of an imaging head) encoded and decoded, and the
/// frequency words of its TxN and RxN fields (see seanet_protocol.hpp).

#include <cmath>
#include <tuple>
#include <utility>

#include "sonarmap/formats/seanet_protocol.hpp"

namespace sonarmap::seanet {
namespace {

constexpr std::uint8_t kV3BParams = 0x1D;  // the V3B block follows (rock, RobDos, SeaNet Pro)
constexpr std::uint8_t kNoV3BParams = 0x01;  // no block (mcgill: a single-channel head)
constexpr std::size_t kCommandBytes = 52;
constexpr std::size_t kV3BBlockBytes = 16;
constexpr double kSynthesizerClockHz = 32e6;
constexpr double kWordsPerTurn = 4294967296.0;  // 2^32

/// Appends little-endian fields to a payload: u8, u16, u32, and arrays of them element by element.
struct Writer {
  std::vector<std::uint8_t> bytes;
  void operator()(std::uint8_t value) { bytes.push_back(value); }
  void operator()(std::uint16_t value) {
    bytes.push_back(static_cast<std::uint8_t>(value & 0xFF));
    bytes.push_back(static_cast<std::uint8_t>(value >> 8));
  }
  void operator()(std::uint32_t value) {
    (*this)(static_cast<std::uint16_t>(value & 0xFFFF));
    (*this)(static_cast<std::uint16_t>(value >> 16));
  }
  template <class T, std::size_t N>
  void operator()(const T (&values)[N]) {
    for (const T& value : values) (*this)(value);
  }
  template <class Field>
  void operator()(const Field&) = delete;  // no other field type has a wire form here
};

/// Reads the fields Writer writes, in order; the caller has checked the size.
struct Reader {
  const std::vector<std::uint8_t>& bytes;
  std::size_t at = 0;
  void operator()(std::uint8_t& value) { value = bytes[at++]; }
  void operator()(std::uint16_t& value) {
    value = static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
    at += 2;
  }
  void operator()(std::uint32_t& value) {
    std::uint16_t low = 0;
    std::uint16_t high = 0;
    (*this)(low);
    (*this)(high);
    value = low | (static_cast<std::uint32_t>(high) << 16);
  }
  template <class T, std::size_t N>
  void operator()(T (&values)[N]) {
    for (T& value : values) (*this)(value);
  }
  template <class Field>
  void operator()(Field&) = delete;
};

/// The fields after V3BParams (payload byte 0), in packet order: the one list encodeHeadCommand
/// writes and decodeHeadCommand reads (`c` a HeadCommand, const or not).
auto commandFields(auto& c) {
  return std::tie(c.hd_ctrl, c.head_type, c.tx_n, c.rx_n, c.tx_pulse_length, c.range_scale_dm, c.left_limit,
                  c.right_limit, c.ad_span, c.ad_low, c.igain, c.slope, c.mo_time, c.step, c.ad_interval, c.nbins,
                  c.max_ad_buf, c.lockout, c.minor_axis_dir, c.major_axis_pan, c.ctl2, c.scan_z);
}

/// The V3B block's fields, after those (when `c.v3b`).
auto v3bBlockFields(auto& c) {
  return std::tie(c.ad_span_ch, c.ad_low_ch, c.igain_ch, c.adc_set_point, c.slope_ch, c.slope_delay);
}

/// Passes each of `fields` (a tuple of references) to `visit` in order.
template <class Fields, class Visit>
void forEachField(const Fields& fields, Visit& visit) {
  std::apply([&](auto&... field) { (visit(field), ...); }, fields);
}

}  // namespace

std::uint32_t frequencyWord(double hz) {
  const double word = std::floor(hz * kWordsPerTurn / kSynthesizerClockHz);
  if (!(word >= 0.0)) return 0;
  return word >= kWordsPerTurn ? 0xFFFFFFFFU : static_cast<std::uint32_t>(word);
}

double frequencyOfWord(std::uint32_t word) { return word * kSynthesizerClockHz / kWordsPerTurn; }

std::vector<std::uint8_t> encodeHeadCommand(const HeadCommand& c, std::uint8_t head_node) {
  Writer w;
  w(c.v3b ? kV3BParams : kNoV3BParams);
  forEachField(commandFields(c), w);
  if (c.v3b) forEachField(v3bBlockFields(c), w);
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
  forEachField(commandFields(c), r);
  if (c.v3b) forEachField(v3bBlockFields(c), r);
  return c;
}

}  // namespace sonarmap::seanet

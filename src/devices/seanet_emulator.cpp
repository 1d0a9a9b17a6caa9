/// @file seanet_emulator.cpp
/// SeaNetEmulator: a SeaNet imaging head answering from the beam simulator (see
/// seanet_emulator.hpp).

#include "sonarmap/devices/seanet_emulator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"

namespace sonarmap {
namespace {

using seanet::MessageType;

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kUnitsPerTurn = 6400.0;
constexpr int kAheadUnits = 3200;
constexpr double kAdIntervalUnit_s = 640e-9;
constexpr double kSimulatedSoundSpeed_m_s = 1500.0;  // sonar_presets.hpp
constexpr double kBootTime_s = 1.0;
constexpr int kMaxBins = 1500;         // rock's limit on NBins
constexpr double kMaxRange_m = 1638.3;  // RangeScale's 14 bits of decimetres
constexpr double kBitsPerByte = 10.0;  // 8N1
// The driver's default command (seanet_driver.hpp): the presets' levels hold for it.
constexpr int kReferenceIGain = 84;
constexpr int kReferenceAdLow = 14;
constexpr int kReferenceAdSpan = 149;

/// The identity of an emulated head.
struct Identity {
  seanet::VersionInfo version;
  bool dual_channel = false;
  std::uint8_t device_type = 2;
};

Identity identityOf(const std::string& preset, std::uint8_t node) {
  Identity identity;
  identity.version.node = node;
  identity.version.node_id = node;
  identity.version.info_bits = 0x01;  // libminiking: a sonar board
  identity.version.program_length = 0x00010000;
  identity.version.checksum = 0x5A5A;
  if (preset == "micron") {
    identity.version.frequency_code = 3;
    identity.version.serial_number = 1001;
    identity.device_type = 0x11;
  } else if (preset == "seaking-30" || preset == "seaking-50") {
    identity.version.frequency_code = 1;
    identity.version.serial_number = 2001;
    identity.dual_channel = true;
  } else {
    throw ValueError("SeaNet emulator: unknown preset '" + preset + "'; expected micron, seaking-30 or seaking-50");
  }
  return identity;
}

std::uint16_t unitsOf(double bearing_rad) {
  const long units = std::lround(bearing_rad * kUnitsPerTurn / kTwoPi) + kAheadUnits;
  return static_cast<std::uint16_t>(((units % 6400) + 6400) % 6400);
}

double radOfUnits(double units) { return units * kTwoPi / kUnitsPerTurn; }

}  // namespace

struct SeaNetEmulator::State {
  MsisBeamSimulator simulator;
  SeaNetEmulatorOptions options;
  Identity identity;
  MsisHeadOptions reference_head;
  EchoModelOptions reference_echo;
  seanet::PacketParser parser;

  std::optional<double> powered_at_s;
  double next_alive_s = 0.0;
  bool has_params = false;
  bool sent_config = false;
  bool in_scan = false;
  seanet::HeadCommand command;
  MsisHeadOptions stepping;  // bearingOf() of the commanded scan
  std::size_t beam_index = 0;
  std::uint16_t motor_units = kAheadUnits;
  double busy_until_s = 0.0;
  std::size_t beams = 0, reboots = 0, head_commands = 0, data_requests = 0;

  State(MsisBeamSimulator sim, SeaNetEmulatorOptions opts)
      : simulator(std::move(sim)), options(std::move(opts)), identity(identityOf(options.preset, options.node)),
        reference_head(simulator.head()), reference_echo(simulator.echo()) {}

  double transfer_s(std::size_t bytes) const { return static_cast<double>(bytes) * kBitsPerByte / options.baud; }

  void powerUp(double now_s) {
    if (powered_at_s) return;
    powered_at_s = now_s;
    next_alive_s = now_s;
  }

  std::uint32_t headTimeMs(double at_s) const {
    return static_cast<std::uint32_t>(std::llround(std::max(0.0, at_s - powered_at_s.value_or(at_s)) * 1000.0));
  }

  std::vector<std::uint8_t> alive(double at_s) const {
    seanet::AliveInfo info;
    info.node = options.node;
    info.head_time_ms = headTimeMs(at_s);
    info.motor_position = motor_units;
    using A = seanet::AliveInfo;
    if (!has_params) info.head_info |= A::kNoParams;
    if (sent_config) info.head_info |= A::kSentConfig;
    // InCentre, not Centred: mcgill reads HeadInf most significant bit first, so its "has config"
    // is InCentre and its "no params" Centred (seanet_emulator.hpp).
    if (has_params && (command.hd_ctrl & seanet::hdctrl::kMotorOff) == 0) info.head_info |= A::kMotorOn | A::kInCentre;
    if (has_params && (command.hd_ctrl & seanet::hdctrl::kScanRight) != 0) info.head_info |= A::kDirection;
    if (in_scan) info.head_info |= A::kInScan;
    if (at_s < busy_until_s) info.head_info |= A::kMotoring;
    return seanet::encodeAlive(info);
  }

  /// Applies a head command to the simulated head; false (nothing changes) when it cannot be.
  bool apply(const seanet::HeadCommand& c) {
    const double range_m = static_cast<double>(c.nbins) * c.ad_interval * kAdIntervalUnit_s * kSimulatedSoundSpeed_m_s / 2.0;
    if (c.nbins == 0 || c.nbins > kMaxBins || c.ad_interval == 0 || c.step == 0 || range_m > kMaxRange_m) return false;
    MsisHeadOptions head = reference_head;
    head.bins = c.nbins;
    head.range_m = range_m;
    EchoModelOptions echo = reference_echo;
    echo.ad_low_db = reference_echo.ad_low_db - (c.igain[0] - kReferenceIGain) * 80.0 / 210.0 +
                     (c.ad_low - kReferenceAdLow) * 80.0 / 255.0;
    echo.ad_span_db = std::max(1.0, reference_echo.ad_span_db + (c.ad_span - kReferenceAdSpan) * 80.0 / 255.0);
    MsisHeadOptions steps = head;
    steps.step_rad = radOfUnits(c.step);
    steps.counter_clockwise = (c.hd_ctrl & seanet::hdctrl::kScanRight) == 0;
    const int width_units = (c.right_limit - c.left_limit + 6400) % 6400;
    const bool continuous = (c.hd_ctrl & seanet::hdctrl::kContinuous) != 0 || width_units == 0;
    steps.start_bearing_rad = 0.0;  // the head centres, then scans from ahead
    steps.sector_width_rad = continuous ? kTwoPi : radOfUnits(std::max(width_units, static_cast<int>(c.step)));
    steps.sector_center_rad = radOfUnits(c.left_limit + 0.5 * width_units - kAheadUnits);
    try {
      steps.validate();
      simulator.setHead(head, echo);
    } catch (const Error&) {
      return false;
    }
    command = c;
    stepping = steps;
    beam_index = 0;
    return true;
  }

  /// One mtHeadData for an mtSendData at `now_s`.
  TimedBytes ping(double now_s) {
    const double start_s = std::max(now_s, busy_until_s);
    const double ping_s = start_s + command.mo_time * 10e-6;
    const double bearing_rad = stepping.bearingOf(beam_index++);
    const Beam beam = simulator.simulate(ping_s, bearing_rad);
    const bool eight_bit = (command.hd_ctrl & seanet::hdctrl::kAdc8On) != 0;
    std::vector<std::uint8_t> data;
    if (eight_bit) {
      data = beam.intensities;
    } else {
      for (std::size_t i = 0; i < beam.intensities.size(); i += 2) {
        const int high = beam.intensities[i] >> 4;
        const int low = i + 1 < beam.intensities.size() ? beam.intensities[i + 1] >> 4 : 0;
        data.push_back(static_cast<std::uint8_t>((high << 4) | low));
      }
    }
    seanet::HeadDataFields fields;
    fields.node = options.node;
    fields.device_type = identity.device_type;
    fields.head_status = eight_bit ? 0x10 : 0x00;
    motor_units = unitsOf(bearing_rad);
    const bool sector = stepping.isSector();
    fields.sweep_code = sector && motor_units == command.left_limit ? 1 : sector && motor_units == command.right_limit ? 2 : 0;
    fields.hd_ctrl = command.hd_ctrl;
    fields.range_scale_dm = command.range_scale_dm;
    fields.tx_n = command.tx_n[(command.hd_ctrl & seanet::hdctrl::kChan2) != 0 ? 1 : 0];
    fields.gain = command.igain[0];
    fields.slope = command.slope[0];
    fields.ad_span = command.ad_span;
    fields.ad_low = command.ad_low;
    fields.ad_interval = command.ad_interval;
    fields.left_limit = command.left_limit;
    fields.right_limit = command.right_limit;
    fields.step = command.step;
    fields.bearing = motor_units;
    std::vector<std::uint8_t> packet = seanet::encodeHeadData(fields, data);
    const double due_s = ping_s + static_cast<double>(command.nbins) * command.ad_interval * kAdIntervalUnit_s +
                         transfer_s(packet.size());
    busy_until_s = due_s;
    ++beams;
    return {due_s, std::move(packet)};
  }

  void onPacket(const seanet::Packet& packet, double now_s, std::vector<TimedBytes>& out) {
    if (packet.rx_node != options.node) return;
    auto reply = [&](std::vector<std::uint8_t> bytes) {
      const double at_s = now_s + transfer_s(bytes.size());
      out.push_back({at_s, std::move(bytes)});
    };
    switch (static_cast<MessageType>(packet.type)) {
      case MessageType::kReBoot:
        ++reboots;
        has_params = sent_config = in_scan = false;
        motor_units = kAheadUnits;
        busy_until_s = now_s;
        next_alive_s = now_s + kBootTime_s;
        break;
      case MessageType::kSendVersion:
        reply(seanet::encodeVersionData(identity.version));
        break;
      case MessageType::kSendBBUser: {
        seanet::BBUserInfo info;
        info.has_motor = true;
        info.dual_synth = identity.dual_channel;
        info.full_duplex = true;
        sent_config = true;
        reply(seanet::encodeBBUserData(info, options.node));
        break;
      }
      case MessageType::kHeadCommand:
        if (const auto c = seanet::decodeHeadCommand(packet); c && apply(*c)) {
          ++head_commands;
          has_params = sent_config = true;
          in_scan = false;
          reply(alive(now_s));
        }
        break;
      case MessageType::kSendData:
        ++data_requests;
        if (has_params) {
          in_scan = true;
          out.push_back(ping(now_s));
        }
        break;
      default:
        break;
    }
  }
};

SeaNetEmulator::SeaNetEmulator(MsisBeamSimulator simulator, SeaNetEmulatorOptions options) {
  if (options.baud == 0) throw ValueError("SeaNet emulator: baud 0; expected a serial rate > 0, e.g. 115200");
  if (!(std::isfinite(options.alive_period_s) && options.alive_period_s > 0.0)) {
    throw ValueError("SeaNet emulator: alive_period_s must be > 0 s");
  }
  state_ = std::make_unique<State>(std::move(simulator), std::move(options));
}

SeaNetEmulator::~SeaNetEmulator() = default;
SeaNetEmulator::SeaNetEmulator(SeaNetEmulator&&) noexcept = default;
SeaNetEmulator& SeaNetEmulator::operator=(SeaNetEmulator&&) noexcept = default;

std::vector<TimedBytes> SeaNetEmulator::receive(std::span<const std::uint8_t> bytes, double now_s) {
  State& s = *state_;
  s.powerUp(now_s);
  std::vector<TimedBytes> out;
  for (const seanet::Packet& packet : s.parser.feed(bytes)) s.onPacket(packet, now_s, out);
  s.parser.takeSkipped();
  std::stable_sort(out.begin(), out.end(), [](const TimedBytes& a, const TimedBytes& b) { return a.at_s < b.at_s; });
  return out;
}

std::vector<TimedBytes> SeaNetEmulator::poll(double now_s) {
  State& s = *state_;
  s.powerUp(now_s);
  std::vector<TimedBytes> out;
  while (s.next_alive_s <= now_s) {
    out.push_back({s.next_alive_s, s.alive(s.next_alive_s)});
    s.next_alive_s += s.options.alive_period_s;
  }
  return out;
}

std::size_t SeaNetEmulator::beamsSent() const { return state_->beams; }

std::string SeaNetEmulator::settingsText() const {
  const State& s = *state_;
  if (!s.has_params) return "no parameters (waiting for mtHeadCommand)";
  const seanet::HeadCommand& c = s.command;
  char text[320];
  std::snprintf(text, sizeof text,
                "range %.1f m (%u dm), %u bins, ADInterval %u (%.2f us), %s %u-%u, step %u, IGain %u, ADSpan %u, "
                "ADLow %u, %s, %s, channel %d",
                s.simulator.head().range_m, c.range_scale_dm, c.nbins, c.ad_interval, c.ad_interval * 0.64,
                s.stepping.isSector() ? "sector" : "continuous, limits", c.left_limit, c.right_limit, c.step,
                c.igain[0], c.ad_span, c.ad_low, (c.hd_ctrl & seanet::hdctrl::kAdc8On) ? "8-bit" : "4-bit",
                (c.hd_ctrl & seanet::hdctrl::kScanRight) ? "clockwise" : "anticlockwise",
                (c.hd_ctrl & seanet::hdctrl::kChan2) ? 2 : 1);
  return text;
}

bool SeaNetEmulator::hasParameters() const { return state_->has_params; }
std::size_t SeaNetEmulator::reboots() const { return state_->reboots; }
std::size_t SeaNetEmulator::headCommands() const { return state_->head_commands; }
std::size_t SeaNetEmulator::dataRequests() const { return state_->data_requests; }

}  // namespace sonarmap

/// @file ping360_emulator.cpp
/// Ping360Emulator: a Ping360's side of ping-protocol over a simulated scene (see
/// ping360_emulator.hpp).

#include "sonarmap/devices/ping360_emulator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/devices/ping360_settings.hpp"
#include "sonarmap/sim/beam_simulator.hpp"

namespace sonarmap {
namespace {

namespace pp = ping_protocol;

/// Ping Viewer's "firmware defaults at boot".
pp::DeviceData bootSettings() { return {1, 0, 0, 32, 80, 740, 1024, {}}; }

/// Why `value` of `field` is outside [low, high], or empty. ASCII: it goes on the wire as a nack's
/// nack_message, which hosts decode as ASCII.
std::string outside(const char* field, long value, long low, long high) {
  if (value >= low && value <= high) return {};
  return std::string(field) + " " + std::to_string(value) + " is outside " + std::to_string(low) + ".." +
         std::to_string(high);
}

/// The first field of a transducer or auto_transmit command outside the json's ranges, or empty.
std::string refusal(int gain, int duration_us, int period, int frequency, int samples) {
  for (std::string why : {outside("gain_setting", gain, 0, 2), outside("transmit_duration", duration_us, 1, 1000),
                          outside("sample_period", period, kPing360MinSamplePeriodTicks, kPing360MaxSamplePeriodTicks),
                          outside("transmit_frequency", frequency, kPing360MinFrequency_khz, kPing360MaxFrequency_khz),
                          outside("number_of_samples", samples, kPing360MinSamples, kPing360MaxSamples)}) {
    if (!why.empty()) return why;
  }
  return {};
}

/// The transmit duration the firmware applies (ping360_settings.hpp).
std::uint16_t appliedDuration(int duration_us, int period) {
  return static_cast<std::uint16_t>(
      std::clamp(duration_us, kPing360MinTransmitDuration_us, std::max(kPing360MinTransmitDuration_us,
                                                                       ping360MaxTransmitDuration_us(period))));
}

}  // namespace

struct Ping360Emulator::State {
  State(Scene scene, Trajectory trajectory, const Eigen::Isometry3d& mounting, std::uint64_t seed,
        const Ping360EmulatorOptions& options_in)
      : options(options_in), device_id(options_in.device_id), settings(bootSettings()),
        simulator(std::move(scene), model().head, model().echo, std::move(trajectory), mounting, seed),
        modelled(settings) {}

  SonarPreset model() const { return ping360EchoModel(settings, options.sound_speed_m_s); }

  /// An auto scan in progress.
  struct AutoScan {
    int start = 0;
    int steps = 0;         ///< sector: steps from start to stop (0: the whole circle)
    int step = 1;          ///< gradians a step
    double delay_s = 0.0;
    std::size_t index = 0;  ///< its next ping
    double next_start_s = 0.0;
  };

  Ping360EmulatorOptions options;
  std::uint8_t device_id;
  pp::DeviceData settings;  ///< the head's state (data unused)
  MsisBeamSimulator simulator;
  pp::DeviceData modelled;  ///< the settings of the simulator's echo model (its angle aside)
  pp::MessageParser parser;
  double busy_until_s = 0.0;
  std::optional<AutoScan> scan;
  std::size_t beams = 0;

  double transfer_s(std::size_t bytes) const {
    return options.baud == 0 ? 0.0 : static_cast<double>(bytes) * 10.0 / options.baud;
  }

  /// When a job received at `now_s` starts: after the one before it.
  double startOf(double now_s) const { return std::max(now_s, busy_until_s); }

  /// `bytes` sent once the head is free after `now_s` and they have crossed the link.
  TimedBytes reply(std::vector<std::uint8_t> bytes, double now_s) {
    busy_until_s = startOf(now_s) + transfer_s(bytes.size());
    return {busy_until_s, std::move(bytes)};
  }

  template <class Body>
  TimedBytes replyWith(const Body& body, double now_s) {
    return reply(pp::encode(body, device_id, 0), now_s);
  }

  /// A nack of message `id` saying `why` (ASCII: nack_message is an ASCII char array).
  TimedBytes nack(std::uint16_t id, const std::string& why, double now_s) {
    return replyWith(pp::Nack{id, pp::messageName(id) + ": " + why}, now_s);
  }

  /// Moves to `angle` from `start_s` and, when `transmit`, pings there: the time the ping is made
  /// (after the travel) and its samples (empty when not transmitting).
  std::pair<double, std::vector<std::uint8_t>> ping(int angle, bool transmit, double start_s) {
    const double travel_s = ping360AngleDistance(settings.angle_grad, angle) * kPing360MotorTurn_s / kPing360GradiansPerTurn;
    settings.angle_grad = static_cast<std::uint16_t>(angle);
    modelled.angle_grad = settings.angle_grad;
    const double ping_s = start_s + travel_s;
    if (!transmit) return {ping_s, {}};
    if (settings.payload() != modelled.payload()) {  // new settings: a new echo model
      const SonarPreset wanted = model();
      simulator.setHead(wanted.head, wanted.echo);
      modelled = settings;
    }
    const Beam beam = simulator.simulate(ping_s, 2.0 * std::numbers::pi * angle / kPing360GradiansPerTurn);
    ++beams;
    return {ping_s, beam.intensities};
  }

  /// The settings of a transducer or auto_transmit command applied.
  template <class Command>
  void apply(const Command& command) {
    settings.gain_setting = command.gain_setting;
    settings.sample_period_ticks = command.sample_period_ticks;
    settings.transmit_frequency_khz = command.transmit_frequency_khz;
    settings.number_of_samples = command.number_of_samples;
    settings.transmit_duration_us = appliedDuration(command.transmit_duration_us, command.sample_period_ticks);
  }

  TimedBytes onTransducer(const pp::Transducer& command, double now_s) {
    std::string why = refusal(command.gain_setting, command.transmit_duration_us, command.sample_period_ticks,
                              command.transmit_frequency_khz, command.number_of_samples);
    if (why.empty()) why = outside("angle", command.angle_grad, 0, kPing360GradiansPerTurn - 1);
    if (!why.empty()) return nack(pp::kTransducer, why, now_s);
    apply(command);
    auto [ping_s, samples] = ping(command.angle_grad, command.transmit != 0, startOf(now_s));
    pp::DeviceData reply = settings;
    reply.data = std::move(samples);
    const double listen_s = reply.data.empty() ? 0.0 : settings.number_of_samples * settings.sample_period_ticks * kPing360Tick_s;
    return reply_at(pp::encode(reply, device_id, 0), ping_s + listen_s);
  }

  TimedBytes reply_at(std::vector<std::uint8_t> bytes, double ready_s) {
    busy_until_s = ready_s + transfer_s(bytes.size());
    return {busy_until_s, std::move(bytes)};
  }

  std::optional<TimedBytes> onAutoTransmit(const pp::AutoTransmit& command, double now_s) {
    std::string why = refusal(command.gain_setting, command.transmit_duration_us, command.sample_period_ticks,
                              command.transmit_frequency_khz, command.number_of_samples);
    if (why.empty()) why = outside("start_angle", command.start_angle_grad, 0, kPing360GradiansPerTurn - 1);
    if (why.empty()) why = outside("stop_angle", command.stop_angle_grad, 0, kPing360GradiansPerTurn - 1);
    if (why.empty()) why = outside("num_steps", command.num_steps, 1, kPing360MaxStepGradians);
    if (why.empty()) why = outside("delay", command.delay_ms, 0, 100);
    if (!why.empty()) return nack(pp::kAutoTransmit, why, now_s);
    apply(command);
    AutoScan auto_scan;
    auto_scan.start = command.start_angle_grad;
    auto_scan.step = command.num_steps;
    const int span = (command.stop_angle_grad - command.start_angle_grad + kPing360GradiansPerTurn) % kPing360GradiansPerTurn;
    auto_scan.steps = (command.stop_angle_grad + 1) % kPing360GradiansPerTurn == command.start_angle_grad ? 0 : span / command.num_steps;
    auto_scan.delay_s = command.delay_ms * 1e-3;
    auto_scan.next_start_s = startOf(now_s);
    scan = auto_scan;
    return std::nullopt;
  }

  int autoAngle(const AutoScan& auto_scan) const {
    if (auto_scan.steps == 0) {
      return static_cast<int>((auto_scan.start + (auto_scan.index % kPing360GradiansPerTurn) * auto_scan.step) %
                              kPing360GradiansPerTurn);
    }
    const auto period = static_cast<std::size_t>(2 * auto_scan.steps);
    const auto k = static_cast<int>(auto_scan.index % period);
    const int position = k <= auto_scan.steps ? k : static_cast<int>(period) - k;
    return (auto_scan.start + position * auto_scan.step) % kPing360GradiansPerTurn;
  }

  /// The auto scan's pings begun by `now_s`.
  void autoPings(double now_s, std::vector<TimedBytes>& out) {
    while (scan && scan->next_start_s <= now_s) {
      const int angle = autoAngle(*scan);
      auto [ping_s, samples] = ping(angle, true, scan->next_start_s);
      pp::AutoDeviceData reply{settings.mode, settings.gain_setting, settings.angle_grad, settings.transmit_duration_us,
                               settings.sample_period_ticks, settings.transmit_frequency_khz,
                               static_cast<std::uint16_t>(scan->start), 0, static_cast<std::uint8_t>(scan->step),
                               static_cast<std::uint8_t>(std::lround(scan->delay_s * 1e3)), settings.number_of_samples,
                               std::move(samples)};
      reply.stop_angle_grad = static_cast<std::uint16_t>(
          scan->steps == 0 ? (scan->start + kPing360GradiansPerTurn - 1) % kPing360GradiansPerTurn
                           : (scan->start + scan->steps * scan->step) % kPing360GradiansPerTurn);
      const double listen_s = settings.number_of_samples * settings.sample_period_ticks * kPing360Tick_s;
      out.push_back(reply_at(pp::encode(reply, device_id, 0), ping_s + listen_s));
      ++scan->index;
      scan->next_start_s = busy_until_s + scan->delay_s;
    }
  }

  std::optional<TimedBytes> onGeneralRequest(const pp::GeneralRequest& request, double now_s) {
    switch (request.requested_id) {
      case pp::kDeviceInformation: return replyWith(options.identity, now_s);
      case pp::kProtocolVersion: return replyWith(options.protocol, now_s);
      case pp::kDeviceData: return replyWith(settings, now_s);
      default:
        return nack(pp::kGeneralRequest, pp::messageName(request.requested_id) + " cannot be requested", now_s);
    }
  }

  std::optional<TimedBytes> handle(const pp::Message& message, double now_s) {
    if (message.id != pp::kGeneralRequest) scan.reset();  // any command but a request ends an auto scan
    std::string why;
    switch (message.id) {
      case pp::kGeneralRequest:
        if (auto request = pp::GeneralRequest::parse(message.payload, &why)) return onGeneralRequest(*request, now_s);
        break;
      case pp::kTransducer:
        if (auto command = pp::Transducer::parse(message.payload, &why)) return onTransducer(*command, now_s);
        break;
      case pp::kAutoTransmit:
        if (auto command = pp::AutoTransmit::parse(message.payload, &why)) return onAutoTransmit(*command, now_s);
        break;
      case pp::kMotorOff:
        if (pp::MotorOff::parse(message.payload, &why)) return replyWith(pp::Ack{pp::kMotorOff}, now_s);
        break;
      case pp::kSetDeviceId:
        if (auto set = pp::SetDeviceId::parse(message.payload, &why)) {
          if (set->id == 0 || set->id == 255) return nack(pp::kSetDeviceId, "id " + std::to_string(set->id) + " is reserved", now_s);
          TimedBytes ack = replyWith(pp::Ack{pp::kSetDeviceId}, now_s);
          device_id = set->id;
          return ack;
        }
        break;
      case pp::kReset:
        if (pp::Reset::parse(message.payload, &why)) {
          settings = bootSettings();
          device_id = options.device_id;
          return std::nullopt;
        }
        break;
      default:
        return nack(message.id, "not a command of this head", now_s);
    }
    return nack(message.id, why, now_s);
  }
};

Ping360Emulator::Ping360Emulator(Scene scene, Trajectory trajectory, const Eigen::Isometry3d& sonar_to_body,
                                 std::uint64_t seed, const Ping360EmulatorOptions& options) {
  if (!(std::isfinite(options.sound_speed_m_s) && options.sound_speed_m_s > 0.0)) {
    throw ValueError("Ping360 emulator: sound speed " + std::to_string(options.sound_speed_m_s) +
                     " m/s, expected positive and finite");
  }
  state_ = std::make_unique<State>(std::move(scene), std::move(trajectory), sonar_to_body, seed, options);
}

Ping360Emulator::~Ping360Emulator() = default;
Ping360Emulator::Ping360Emulator(Ping360Emulator&&) noexcept = default;
Ping360Emulator& Ping360Emulator::operator=(Ping360Emulator&&) noexcept = default;

std::vector<TimedBytes> Ping360Emulator::receive(std::span<const std::uint8_t> bytes, double now_s) {
  State& s = *state_;
  std::vector<TimedBytes> out;
  s.autoPings(now_s, out);
  for (const pp::Message& message : s.parser.feed(bytes)) {
    if (std::optional<TimedBytes> reply = s.handle(message, now_s)) out.push_back(std::move(*reply));
  }
  s.parser.takeSkipReasons();
  return out;
}

std::vector<TimedBytes> Ping360Emulator::poll(double now_s) {
  std::vector<TimedBytes> out;
  state_->autoPings(now_s, out);
  return out;
}

std::size_t Ping360Emulator::beamsSent() const { return state_->beams; }

pp::DeviceData Ping360Emulator::state() const { return state_->settings; }

std::string Ping360Emulator::settingsText() const {
  const State& s = *state_;
  const pp::DeviceData& d = s.settings;
  char text[256];
  std::snprintf(text, sizeof text, "range %.4g m (%d samples of %d ticks), gain %d, angle %d grad, transmit %d us, %d kHz",
                d.number_of_samples * d.sample_period_ticks * kPing360Tick_s * s.options.sound_speed_m_s / 2.0,
                d.number_of_samples, d.sample_period_ticks, d.gain_setting, d.angle_grad, d.transmit_duration_us,
                d.transmit_frequency_khz);
  std::string line = text;
  if (s.scan) {
    const int stop = s.scan->steps == 0 ? (s.scan->start + kPing360GradiansPerTurn - 1) % kPing360GradiansPerTurn
                                        : (s.scan->start + s.scan->steps * s.scan->step) % kPing360GradiansPerTurn;
    line += ", auto-transmit " + std::to_string(s.scan->start) + ".." + std::to_string(stop) + " grad by " +
            std::to_string(s.scan->step);
  }
  return line;
}

}  // namespace sonarmap

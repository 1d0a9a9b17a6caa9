/// @file ping360_driver.cpp
/// Ping360Driver: the Ping360's ping-protocol conversation (see ping360_driver.hpp).

#include "sonarmap/devices/ping360_driver.hpp"

#include <algorithm>
#include <bit>
#include <deque>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>

#include "sonarmap/formats/ping_protocol.hpp"

namespace sonarmap {
namespace {

namespace pp = ping_protocol;

/// Whether a repeated condition seen `count` times is said now: at the 1st, 2nd, 4th, 8th… time,
/// so that a lasting fault is said a few times, less and less often.
bool saidAt(std::size_t count) { return std::has_single_bit(count); }

constexpr double kIdentityRetry_s = 0.5;  ///< ping-python's request timeout
constexpr double kNackRetry_s = 1.0;
constexpr double kLatency_s = 0.2;        ///< Ping Viewer: "use 200ms for network delay"
constexpr double kNoteInterval_s = 1.0;   ///< skipped bytes and motor_off: at most one a second
constexpr std::size_t kReplyOverheadBytes = pp::kHeaderBytes + 14 + pp::kChecksumBytes;  ///< device_data's fields

std::string seconds(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

void append(std::vector<std::uint8_t>& out, const std::vector<std::uint8_t>& bytes) {
  out.insert(out.end(), bytes.begin(), bytes.end());
}

}  // namespace

struct Ping360Driver::State {
  enum class Phase { kIdle, kIdentifying, kScanning, kStopped };

  Ping360Settings settings;
  Ping360DriverOptions options;
  pp::MessageParser parser;
  Phase phase = Phase::kIdle;
  std::string device;
  bool heard = false;

  std::size_t index = 0;         ///< the scan's ping the pending command asks for
  bool pending = false;          ///< a transducer command awaits its device_data
  int pending_angle = 0;
  double deadline_s = 0.0;
  double timeout_used_s = 0.0;    ///< the pending command's timeout
  std::optional<int> head_angle;  ///< where the head last said it was
  std::size_t identity_requests = 0;
  double identity_deadline_s = 0.0;
  std::size_t repeats = 0;
  std::size_t unanswered = 0;    ///< transducer commands sent again since the last reply
  double last_reply_s = -1.0;    ///< the last device_data that answered a command (−1: none yet)
  std::size_t foreign = 0;       ///< device_data at an angle no command of ours asked for
  std::size_t late = 0;          ///< device_data answering an earlier command of ours (sent again)
  static constexpr std::size_t kCommandedKept = 8;
  std::deque<int> commanded;     ///< the angles of our last kCommandedKept transducer commands
  std::optional<pp::DeviceData> reported;  ///< the last reply's settings (its data dropped)

  double last_motor_off_s = -std::numeric_limits<double>::infinity();
  double last_skip_note_s = -std::numeric_limits<double>::infinity();
  std::string first_skip;       ///< the first skip line not yet noted
  std::size_t skips_unnoted = 0;
  std::set<std::string> noted;  ///< notes given once

  void noteOnce(DriverOutput& out, const std::string& note) {
    if (noted.insert(note).second) out.notes.push_back(note);
  }

  std::vector<std::uint8_t> transducer(int angle) const {
    pp::Transducer command;
    command.mode = 1;
    command.gain_setting = settings.gain_setting;
    command.angle_grad = static_cast<std::uint16_t>(angle);
    command.transmit_duration_us = settings.transmit_duration_us;
    command.sample_period_ticks = settings.sampling.sample_period_ticks;
    command.transmit_frequency_khz = settings.transmit_frequency_khz;
    command.number_of_samples = settings.sampling.samples;
    command.transmit = 1;
    return pp::encode(command);
  }

  double timeout_s(int travel_grad) const {
    const double travel_s = travel_grad * kPing360SlowMotorTurn_s / kPing360GradiansPerTurn;
    const double listen_s = settings.sampling.samples * settings.sampling.sample_period_ticks * kPing360Tick_s +
                            settings.transmit_duration_us * 1e-6;
    const double transfer_s = options.link_baud == 0
                                  ? 0.0
                                  : static_cast<double>(settings.sampling.samples + kReplyOverheadBytes) * 10.0 /
                                        options.link_baud;
    return std::min(kPing360MaxReply_s, travel_s + listen_s + transfer_s + kLatency_s);
  }

  /// Sends the command of ping `index` (again, when it is pending).
  void sendPing(DriverOutput& out, double now_s) {
    pending_angle = settings.angleOf(index);
    const int travel = head_angle ? ping360AngleDistance(*head_angle, pending_angle) : kPing360GradiansPerTurn / 2;
    pending = true;
    commanded.push_back(pending_angle);
    if (commanded.size() > kCommandedKept) commanded.pop_front();
    timeout_used_s = timeout_s(travel);
    deadline_s = now_s + timeout_used_s;
    append(out.send, transducer(pending_angle));
  }

  void requestIdentity(DriverOutput& out, double now_s) {
    append(out.send, pp::encode(pp::GeneralRequest{pp::kProtocolVersion}));
    append(out.send, pp::encode(pp::GeneralRequest{pp::kDeviceInformation}));
    ++identity_requests;
    identity_deadline_s = now_s + kIdentityRetry_s;
  }

  void beginScan(DriverOutput& out, double now_s) {
    if (phase != Phase::kIdentifying) return;
    phase = Phase::kScanning;
    sendPing(out, now_s);
  }

  void noteSkips(DriverOutput& out, double now_s) {
    for (std::string& reason : parser.takeSkipReasons()) {
      if (skips_unnoted++ == 0) first_skip = std::move(reason);
    }
    if (skips_unnoted == 0 || now_s - last_skip_note_s < kNoteInterval_s) return;
    std::string note = "Ping360 link: " + first_skip;
    if (skips_unnoted > 1) note += " (and " + std::to_string(skips_unnoted - 1) + " more skipped runs)";
    out.notes.push_back(note);
    skips_unnoted = 0;
    last_skip_note_s = now_s;
  }

  void checkReported(DriverOutput& out, const pp::DeviceData& ping) {
    const auto differs = [&](const char* field, int got, int asked) {
      if (got != asked) {
        noteOnce(out, "the Ping360 applied " + std::string(field) + " " + std::to_string(got) + " (asked " +
                          std::to_string(asked) + ")");
      }
    };
    differs("gain_setting", ping.gain_setting, settings.gain_setting);
    differs("transmit_duration_us", ping.transmit_duration_us, settings.transmit_duration_us);
    differs("sample_period_ticks", ping.sample_period_ticks, settings.sampling.sample_period_ticks);
    differs("transmit_frequency_khz", ping.transmit_frequency_khz, settings.transmit_frequency_khz);
    differs("number_of_samples", ping.number_of_samples, settings.sampling.samples);
  }

  void onPing(DriverOutput& out, const pp::DeviceData& ping, double now_s) {
    if (ping.data.empty()) return;  // a reply without a ping (transmit 0, a general request)
    head_angle = ping.angle_grad;
    std::string why;
    std::optional<Beam> beam = pp::ping360Beam(ping, settings.sound_speed_m_s, &why);
    if (!beam) {
      out.notes.push_back("Ping360 device_data dropped: " + why);
      return;
    }
    checkReported(out, ping);
    reported = ping;
    reported->data.clear();
    if (!pending || ping.angle_grad != pending_angle) {
      if (std::find(commanded.begin(), commanded.end(), ping.angle_grad) != commanded.end()) {
        // the reply to a command of ours that was sent again: said at the 1st, 2nd, 4th... such reply
        ++late;
        if (saidAt(late)) {
          out.notes.push_back("Ping360 device_data at " + std::to_string(ping.angle_grad) + " grad while waiting for " +
                              std::to_string(pending_angle) + " grad (the reply to a command sent again; " +
                              std::to_string(late) + " so far): dropped");
        }
        return;
      }
      // A reply no command of ours asked for: another program (Ping Viewer, a second live) commands
      // the head through the same proxy, and the two take turns. Said at the 1st, 2nd, 4th... such reply.
      ++foreign;
      if (saidAt(foreign)) {
        out.notes.push_back("Ping360 device_data at " + std::to_string(ping.angle_grad) + " grad, " +
                            (pending ? "not the " + std::to_string(pending_angle) + " grad commanded" : "with no command waiting") +
                            ": another program is commanding the head (" + std::to_string(foreign) +
                            (foreign == 1 ? " such reply" : " such replies") + " so far, dropped); stop it or run with --listen-only");
      }
      return;
    }
    out.beams.push_back(std::move(*beam));
    pending = false;
    unanswered = 0;
    last_reply_s = now_s;
    ++index;
    if (phase == Phase::kScanning) sendPing(out, now_s);
  }

  void onAutoPing(DriverOutput& out, const pp::AutoDeviceData& automatic, double now_s) {
    std::string why;
    std::optional<Beam> beam = pp::ping360Beam(automatic.deviceData(), settings.sound_speed_m_s, &why);
    if (beam) {
      head_angle = automatic.angle_grad;
      out.beams.push_back(std::move(*beam));
    } else if (!automatic.data.empty()) {
      out.notes.push_back("Ping360 auto_device_data dropped: " + why);
    }
    if (phase == Phase::kStopped || now_s - last_motor_off_s < kNoteInterval_s) return;
    noteOnce(out, "the Ping360 is in auto-transmit mode (auto_device_data): its pings are used, and motor_off sent "
                  "to end it");
    append(out.send, pp::encode(pp::MotorOff{}));
    last_motor_off_s = now_s;
  }

  void onNack(DriverOutput& out, const pp::Nack& nack, double now_s) {
    out.notes.push_back("the Ping360 refused " + pp::messageName(nack.nacked_id) +
                        (nack.text.empty() ? "" : ": " + nack.text));
    if (nack.nacked_id == pp::kGeneralRequest) beginScan(out, now_s);
    if (nack.nacked_id == pp::kTransducer && pending) deadline_s = std::min(deadline_s, now_s + kNackRetry_s);
  }

  void handle(DriverOutput& out, const pp::Message& message, double now_s) {
    std::string why;
    switch (message.id) {
      case pp::kDeviceData:
        if (auto ping = pp::DeviceData::parse(message.payload, &why)) onPing(out, *ping, now_s);
        break;
      case pp::kAutoDeviceData:
        if (auto automatic = pp::AutoDeviceData::parse(message.payload, &why)) onAutoPing(out, *automatic, now_s);
        break;
      case pp::kDeviceInformation:
        if (auto info = pp::DeviceInformation::parse(message.payload, &why)) {
          if (device != info->text()) out.notes.push_back("found " + info->text());
          device = info->text();
          if (info->device_type != 2) {
            noteOnce(out, "device type " + std::to_string(info->device_type) + " is not a Ping360 (2): driven as one");
          }
          beginScan(out, now_s);
        }
        break;
      case pp::kProtocolVersion:
        if (auto version = pp::ProtocolVersion::parse(message.payload, &why)) {
          noteOnce(out, "ping-protocol " + std::to_string(version->version_major) + "." +
                            std::to_string(version->version_minor) + "." + std::to_string(version->version_patch));
        }
        break;
      case pp::kNack:
        if (auto nack = pp::Nack::parse(message.payload, &why)) onNack(out, *nack, now_s);
        break;
      case pp::kAsciiText:
        out.notes.push_back("the Ping360 says: " + pp::AsciiText::parse(message.payload)->text);
        break;
      case pp::kAck:
        return;
      default:
        noteOnce(out, "ignored " + pp::messageName(message.id) + " from the Ping360");
        return;
    }
    if (!why.empty()) out.notes.push_back("Ping360 " + pp::messageName(message.id) + " dropped: " + why);
  }
};

Ping360Driver::Ping360Driver(const HeadSettings& settings, const Ping360DriverOptions& options)
    : state_(std::make_unique<State>()) {
  state_->settings = ping360Settings(settings);
  state_->options = options;
}

Ping360Driver::~Ping360Driver() = default;

DriverOutput Ping360Driver::start(double now_s) {
  DriverOutput out;
  State& s = *state_;
  if (s.phase != State::Phase::kIdle) return out;
  s.phase = State::Phase::kIdentifying;
  out.notes = s.settings.notes;  // what the settings rounded to the head's units
  s.requestIdentity(out, now_s);
  return out;
}

DriverOutput Ping360Driver::receive(std::span<const std::uint8_t> bytes, double now_s) {
  DriverOutput out;
  State& s = *state_;
  const std::vector<pp::Message> messages = s.parser.feed(bytes);
  s.heard = s.heard || !messages.empty();
  for (const pp::Message& message : messages) s.handle(out, message, now_s);
  s.noteSkips(out, now_s);
  if (s.phase == State::Phase::kStopped) out.send.clear();
  return out;
}

DriverOutput Ping360Driver::poll(double now_s) {
  DriverOutput out;
  State& s = *state_;
  if (s.phase == State::Phase::kIdentifying && now_s >= s.identity_deadline_s) {
    const std::size_t asked = s.identity_requests;
    if (saidAt(asked)) {  // after 1, 2, 4, 8... unanswered requests
      out.notes.push_back("no device_information from the Ping360 after " + std::to_string(asked) +
                          (asked == 1 ? " request" : " requests") + ": asking again");
    }
    s.requestIdentity(out, now_s);
  } else if (s.phase == State::Phase::kScanning && s.pending && now_s >= s.deadline_s) {
    ++s.repeats;
    ++s.unanswered;
    if (saidAt(s.unanswered)) {
      const std::string since = s.last_reply_s < 0.0 ? "no reply yet" : "head silent for " + seconds(now_s - s.last_reply_s) + " s";
      out.notes.push_back("no device_data for " + std::to_string(s.pending_angle) + " grad from the Ping360 in time (" +
                          seconds(s.timeout_used_s) + " s; " + since + "): command sent again (" +
                          std::to_string(s.unanswered) + " in a row, " + std::to_string(s.repeats) + " in all)");
    }
    s.sendPing(out, now_s);
  }
  s.noteSkips(out, now_s);
  return out;
}

std::vector<std::uint8_t> Ping360Driver::stop() {
  state_->phase = State::Phase::kStopped;  // a reply already on its way still gives its beam
  return pp::encode(pp::MotorOff{});
}

AppliedSettings Ping360Driver::applied() const {
  const State& s = *state_;
  if (!s.reported) return s.settings.applied();
  Ping360Settings head = s.settings;
  head.gain_setting = s.reported->gain_setting;
  head.transmit_duration_us = s.reported->transmit_duration_us;
  head.sampling.sample_period_ticks = s.reported->sample_period_ticks;
  head.sampling.samples = s.reported->number_of_samples;
  head.transmit_frequency_khz = s.reported->transmit_frequency_khz;
  return head.applied();
}

std::string Ping360Driver::device() const { return state_->device; }
bool Ping360Driver::heard() const { return state_->heard; }
const Ping360Settings& Ping360Driver::settings() const { return state_->settings; }
std::size_t Ping360Driver::repeats() const { return state_->repeats; }
double Ping360Driver::replyTimeout_s(int travel_grad) const { return state_->timeout_s(travel_grad); }

}  // namespace sonarmap

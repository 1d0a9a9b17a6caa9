/// @file seanet_driver.cpp
/// SeaNetDriver: the host's conversation with a SeaNet imaging head (see seanet_driver.hpp).

#include "sonarmap/devices/seanet_driver.hpp"

#include <chrono>
#include <utility>

#include "seanet_settings.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"

namespace sonarmap {
namespace {

using seanet::MessageType;

constexpr double kRebootRepeat_s = 5.0;     // no mtAlive after mtReBoot
constexpr double kQuestionRepeat_s = 1.0;   // mtSendVersion / mtSendBBUser unanswered (RobDos: 1 s)
constexpr int kBBUserTries = 3;
constexpr double kConfigureRepeat_s = 5.0;  // no confirming mtAlive (RobDos: 5 s)
constexpr double kStaleAlive_s = 2.0;       // an mtAlive saying NoParams this long after the command
constexpr double kReplyTimeout_s = 1.0;     // + twice the listening time (mcgill: 1 s)
constexpr int kTimeoutsBeforeReconfigure = 5;  // mcgill
constexpr std::uint8_t kMotorErrorStatus = 1U << 1;

enum class Stage { kIdle, kRebooting, kAskingVersion, kAskingUser, kConfiguring, kScanning, kStopped };

std::uint32_t utcTimeOfDayMs() {
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  return static_cast<std::uint32_t>(std::chrono::duration_cast<std::chrono::milliseconds>(now).count() % 86'400'000);
}

void append(std::vector<std::uint8_t>& out, const std::vector<std::uint8_t>& bytes) {
  out.insert(out.end(), bytes.begin(), bytes.end());
}

}  // namespace

struct SeaNetDriver::State {
  SeaNetDriverOptions options;
  detail::SeaNetHeadKnowledge head;
  detail::SeaNetPlan plan;
  seanet::PacketParser parser;
  Stage stage = Stage::kIdle;
  double sent_at_s = 0.0;  // the last command of the current stage
  int tries = 0;           // of the current stage's command
  int timeouts_in_row = 0;
  int head_commands = 0;
  bool heard = false;

  std::vector<std::uint8_t> simple(MessageType type) const { return seanet::encodeSimpleCommand(type, options.head_node); }

  void ask(DriverOutput& out, Stage next, MessageType type, double now_s) {
    append(out.send, simple(type));
    stage = next;
    sent_at_s = now_s;
    tries = 1;
  }

  void sendHeadCommand(DriverOutput& out, double now_s, const std::string& why) {
    plan = detail::planSeaNetCommand(options, head);
    for (const std::string& note : plan.notes) out.notes.push_back(note);
    append(out.send, seanet::encodeHeadCommand(plan.command, options.head_node));
    ++head_commands;
    out.notes.push_back("mtHeadCommand sent (" + why + "): " + plan.applied.text());
    stage = Stage::kConfiguring;
    sent_at_s = now_s;
    timeouts_in_row = 0;
  }

  void requestBeam(DriverOutput& out, double now_s) {
    const std::uint32_t time_ms = options.time_of_day_ms ? options.time_of_day_ms() : utcTimeOfDayMs();
    append(out.send, seanet::encodeSendData(time_ms, options.head_node));
    sent_at_s = now_s;
  }

  double replyTimeout() const { return kReplyTimeout_s + 2.0 * plan.listening_s; }

  void onAlive(const seanet::AliveInfo& alive, DriverOutput& out, double now_s) {
    const bool params_in = !alive.has(seanet::AliveInfo::kNoParams) && alive.has(seanet::AliveInfo::kSentConfig);
    switch (stage) {
      case Stage::kRebooting:
        out.notes.push_back("mtAlive heard (" + alive.describe() + ")");
        ask(out, Stage::kAskingVersion, MessageType::kSendVersion, now_s);
        break;
      case Stage::kConfiguring:
        if (params_in) {
          stage = Stage::kScanning;
          timeouts_in_row = 0;
          out.notes.push_back("the head has its parameters (" + alive.describe() + "): scanning");
          requestBeam(out, now_s);
        } else if (alive.has(seanet::AliveInfo::kNoParams) && now_s - sent_at_s >= kStaleAlive_s) {
          sendHeadCommand(out, now_s, "the head still has no parameters");
        }
        break;
      case Stage::kScanning:
        if (alive.has(seanet::AliveInfo::kNoParams)) {
          sendHeadCommand(out, now_s, "the head reports no parameters: rebooted or lost power");
        }
        break;
      default:
        break;
    }
  }

  void onHeadData(const seanet::Packet& packet, DriverOutput& out, double now_s) {
    if (stage != Stage::kScanning) return;  // a late reply to a request before a reconfiguration
    seanet::HeadDataReply reply = seanet::decodeHeadData(packet, options.settings.sound_speed_m_s);
    timeouts_in_row = 0;
    if (reply.beam) {
      out.beams.push_back(std::move(*reply.beam));
    } else {
      out.notes.push_back("mtHeadData without a beam: " + reply.problem);
    }
    if (reply.fields && (reply.fields->head_status & kMotorErrorStatus) != 0) {
      sendHeadCommand(out, now_s, "the head's motor lost sync");
      return;
    }
    requestBeam(out, now_s);
  }

  void onPacket(const seanet::Packet& packet, DriverOutput& out, double now_s) {
    // Only the head's own packets: a half-duplex RS-485 line also echoes the host's commands.
    if (packet.tx_node != options.head_node) return;
    heard = true;
    switch (static_cast<MessageType>(packet.type)) {
      case MessageType::kAlive:
        if (const auto alive = seanet::decodeAlive(packet)) onAlive(*alive, out, now_s);
        break;
      case MessageType::kVersionData:
        if (const auto version = seanet::decodeVersionData(packet)) {
          head.version = version;
          if (stage == Stage::kAskingVersion) {
            out.notes.push_back("mtVersionData: " + version->describe());
            ask(out, Stage::kAskingUser, MessageType::kSendBBUser, now_s);
          }
        }
        break;
      case MessageType::kBBUserData:
        if (const auto user = seanet::decodeBBUserData(packet)) {
          head.user = user;
          if (stage == Stage::kAskingUser) {
            out.notes.push_back(std::string("mtBBUserData: ") + (user->dual_synth ? "two channels" : "one channel") +
                                (user->full_duplex ? (*user->full_duplex ? ", full duplex" : ", half duplex") : ""));
            sendHeadCommand(out, now_s, "settings");
          }
        }
        break;
      case MessageType::kHeadData:
        onHeadData(packet, out, now_s);
        break;
      default:
        break;
    }
  }
};

SeaNetDriver::SeaNetDriver(SeaNetDriverOptions options) : state_(std::make_unique<State>()) {
  state_->options = std::move(options);
  state_->plan = detail::planSeaNetCommand(state_->options, state_->head);  // throws for bad settings
}

SeaNetDriver::~SeaNetDriver() = default;
SeaNetDriver::SeaNetDriver(SeaNetDriver&&) noexcept = default;
SeaNetDriver& SeaNetDriver::operator=(SeaNetDriver&&) noexcept = default;

DriverOutput SeaNetDriver::start(double now_s) {
  DriverOutput out;
  if (state_->stage == Stage::kStopped) return out;
  state_->ask(out, Stage::kRebooting, MessageType::kReBoot, now_s);
  out.notes.push_back("mtReBoot sent; waiting for the head's mtAlive");
  return out;
}

DriverOutput SeaNetDriver::receive(std::span<const std::uint8_t> bytes, double now_s) {
  DriverOutput out;
  for (const seanet::Packet& packet : state_->parser.feed(bytes)) {
    if (state_->stage == Stage::kStopped) break;
    state_->onPacket(packet, out, now_s);
  }
  return out;
}

DriverOutput SeaNetDriver::poll(double now_s) {
  DriverOutput out;
  State& s = *state_;
  const double waited_s = now_s - s.sent_at_s;
  switch (s.stage) {
    case Stage::kRebooting:
      if (waited_s >= kRebootRepeat_s) {
        out.notes.push_back("no mtAlive for 5 s: mtReBoot repeated");
        s.ask(out, Stage::kRebooting, MessageType::kReBoot, now_s);
      }
      break;
    case Stage::kAskingVersion:
      if (waited_s >= kQuestionRepeat_s) {
        append(out.send, s.simple(MessageType::kSendVersion));
        s.sent_at_s = now_s;
        ++s.tries;
      }
      break;
    case Stage::kAskingUser:
      if (waited_s >= kQuestionRepeat_s) {
        if (s.tries >= kBBUserTries) {
          out.notes.push_back("no mtBBUserData after 3 mtSendBBUser: going on without it (one channel assumed)");
          s.sendHeadCommand(out, now_s, "settings");
        } else {
          append(out.send, s.simple(MessageType::kSendBBUser));
          s.sent_at_s = now_s;
          ++s.tries;
        }
      }
      break;
    case Stage::kConfiguring:
      if (waited_s >= kConfigureRepeat_s) s.sendHeadCommand(out, now_s, "no mtAlive confirmed the parameters in 5 s");
      break;
    case Stage::kScanning:
      if (waited_s >= s.replyTimeout()) {
        if (++s.timeouts_in_row >= kTimeoutsBeforeReconfigure) {
          s.sendHeadCommand(out, now_s, "5 mtHeadData overdue in a row");
        } else {
          out.notes.push_back("mtHeadData overdue: mtSendData repeated");
          s.requestBeam(out, now_s);
        }
      }
      break;
    default:
      break;
  }
  return out;
}

std::vector<std::uint8_t> SeaNetDriver::stop() {
  state_->stage = Stage::kStopped;
  return state_->simple(MessageType::kReBoot);
}

AppliedSettings SeaNetDriver::applied() const { return state_->plan.applied; }

std::string SeaNetDriver::device() const {
  return state_->head.version ? state_->head.version->describe() : std::string();
}

bool SeaNetDriver::heard() const { return state_->heard; }
bool SeaNetDriver::scanning() const { return state_->stage == Stage::kScanning; }
int SeaNetDriver::headCommandsSent() const { return state_->head_commands; }

}  // namespace sonarmap

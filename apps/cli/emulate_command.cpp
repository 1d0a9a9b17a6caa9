#include "emulate_command.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <optional>

#include <poll.h>

#include "help_groups.hpp"
#include "simulate_command.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/devices/autopilot_emulator.hpp"
#include "sonarmap/devices/heads.hpp"
#include "sonarmap/live/byte_link.hpp"
#include "sonarmap/sim/missions.hpp"

namespace sonarmap::cli {
namespace {

volatile std::sig_atomic_t g_stop = 0;  // set by SIGINT / SIGTERM

extern "C" void onEmulateStopSignal(int) { g_stop = 1; }

/// SIGINT and SIGTERM set g_stop and interrupt poll() (no SA_RESTART).
void catchStopSignals() {
  struct sigaction action {};
  action.sa_handler = onEmulateStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

using Clock = std::chrono::steady_clock;

/// One emulated head on one link, and the bytes it has yet to send.
struct ServedHead {
  ServedHead(const std::string& spec, unsigned baud, std::unique_ptr<HeadEmulator> emulator)
      : link(spec, baud), head(std::move(emulator)) {}

  ByteLink link;
  std::unique_ptr<HeadEmulator> head;
  std::deque<TimedBytes> due;  ///< in order of their times
  std::size_t dropped = 0;     ///< messages nobody could take (no UDP peer yet, a full pty)

  void queue(std::vector<TimedBytes> replies) {
    for (TimedBytes& reply : replies) due.push_back(std::move(reply));
    std::stable_sort(due.begin(), due.end(), [](const TimedBytes& a, const TimedBytes& b) { return a.at_s < b.at_s; });
  }

  /// Writes what is due by `now_s`, each message whole (one datagram on UDP). A message the link
  /// cannot take now is lost, as a real head's bytes are when nobody listens.
  void send(double now_s) {
    while (!due.empty() && due.front().at_s <= now_s) {
      pollfd room{link.fd(), POLLOUT, 0};
      if (::poll(&room, 1, 0) <= 0 || (room.revents & POLLOUT) == 0 || !link.write(due.front().bytes)) ++dropped;
      due.pop_front();
    }
  }
};

void check(const EmulateArgs& args, MsisSimulationOptions& run) {
  const std::vector<std::string> names = emulatedHeadNames();
  if (std::find(names.begin(), names.end(), args.sonar) == names.end()) {
    throw ValueError("--sonar " + args.sonar + " cannot be emulated: expected one of " + joined(names, ", "));
  }
  if (!isBuiltinSceneName(args.scene) && !std::filesystem::exists(args.scene)) {
    throw ValueError("--scene '" + args.scene + "' is neither a built-in scene (" + joined(allBuiltinSceneNames(), ", ") +
                     ") nor a scene file");
  }
  if (args.serial.empty() && args.udp.empty()) {
    throw ValueError("no link to serve the head on: give --serial pty:PATH and/or --udp udp://:PORT");
  }
  if (!(std::isfinite(args.duration_s) && args.duration_s >= 0.0)) {
    throw ValueError("--duration " + std::to_string(args.duration_s) + " s, expected ≥ 0 (0: until stopped)");
  }
  if (!(std::isfinite(args.nav_rate_hz) && args.nav_rate_hz > 0.0 && args.nav_rate_hz <= 100.0)) {
    throw ValueError("--nav-rate must be in (0, 100] Hz");
  }
  if (!(std::isfinite(args.time_scale) && args.time_scale >= 0.1 && args.time_scale <= 100.0)) {
    throw ValueError("--time-scale must be within 0.1 .. 100");
  }
  if (args.no_position && args.mavlink.empty()) throw ValueError("--no-position shapes --mavlink's navigation: give --mavlink");
  checkMissionScene(args, args.scene);
  run = toSimulationOptions(args, args.scene);
}

/// The vehicle's navigation sent as ArduSub sends it: every 1 / rate of the emulated time, the pose
/// of the trajectory then; its boot clock is the wall clock, as the receiving end times arrivals.
/// On a listening link (udp://:PORT) it is served as BlueOS's MAVLink "UDP Server" endpoints serve
/// it: to the clients that have sent a datagram (ByteLink), whose datagrams are read and counted.
struct ServedAutopilot {
  ServedAutopilot(const std::string& spec, const AutopilotEmulatorOptions& options) : link(spec, 115200), autopilot(options) {}
  ByteLink link;
  AutopilotEmulator autopilot;
  double next_s = 0.0;   ///< emulated time of the next update
  std::size_t updates = 0, dropped = 0, heard = 0;
};

void run(const EmulateArgs& args, const MsisSimulationOptions& options) {
  EmulatedHeadPlace place;
  place.scene = sceneOf(args.scene, options.head);
  place.trajectory = options.trajectory;
  place.sonar_to_body = options.sonar_to_body;
  place.seed = options.seed;
  place.sound_speed_m_s = args.sound_speed_m_s;
  std::vector<std::unique_ptr<ServedHead>> heads;
  for (const std::string& spec : args.serial) {
    place.baud = args.baud;
    heads.push_back(std::make_unique<ServedHead>(spec, args.baud, makeHeadEmulator(args.sonar, place)));
  }
  for (const std::string& spec : args.udp) {
    place.baud = 0;
    heads.push_back(std::make_unique<ServedHead>(spec, args.baud, makeHeadEmulator(args.sonar, place)));
  }
  std::optional<ServedAutopilot> autopilot;
  if (!args.mavlink.empty()) {
    AutopilotEmulatorOptions autopilot_options;
    autopilot_options.position = !args.no_position;
    autopilot.emplace(args.mavlink, autopilot_options);
  }
  g_stop = 0;
  catchStopSignals();
  for (const auto& served : heads) {
    std::fprintf(stderr, "sonarmap: emulate: %s in %s (built for %g m) on %s\n", args.sonar.c_str(), args.scene.c_str(),
                 options.head.range_m, served->link.description().c_str());
  }
  if (autopilot) {
    std::fprintf(stderr, "sonarmap: emulate: the vehicle's navigation as MAVLink at %g Hz%s to %s\n", args.nav_rate_hz,
                 args.no_position ? " (attitude and depth: no position)" : "", autopilot->link.description().c_str());
  }
  std::fflush(stderr);
  const Clock::time_point start = Clock::now();
  const auto wall_s = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  // The emulated clock: the heads' and the trajectory's, args.time_scale times the wall clock.
  const auto now_s = [&] { return args.time_scale * wall_s(); };
  std::array<std::uint8_t, 65536> buffer{};
  while (g_stop == 0 && (args.duration_s == 0.0 || now_s() < args.duration_s)) {
    double wait_s = 0.02;  // the heads are polled at least this often (auto-transmit pings)
    for (const auto& served : heads) {
      if (!served->due.empty()) wait_s = std::min(wait_s, std::max(0.0, served->due.front().at_s - now_s()));
    }
    if (autopilot) wait_s = std::min(wait_s, std::max(0.0, autopilot->next_s - now_s()));
    std::vector<pollfd> waiting;
    for (const auto& served : heads) waiting.push_back({served->link.fd(), POLLIN, 0});
    if (autopilot) waiting.push_back({autopilot->link.fd(), POLLIN, 0});
    const int ready =
        ::poll(waiting.data(), waiting.size(), static_cast<int>(std::ceil(wait_s / args.time_scale * 1000.0)));
    const double now = now_s();
    for (std::size_t i = 0; i < heads.size(); ++i) {
      ServedHead& served = *heads[i];
      if (ready > 0 && (waiting[i].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
        const long got = served.link.read(buffer);
        if (got > 0) served.queue(served.head->receive(std::span(buffer.data(), static_cast<std::size_t>(got)), now));
      }
      served.queue(served.head->poll(now));
      served.send(now);
    }
    if (autopilot && ready > 0 && (waiting.back().revents & POLLIN) != 0 && autopilot->link.read(buffer) > 0) {
      ++autopilot->heard;
    }
    if (autopilot && now >= autopilot->next_s) {
      NavSample fix = options.trajectory(now);
      if (!autopilot->link.write(autopilot->autopilot.frames(fix, wall_s()))) ++autopilot->dropped;
      ++autopilot->updates;
      autopilot->next_s = std::max(autopilot->next_s + 1.0 / args.nav_rate_hz, now);
    }
  }
  for (const auto& served : heads) {
    const std::string dropped =
        served->dropped == 0 ? "" : ", " + std::to_string(served->dropped) + " messages nobody took";
    std::fprintf(stderr, "sonarmap: emulate: %s: %zu pings sent%s; last settings: %s\n",
                 served->link.description().c_str(), served->head->beamsSent(), dropped.c_str(),
                 served->head->settingsText().c_str());
  }
  if (autopilot) {
    std::fprintf(stderr, "sonarmap: emulate: %s: %zu navigation updates sent, %zu with no client to take them, %zu "
                 "datagrams received\n", autopilot->link.description().c_str(), autopilot->updates, autopilot->dropped,
                 autopilot->heard);
  }
}

}  // namespace

Command addEmulateCommand(CLI::App& app, EmulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "emulate", "Emulate a sonar head on a pseudo-terminal or UDP, its pings simulated in a scene");
  cmd->add_option("--sonar", args.sonar, "Head: " + joined(emulatedHeadNames(), " | ") + " (scenes built for its range)")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--scene", args.scene, "Built-in scene or scene file")->capture_default_str()->group(help_group::kInput);
  cmd->add_option("--seed", args.seed, "Seed of the speckle and noise")->capture_default_str()->group(help_group::kInput);
  cmd->add_option("--sound-speed", args.sound_speed_m_s, "The water's speed of sound (m/s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group(help_group::kInput);
  addVehiclePathOptions(*cmd, args);
  cmd->add_option("--serial", args.serial, "Serve a head on pty:PATH (a pseudo-terminal linked at PATH) or a serial device")
      ->group(help_group::kOutput);
  cmd->add_option("--udp", args.udp, "Serve a head on udp://:PORT (answers the last peer)")->group(help_group::kOutput);
  cmd->add_option("--baud", args.baud, "Serial rate the replies take to cross (bits/s; UDP: no delay)")
      ->capture_default_str()
      ->group(help_group::kOutput);
  cmd->add_option("--mavlink", args.mavlink,
                  "The vehicle's navigation as ArduSub sends it: to udp://HOST:PORT, or served at udp://:PORT as BlueOS does")
      ->group(help_group::kOutput);
  cmd->add_option("--nav-rate", args.nav_rate_hz, "HZ: navigation updates a second")
      ->capture_default_str()
      ->group(help_group::kOutput);
  cmd->add_flag("--no-position", args.no_position, "The vehicle has no DVL: attitude and depth only, no LOCAL_POSITION_NED")
      ->group(help_group::kOutput);
  cmd->add_option("--time-scale", args.time_scale, "The dive runs this many times faster than the wall clock")
      ->capture_default_str()
      ->group(help_group::kOutput);
  cmd->add_option("--duration", args.duration_s, "Stop after SECONDS (0: at Ctrl-C or SIGTERM)")
      ->capture_default_str()
      ->group(help_group::kOutput);
  auto options = std::make_shared<MsisSimulationOptions>();
  return {cmd, [&args, options] { check(args, *options); }, [&args, options] { run(args, *options); }};
}

}  // namespace sonarmap::cli

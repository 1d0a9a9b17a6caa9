#include "live_command.hpp"

#include "help_groups.hpp"

#include <poll.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <exception>
#include <mutex>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "live_latency.hpp"
#include "sonarmap/live/byte_link.hpp"
#include "output_checks.hpp"
#include "reader_skips.hpp"
#include "navigation_input.hpp"
#include "origin_option.hpp"
#include "map_command.hpp"
#include "map_outputs.hpp"
#include "sonarmap/core/statistics.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/ping360_reader.hpp"
#include "sonarmap/formats/wire_stream.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam_source.hpp"
#include "sonarmap/sonar/log_survey.hpp"
#include "sonarmap/slam/online_slam.hpp"
#include "slam_outputs.hpp"

namespace sonarmap::cli {
namespace {

volatile std::sig_atomic_t g_stop = 0;  // set by SIGINT / SIGTERM: finish and write the map

extern "C" void onStopSignal(int) { g_stop = 1; }

/// SIGINT and SIGTERM set g_stop and interrupt poll() (no SA_RESTART).
void catchStopSignals() {
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// The mapper fed by the stream, with each beam's arrival kept until it is shown and committed.
class LiveMapping {
 public:
  /// `known_fixes`: the navigation known at the start (--nav, a replayed log's own); `navigation`:
  /// whether fixes come at all (those, or a --nav-stream's).
  /// `origin`: the known fixes' (already moved to it); unset: decided at the first streamed fix
  /// (chooseLocalOrigin at `origin_resolution_m`, --origin's when given).
  LiveMapping(const LiveArgs& args, const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body,
              Clock::time_point start, const NavTrack& known_fixes, bool navigation, std::optional<LocalOrigin> origin,
              double origin_resolution_m)
      : start_(start), origin_(std::move(origin)), given_origin_(givenOrigin(args.map.origin)),
        origin_resolution_m_(origin_resolution_m) {
    const OnlineIntegration integration = args.show == "sweep" ? OnlineIntegration::kSweep : OnlineIntegration::kProvisionalBeams;
    if (args.map.slam) {
      // The odometry's reading period from the fixes known at the start, as `map --slam` takes it
      // from its whole track (the default period without them).
      slam_ = std::make_unique<OnlineSlam>(options, sonar_to_body, navigation,
                                           withNavigationPeriod(toSlamOptions(args.map.odometry, known_fixes), known_fixes),
                                           integration);
      for (const NavSample& fix : known_fixes) slam_->addNavFix(fix);
    } else if (!navigation) {
      mapper_ = std::make_unique<OnlineMapper>(options, integration);
    } else {
      mapper_ = std::make_unique<OnlineMapper>(options, sonar_to_body, integration);
      for (const NavSample& fix : known_fixes) mapper_->addNavFix(fix);
    }
  }

  /// Maps `beams`, whose last bytes arrived at `arrival_s` (seconds since the start): the raw
  /// protocols carry no clock, so the arrival is the beam's time.
  void add(std::vector<Beam> beams, double arrival_s) {
    for (Beam& beam : beams) {
      beam.time_s = arrival_s;
      addRecorded(std::move(beam), arrival_s);
    }
  }

  /// Maps one beam of a replayed log, with its recorded time, fed at `arrival_s`.
  void addRecorded(Beam beam, double arrival_s) {
    shown_.arrived(arrival_s, sweepsIntegrated() == 0);
    committed_.arrived(arrival_s, sweepsIntegrated() == 0);
    if (slam_) {
      slam_->addBeam(std::move(beam));
    } else {
      mapper_->addBeam(std::move(beam));
    }
    ++beams_;
    collect();
  }
  /// The end of the stream. The beams mapped only now (the last sweep, after an idle timeout or a
  /// signal) are not timed: their wait is the stream's end, not the mapping's.
  void finish() {
    if (slam_) {
      slam_->finish();
    } else {
      mapper_->finish();
    }
  }

  /// Adds navigation fixes whose rows arrived at `arrival_s`: the stream's clock is aligned to the
  /// arrival of its first fix (a constant offset), so fixes and beams share the arrival clock.
  void addFixes(std::vector<NavSample> fixes, double arrival_s) {
    for (NavSample& fix : fixes) {
      if (!nav_offset_s_) nav_offset_s_ = arrival_s - fix.time_s;
      fix.time_s += *nav_offset_s_;
      if (!origin_) origin_ = chooseLocalOrigin({fix}, given_origin_, origin_resolution_m_, 0.0);
      fix.position_ned_m -= origin_->ned_m;
      if (slam_) {
        slam_->addNavFix(fix);
      } else {
        mapper_->addNavFix(fix);
      }
      collect();
    }
  }

  /// The mapper of the current map (with --slam: rebuilt when a loop closes; feeding thread only).
  OnlineMapper& mapper() { return slam_ ? slam_->mapper() : *mapper_; }
  /// The map as shown (the provisional beams over the committed map); safe from any thread (the
  /// periodic writer's).
  OcTree16 shownSnapshot() const { return slam_ ? slam_->shownSnapshot() : mapper_->shownSnapshot(); }
  std::size_t sweepsIntegrated() const { return slam_ ? slam_->sweepsIntegrated() : mapper_->sweepsIntegrated(); }
  const OnlineSlam* slam() const { return slam_.get(); }
  /// The map's zero in the navigation's frame (zero before any fix).
  LocalOrigin origin() const { return origin_.value_or(LocalOrigin{}); }
  std::size_t beams() const { return beams_; }
  /// From a beam's arrival to the map as shown, and to the committed map.
  StageLatencies& shown() { return shown_; }
  StageLatencies& committed() { return committed_; }

 private:
  void collect() {
    const double now_s = secondsSince(start_);
    shown_.settle(slam_ ? slam_->beamsUnshown() : mapper_->beamsUnshown(), now_s);
    committed_.settle(slam_ ? slam_->beamsPending() : mapper_->beamsPending(), now_s);
  }

  Clock::time_point start_;
  std::unique_ptr<OnlineMapper> mapper_;
  std::unique_ptr<OnlineSlam> slam_;  ///< with --slam, instead of mapper_
  StageLatencies shown_;
  StageLatencies committed_;
  std::size_t beams_ = 0;
  std::optional<double> nav_offset_s_;  ///< arrival clock − the navigation stream's clock
  std::optional<LocalOrigin> origin_;
  std::optional<Eigen::Vector3d> given_origin_;  ///< --origin's
  double origin_resolution_m_;
};

/// One status line: the latencies from a beam's read to the map as shown and to the committed map,
/// since the last line, or with `whole_run` those of every beam after the first sweep (the median
/// and the 99th percentile; the first sweep's beams wait for its end).
void printStatus(LiveMapping& live, std::size_t bytes, std::size_t skipped, double elapsed_s, double rate_per_s,
                 bool whole_run = false) {
  std::vector<double> recent_shown = live.shown().takeRecent();
  std::vector<double> recent_committed = live.committed().takeRecent();
  std::vector<double>& shown = whole_run ? live.shown().all() : recent_shown;
  std::vector<double>& committed = whole_run ? live.committed().all() : recent_committed;
  const OnlineMapper& mapper = live.mapper();
  std::fprintf(stderr,
               "sonarmap: live: %.0f s, %zu bytes, %zu beams (%.1f/s), %zu skipped, %zu sweeps, %zu map nodes, "
               "latency median %.1f ms shown, %.1f ms committed",
               elapsed_s, bytes, live.beams(), rate_per_s, skipped, live.sweepsIntegrated(),
               mapper.mapper().map().counts().nodes, 1000.0 * percentile(shown, 0.5), 1000.0 * percentile(committed, 0.5));
  if (whole_run) {
    std::fprintf(stderr,
                 ", 99th percentile %.1f ms shown, %.1f ms committed (from read, after the first sweep, before the "
                 "end of the stream; the first sweep's beams waited %.0f ms)",
                 1000.0 * percentile(shown, 0.99), 1000.0 * percentile(committed, 0.99),
                 1000.0 * percentile(live.shown().firstSweep(), 0.5));
  }
  std::fputc('\n', stderr);
}

/// Rewrites the map as shown atomically every `every_s` seconds from a snapshot (shownSnapshot),
/// on its own thread, so that writing a large map never holds up the beams.
class PeriodicWriter {
 public:
  /// `origin_ned_m`: the local origin known before the first beam (a --nav file's); a streamed
  /// navigation's origin, decided at its first fix, is named by the final write only.
  PeriodicWriter(const LiveMapping& mapper, std::string path, MapFrame frame, Eigen::Vector3d origin_ned_m, double every_s)
      : thread_([this, &mapper, path = std::move(path), frame, origin_ned_m, every_s](std::stop_token stop) {
          std::mutex mutex;
          std::unique_lock lock(mutex);
          while (!wake_.wait_for(lock, stop, std::chrono::duration<double>(every_s), [] { return false; })) {
            if (stop.stop_requested()) return;
            if (mapper.sweepsIntegrated() == 0) continue;  // a map from the first sweep on
            try {
              writeMapFileInFrame(mapper.shownSnapshot(), path, frame, origin_ned_m);
            } catch (const std::exception& error) {  // the last good map stays; the final write reports for good
              std::fprintf(stderr, "sonarmap: warning: periodic map write failed: %s\n", error.what());
            }
          }
        }) {}

 private:
  std::condition_variable_any wake_;
  std::jthread thread_;  // last: stopped and joined first
};

/// The end of a live run: the last sweep integrated, the map (and with --slam the trajectory)
/// written, the summary printed.
void finishLive(const LiveArgs& args, LiveMapping& live, Clock::time_point start, std::size_t bytes, std::size_t skipped,
                const std::vector<SkipReasonGroup>& skip_reasons, bool with_nav) {
  live.finish();
  const double seconds = secondsSince(start);
  if (!args.map.quiet) printStatus(live, bytes, skipped, seconds, static_cast<double>(live.beams()) / std::max(seconds, 1e-9), true);
  const NavTrack trajectory = live.slam() ? live.slam()->trajectory() : NavTrack{};
  const std::optional<SlamReport> slam_report =
      live.slam() ? std::optional<SlamReport>(live.slam()->localizer().report()) : std::nullopt;
  MappedLog run{std::move(live.mapper()).release(), seconds};
  if (const std::size_t changes = run.mapper.stats().resolution_changes; changes > 0) {
    run.resolution_note = " (auto: coarsened " + std::to_string(changes) + (changes == 1 ? " time" : " times") +
                          " as the range scale grew)";
  }
  run.mapper.stats().beams_skipped = skipped;
  writeMapFileInFrame(run.mapper.map(), args.map.output_bt, args.map.map_frame, live.origin().ned_m);
  if (!args.map.trajectory_out.empty()) {
    FileTransaction outputs;
    stageTrajectory(outputs, args.map.trajectory_out, inNavigationFrame(trajectory, live.origin()));
    outputs.commit();
  }
  run.skip_note = skipNote(skipped, skip_reasons, run.mapper.stats().out_of_map, args.map.input);
  const std::vector<std::string> warnings =
      mappingWarnings(run.mapper.stats(), run.mapper.options(), run.mapper.map().resolution_m());
  printWarnings(warnings);
  printOrigin(live.origin());
  printMapSummary(run, args.map, with_nav || args.map.slam, warnings.size());
  if (slam_report) printSlamSummary(*slam_report, with_nav);
}

void runLive(const LiveArgs& args, const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body) {
  const LogFormat format = parseLogFormat(args.map.format);
  const MapperOptions sonar_options = withSonarBeam(options, args.map, format);
  const Clock::time_point start = Clock::now();
  NavTrack known_fixes = args.map.nav_file.empty() ? NavTrack{} : readNavCsv(args.map.nav_file);
  // The resolution is chosen as the beams come: whether the navigation is far from zero is judged
  // at --resolution, else at the auto resolution of --max-range.
  const double origin_resolution_m =
      sonar_options.resolution_m.value_or(autoResolution_m(sonar_options.max_range_m));
  std::optional<LocalOrigin> origin;
  if (!known_fixes.empty()) origin = moveTrackToOrigin(known_fixes, args.map.origin, origin_resolution_m, 0.0);
  LiveMapping live(args, sonar_options, sonar_to_body, start, known_fixes,
                   !args.map.nav_file.empty() || !args.nav_stream.empty(), origin, origin_resolution_m);
  g_stop = 0;
  catchStopSignals();
  ByteLink source(args.map.input, args.baud);
  if (!args.map.quiet) std::fprintf(stderr, "sonarmap: live: reading %s\n", source.description().c_str());
  WireStreamDecoder decoder(format, {}, args.map.input);

  std::optional<PeriodicWriter> writer(std::in_place, live, args.map.output_bt, args.map.map_frame,
                                      origin ? origin->ned_m : Eigen::Vector3d::Zero(), args.write_every_s);
  std::vector<SkipReasonGroup> skip_reasons;  // grouped as they come: a stream may run for days
  std::array<std::uint8_t, 65536> buffer{};
  double last_status_s = 0.0;
  double last_byte_s = 0.0;
  std::size_t beams_at_status = 0;
  std::optional<ByteLink> nav_source;
  std::optional<NavCsvStream> nav_rows;
  if (!args.nav_stream.empty()) {
    nav_source.emplace(args.nav_stream, args.baud);
    nav_rows.emplace(nav_source->description());
    if (!args.map.quiet) std::fprintf(stderr, "sonarmap: live: navigation from %s\n", nav_source->description().c_str());
  }
  while (g_stop == 0) {
    std::array<pollfd, 2> waiting{pollfd{source.fd(), POLLIN, 0}, pollfd{nav_source ? nav_source->fd() : -1, POLLIN, 0}};
    const int ready = ::poll(waiting.data(), nav_source ? 2 : 1, 100);
    const double now_s = secondsSince(start);
    if (ready > 0 && nav_source && (waiting[1].revents & (POLLIN | POLLHUP)) != 0) {
      const long got = nav_source->read(buffer);
      if (got == 0) {
        nav_source.reset();  // the navigation ended: the sonar goes on (beams beyond the last fix wait, then count)
      } else if (got > 0) {
        live.addFixes(nav_rows->feed(std::span(buffer.data(), static_cast<std::size_t>(got))), secondsSince(start));
      }
    }
    if (ready > 0 && (waiting[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
      const long got = source.read(buffer);
      if (got == 0) break;  // end of the stream
      if (got > 0) {
        if (decoder.bytesFed() == 0 && isPingViewerLog(std::span(buffer.data(), static_cast<std::size_t>(got)))) {
          throw ValueError(source.description() + " sends a Ping Viewer log, not the sonar's wire bytes: give the "
                           "log's file path to replay it as `map` reads it");
        }
        last_byte_s = secondsSince(start);
        live.add(decoder.feed(std::span(buffer.data(), static_cast<std::size_t>(got))), last_byte_s);
        addSkipReasons(skip_reasons, decoder.takeSkipReasons());
      }
    }
    if (args.idle_timeout_s > 0.0 && now_s - last_byte_s >= args.idle_timeout_s) break;
    if (now_s >= last_status_s + 1.0) {
      const double rate_per_s = static_cast<double>(live.beams() - beams_at_status) / (now_s - last_status_s);
      if (!args.map.quiet) printStatus(live, decoder.bytesFed(), decoder.skippedItems(), now_s, rate_per_s);
      beams_at_status = live.beams();
      last_status_s = now_s;
    }
  }
  live.add(decoder.finish(), secondsSince(start));
  addSkipReasons(skip_reasons, decoder.takeSkipReasons());
  if (live.beams() == 0) {
    throw FileError(args.map.input + ": no beam received in " + std::to_string(decoder.bytesFed()) + " bytes" +
                    (skip_reasons.empty() ? "" : " (" + skip_reasons.front().first_reason + ")"));
  }
  if (nav_rows && nav_rows->skippedRows() > 0) {
    std::fprintf(stderr, "sonarmap: warning: %zu navigation rows skipped, the last: %s\n", nav_rows->skippedRows(),
                 nav_rows->lastSkipReason().c_str());
  }
  writer.reset();  // no periodic write races the final one
  finishLive(args, live, start, decoder.bytesFed(), decoder.skippedItems(), skip_reasons,
             !args.map.nav_file.empty() || !args.nav_stream.empty());
}

/// Whether `live` replays a recorded log beam by beam with its own clock, read as `map` reads it,
/// rather than decoding a wire stream: a ROS log (by --format, or the source's name) or a Ping
/// Viewer log file (by its header: its records wrap the sonar's bytes in time stamps and lengths,
/// which no wire decoder may read as the sonar's).
bool isReplay(const LiveArgs& args) {
  const std::optional<LogFormat> format =
      args.map.format != "auto" ? std::optional(parseLogFormat(args.map.format)) : logFormatOfPath(args.map.input);
  if (!format) return false;
  return isRosLog(*format) || (*format == LogFormat::kPing360 && isPingViewerLogFile(args.map.input));
}

/// `live` on a recorded log (a replay: a ROS log, a Ping Viewer log): its beams, as `map` reads
/// them, fed in order with their recorded times, its own navigation (or --nav's, any file `map
/// --nav` reads, joined by its clock) known from the start.
void runLiveReplay(const LiveArgs& args, const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body) {
  const LogFormat format = inputFormat(args.map.input, args.map.format);
  // Read beam by beam: a replay holds no more of the log than a sonar on the wire would send.
  const std::unique_ptr<BeamSource> source = openBeamSource(args.map.input, format, args.map.log_read);
  const MapperOptions sonar_options = withSonarBeam(options, args.map, format);
  std::optional<AlignedNavigation> navigation = navigationFor(
      args.map.input, format, source->header(), args.map.nav_file, args.map.nav_topic, args.map.nav_time_offset_s);
  // One pass before anything is mapped or written: the file's errors and skips, as reading it
  // whole found them, and the clocks' overlap.
  const BeamPass pass = passOver(*source);
  const LogSurvey survey = surveyLog(pass, 1, spanOf(navigation));
  std::optional<LocalOrigin> origin;
  const double origin_resolution_m = sonar_options.resolution_m.value_or(
      survey.beams > 0 ? autoResolutionForLog(survey, sonar_options).resolution_m : autoResolution_m(sonar_options.max_range_m));
  if (navigation) {
    printNavigationSource(*navigation, args.map.nav_file);
    requireClockOverlap(survey, source->header().clock_utc_s, *navigation);
    origin = moveTrackToOrigin(navigation->source.track, args.map.origin, origin_resolution_m,
                               std::min(survey.reach_m, sonar_options.max_range_m));
  }
  const Eigen::Isometry3d mounting =
      mountingFor(args.map.input, format, source->header(), navigation, !args.map.mounting.empty(), sonar_to_body);
  const Clock::time_point start = Clock::now();
  LiveMapping live(args, sonar_options, mounting, start, navigation ? navigation->source.track : NavTrack{},
                   navigation.has_value(), origin, origin_resolution_m);
  g_stop = 0;
  catchStopSignals();
  if (!args.map.quiet) std::fprintf(stderr, "sonarmap: live: replaying %s\n", args.map.input.c_str());
  std::optional<PeriodicWriter> writer(std::in_place, live, args.map.output_bt, args.map.map_frame,
                                      origin ? origin->ned_m : Eigen::Vector3d::Zero(), args.write_every_s);
  double last_status_s = 0.0;
  std::size_t beams_at_status = 0;
  source->rewind();
  while (g_stop == 0) {
    std::optional<Beam> beam = source->next();
    if (!beam) break;
    live.addRecorded(std::move(*beam), secondsSince(start));
    if (const double now_s = secondsSince(start); now_s >= last_status_s + 1.0) {
      const double rate_per_s = static_cast<double>(live.beams() - beams_at_status) / (now_s - last_status_s);
      if (!args.map.quiet) printStatus(live, 0, source->header().skipped_beams, now_s, rate_per_s);
      beams_at_status = live.beams();
      last_status_s = now_s;
    }
  }
  writer.reset();
  std::vector<SkipReasonGroup> skip_reasons;
  addSkipReasons(skip_reasons, source->header().skip_reasons);
  finishLive(args, live, start, 0, source->header().skipped_beams, skip_reasons, navigation.has_value());
}

}  // namespace

Command addLiveCommand(CLI::App& app, LiveArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "live", "Map beams as they arrive from a sonar (SeaNet, Ping360) or a replayed log");
  cmd->add_option("source", args.map.input, "Serial device, udp://HOST:PORT, tcp://HOST:PORT, - or a file")
      ->required();
  cmd->add_option("-o,--output", args.map.output_bt, "Output map (.bt or .ot), rewritten every --write-every")
      ->required()
      ->group(help_group::kOutput);
  addMappingOptions(*cmd, args.map);
  cmd->add_option("--baud", args.baud, "Serial devices: bits per second (8N1, raw)")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--show", args.show, "When a beam shows in the written map: beam | sweep")
      ->check(CLI::IsMember({"beam", "sweep"}))
      ->capture_default_str()
      ->group(help_group::kOutput);
  cmd->add_option("--write-every", args.write_every_s, "SECONDS between map writes (> 0)")
      ->capture_default_str()
      ->group(help_group::kOutput);
  cmd->add_option("--idle-timeout", args.idle_timeout_s, "End after this many SECONDS without a byte (0: never)")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--nav", args.map.nav_file, "Navigation CSV (times since the start) or a replayed log's")
      ->group(help_group::kNavigation);
  cmd->add_option("--nav-stream", args.nav_stream, "A second SOURCE sending navigation CSV rows")
      ->excludes("--nav")
      ->group(help_group::kNavigation);
  addMountingOption(*cmd, args.map.mounting, "With --nav or --nav-stream: ");
  cmd->add_flag("--slam", args.map.slam, "Correct the navigation by scan matching as sweeps complete")
      ->group(help_group::kLocalization);
  addOdometryOptions(*cmd, args.map.odometry);
  addOriginOption(*cmd, args.map.origin);
  cmd->add_option("--trajectory", args.map.trajectory_out, "With --slam: write the corrected trajectory (.csv, .tum)")
      ->group(help_group::kOutput);
  struct Checked {
    MapperOptions options;
    Eigen::Isometry3d sonar_to_body;
  };
  auto checked = std::make_shared<Checked>();
  auto check = [&args, checked] {
    if (!isReplay(args) && args.map.format != "seanet" && args.map.format != "ping360") {
      throw ValueError("live needs --format seanet or --format ping360 (a raw wire stream), or a recorded ROS log "
                       "(.bag, .mcap, .db3, a rosbag2 folder) or Ping Viewer log (.bin), got '" + args.map.format + "'");
    }
    if (isReplay(args) && !args.nav_stream.empty()) throw ValueError("a replayed log takes --nav, not --nav-stream");
    if (!(args.write_every_s > 0.0)) throw ValueError("--write-every must be > 0 seconds");
    checkOdometryArgs(args.map.odometry, args.map.slam);
    if (!(args.idle_timeout_s >= 0.0)) throw ValueError("--idle-timeout must be >= 0 seconds");
    if (!args.map.mounting.empty() && args.map.nav_file.empty() && args.nav_stream.empty() && !args.map.slam) {
      throw ValueError("--mounting needs --nav, --nav-stream or --slam");
    }
    if (!args.map.trajectory_out.empty() && !args.map.slam) throw ValueError("live --trajectory needs --slam");
    requireMapOutput(args.map.output_bt);
    requireTrajectoryOutput(args.map.trajectory_out);
    checked->options = toMapperOptions(args.map);
    checked->sonar_to_body = toSonarToBody(args.map.mounting);
  };
  return {cmd, check, [&args, checked] {
            if (isReplay(args)) {
              runLiveReplay(args, checked->options, checked->sonar_to_body);
            } else {
              runLive(args, checked->options, checked->sonar_to_body);
            }
          }};
}

}  // namespace sonarmap::cli

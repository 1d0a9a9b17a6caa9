// Running `sonarmap live` (see live_run.hpp): the session built from the options, its progress
// on stderr, its outputs and summary.

#include "live_run.hpp"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "map_command.hpp"
#include "map_outputs.hpp"
#include "navigation_input.hpp"
#include "odometry_options.hpp"
#include "origin_option.hpp"
#include "reader_skips.hpp"
#include "slam_outputs.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/core/statistics.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/ping360_reader.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/geotiff.hpp"
#include "sonarmap/live/live_map_files.hpp"
#include "sonarmap/live/live_page.hpp"
#include "sonarmap/live/live_session.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/sonar/beam_source.hpp"
#include "sonarmap/sonar/log_survey.hpp"

namespace sonarmap::cli {
namespace {

volatile std::sig_atomic_t g_stop = 0;  // set by SIGINT / SIGTERM / SIGHUP: finish and write the map

extern "C" void onStopSignal(int) { g_stop = 1; }

/// SIGINT, SIGTERM and SIGHUP set g_stop and interrupt poll() (no SA_RESTART). SIGHUP is what a
/// closed SSH session or terminal sends: the dive ends as at Ctrl-C, its map and recording whole.
void catchStopSignals() {
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);
}

/// "12.3 ms", or "-" for none (NaN: no beam reached the stage in the period).
std::string milliseconds(double seconds) {
  if (!std::isfinite(seconds)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", 1000.0 * seconds);
  return text;
}

/// A run's progress on stderr: the head's settings, notes, a status line a second.
class ConsoleObserver final : public LiveObserver {
 public:
  explicit ConsoleObserver(bool quiet) : quiet_(quiet) {}
  void headSettings(const std::string& device, const AppliedSettings& settings) override {
    if (quiet_) return;
    if (!device.empty()) std::fprintf(stderr, "sonarmap: live: head: %s\n", device.c_str());
    if (!settings.fields.empty()) std::fprintf(stderr, "sonarmap: live: settings: %s\n", settings.text().c_str());
  }
  void note(const std::string& line) override {
    if (!quiet_) std::fprintf(stderr, "sonarmap: live: %s\n", line.c_str());
  }
  void status(const LiveProgress& s) override {
    if (quiet_) return;
    std::fprintf(stderr,
                 "sonarmap: live: %.0f s, %zu bytes, %zu beams (%.1f/s), %zu skipped, %zu sweeps, %zu map nodes, "
                 "%zu fixes, latency median %s shown, %s committed\n",
                 s.elapsed_s, s.bytes, s.beams, s.beams_per_s, s.skipped, s.sweeps, s.map_nodes, s.fixes,
                 milliseconds(s.shown_latency_s).c_str(), milliseconds(s.committed_latency_s).c_str());
  }

 private:
  bool quiet_;
};

/// The final status line: every beam's latency after the first sweep (the median and the 99th
/// percentile; the first sweep's beams wait for its calibration).
void printLatencies(LiveMapping& live) {
  std::vector<double>& shown = live.shown().all();
  std::vector<double>& committed = live.committed().all();
  std::fprintf(stderr,
               "sonarmap: live: latency median %.1f ms shown, %.1f ms committed, 99th percentile %.1f ms shown, "
               "%.1f ms committed (from read, after the first sweep, before the end of the stream; the first sweep's "
               "beams waited %.0f ms)\n",
               1000.0 * percentile(shown, 0.5), 1000.0 * percentile(committed, 0.5), 1000.0 * percentile(shown, 0.99),
               1000.0 * percentile(committed, 0.99), 1000.0 * percentile(live.shown().firstSweep(), 0.5));
}

/// Fails a run whose map cannot be what the user wanted: nothing received, or no beam placed by
/// the navigation (a navigation on another clock, a stream that sent nothing usable).
void requireMappedBeams(const LiveArgs& args, const LiveResult& result, const MappingStats& stats, bool with_nav) {
  if (result.beams == 0) {
    std::string why;
    if (!result.skip_reasons.empty()) why = " (" + result.skip_reasons.front().first_reason + ")";
    if (result.bytes == 0 && !isReplay(args)) {
      why = args.head.listen_only ? " (nothing arrived: with --listen-only another program must make the head ping)"
                                  : " (the head did not answer: is it a " + args.map.format + " head at " +
                                        std::to_string(args.baud) + " baud, powered, on this link?)";
    }
    throw FileError(args.map.input + ": no beam received in " + std::to_string(result.bytes) + " bytes" + why);
  }
  if (with_nav && stats.beams_without_nav >= result.beams) {
    throw FileError("none of the " + std::to_string(result.beams) + " beams lies within the navigation's time span (" +
                    std::to_string(result.fixes) + " fixes received" +
                    (result.fixes == 0 ? ": the navigation link sent nothing usable" : "") +
                    "): the map would be empty");
  }
}

/// The end of a run: the map (and with --slam the trajectory) written, the summary printed.
void finishLive(const LiveArgs& args, LiveSession& session, const LiveResult& result, bool with_nav) {
  LiveMapping& live = session.mapping();
  if (!args.map.quiet) printLatencies(live);
  const NavTrack trajectory = live.slam() ? live.slam()->trajectory() : NavTrack{};
  const std::optional<SlamReport> slam_report =
      live.slam() ? std::optional<SlamReport>(live.slam()->localizer().report()) : std::nullopt;
  const LocalOrigin origin = live.origin();
  MappedLog run{std::move(live.mapper()).release(), result.seconds};
  requireMappedBeams(args, result, run.mapper.stats(), with_nav);
  if (const std::size_t changes = run.mapper.stats().resolution_changes; changes > 0) {
    run.resolution_note = " (auto: coarsened " + std::to_string(changes) + (changes == 1 ? " time" : " times") +
                          " as the range scale grew)";
  }
  run.mapper.stats().beams_skipped = result.skipped;
  const LiveOutputs& files = session.outputs();  // the map, and its GeoTIFF, as the periodic writes
  live::writeLiveMapFiles(run.mapper.map(), files, origin);
  if (!args.map.trajectory_out.empty()) {
    FileTransaction outputs;
    stageTrajectory(outputs, args.map.trajectory_out, inNavigationFrame(trajectory, origin));
    outputs.commit();
  }
  run.skip_note = skipNote(result.skipped, result.skip_reasons, run.mapper.stats().out_of_map, args.map.input);
  const std::vector<std::string> warnings =
      mappingWarnings(run.mapper.stats(), run.mapper.options(), run.mapper.map().resolution_m());
  printWarnings(warnings);
  if (result.nav_skipped > 0) {
    std::fprintf(stderr, "sonarmap: warning: %zu navigation rows or frames skipped (%s), the last note: %s\n",
                 result.nav_skipped, result.nav_protocol.c_str(), result.nav_skip_reason.c_str());
  }
  if (result.fixes_dropped > 0) {
    std::fprintf(stderr, "sonarmap: warning: %zu navigation fixes dropped (not after the previous one, or not finite)\n",
                 result.fixes_dropped);
  }
  printOrigin(origin);
  printGeodeticZero(live::liveGeodeticZero(files, origin), !args.map.geo_origin.empty() ? "--geo-origin" : "the log's navigation");
  printMapSummary(run, args.map, with_nav || args.map.slam, warnings.size());
  if (slam_report) printSlamSummary(*slam_report, with_nav);
  if (!result.recorded.empty()) {
    std::fprintf(stderr, "sonarmap: live: recorded %zu beams and %zu fixes -> %s (map it with `sonarmap map %s`)\n",
                 result.beams, result.fixes, result.recorded.c_str(), result.recorded.c_str());
  }
  if (result.resets > 0) std::fprintf(stderr, "sonarmap: live: the map was reset %zu times from the page\n", result.resets);
  // A dive whose map holds no obstacle did not map what it was run for (the navigation lost, the
  // head out of the water, a gain too low): the map is written, and the run fails.
  if (run.mapper.stats().obstacles == 0) {
    const std::string why = run.mapper.stats().sweeps == 0
                                ? "no sweep completed: a sweep is mapped once its turn or sector pass ends"
                                : std::to_string(run.mapper.stats().beams_without_nav) + " without navigation";
    throw FileError("the map is empty: no obstacle in " + std::to_string(result.beams) + " beams (" + why +
                    "); written to " + args.map.output_bt + " all the same");
  }
}

/// The mapping options of a run: the sonar's beam, the integration, the navigation and SLAM.
LiveMappingOptions mappingOptions(const LiveArgs& args, const MapperOptions& sonar_options,
                                  const Eigen::Isometry3d& mounting, bool navigation, const NavTrack& known_fixes,
                                  double origin_resolution_m) {
  LiveMappingOptions mapping;
  mapping.mapper = sonar_options;
  mapping.sonar_to_body = mounting;
  // A log replayed as fast as possible is not watched beam by beam: showing each beam on the
  // provisional layer would cost as much again as mapping it (a 2-hour SeaKing log with --slam).
  const bool by_sweep = args.show == "sweep" || (args.show == "auto" && isReplay(args) && args.rate == 0.0);
  mapping.integration = by_sweep ? OnlineIntegration::kSweep : OnlineIntegration::kProvisionalBeams;
  mapping.navigation = navigation;
  // The odometry's reading period from the fixes known at the start, as `map --slam` takes it from
  // its whole track (the default period without them).
  if (args.map.slam) mapping.slam = withNavigationPeriod(toSlamOptions(args.map.odometry, known_fixes), known_fixes);
  // A stream's navigation is known only as it comes: its class (a vehicle without a DVL sends north
  // and east 0) and its period are decided at the first sweep, from the fixes received by then.
  if (args.map.slam && navigation && known_fixes.empty()) {
    const OdometryArgs odometry = args.map.odometry;
    mapping.slam_from_fixes = [odometry](const NavTrack& fixes) {
      return withNavigationPeriod(toSlamOptions(odometry, fixes), fixes);
    };
  }
  mapping.given_origin = givenOrigin(args.map.origin);
  mapping.origin_resolution_m = origin_resolution_m;
  return mapping;
}

LiveOutputs outputsOf(const LiveArgs& args) {
  LiveOutputs outputs;
  outputs.map_path = args.map.output_bt;
  outputs.map_frame = args.map.map_frame;
  outputs.write_every_s = args.write_every_s;
  outputs.geotiff_path = args.map.geotiff;
  if (!args.map.geo_origin.empty()) outputs.geodetic_origin = parseGeodeticPoint(args.map.geo_origin);
  outputs.record_path = args.record;
  outputs.record_metadata = {{"program", "sonarmap " SONARMAP_VERSION " live"}, {"source", args.map.input},
                             {"format", args.map.format}, {"mounting", mountingText({})}};
  if (!args.map.mounting.empty()) {
    std::array<double, 6> mounting{};
    std::copy_n(args.map.mounting.begin(), 6, mounting.begin());
    outputs.record_metadata["mounting"] = mountingText(mounting);
  }
  return outputs;
}

/// --geotiff needs the map's place on the Earth: --geo-origin, or a replayed log's latitude and longitude.
void requireGeoTiffPlace(const LiveArgs& args, const LiveOutputs& outputs) {
  if (!args.map.geotiff.empty() && !outputs.geodetic_origin) {
    throw ValueError("--geotiff needs the map's place on the Earth: give --geo-origin LAT,LON (a replayed log's own "
                     "latitude and longitude are taken when it has them)");
  }
}

/// Runs `session` to its end and finishes it, its page served with --serve.
void runSession(const LiveArgs& args, LiveSession& session, LiveObserver& console, bool with_nav) {
  std::optional<LivePage> page;
  if (!args.serve.empty()) {
    page.emplace(session, webServerOptions(args.serve), &console);
    if (!args.record.empty()) page->view().setRecordingPath(args.record);
    std::fprintf(stderr, "sonarmap: live: the page is at %s\n", page->url().c_str());
  }
  if (!args.map.quiet) {
    std::fprintf(stderr, "sonarmap: live: reading %s\n", session.headDescription().c_str());
    if (!session.navDescription().empty()) {
      std::fprintf(stderr, "sonarmap: live: navigation from %s\n", session.navDescription().c_str());
    }
  }
  g_stop = 0;
  catchStopSignals();
  const LiveResult result = session.run([] { return g_stop != 0; });
  page.reset();  // the page stops before the map is handed over
  finishLive(args, session, result, with_nav);
}

/// `live` on a head's link: driven or listened to, navigation from --nav or --nav-stream.
void runOnHead(const LiveArgs& args, const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body) {
  const LogFormat format = parseLogFormat(args.map.format);
  const MapperOptions sonar_options = withSonarBeam(options, args.map, format);
  const NavTrack known_fixes = args.map.nav_file.empty() ? NavTrack{} : readNavCsv(args.map.nav_file);
  // The resolution is chosen as the beams come: whether the navigation is far from zero is judged
  // at --resolution, else at the auto resolution of --max-range.
  const double origin_resolution_m = sonar_options.resolution_m.value_or(autoResolution_m(sonar_options.max_range_m));
  const bool with_nav = !args.map.nav_file.empty() || !args.nav_stream.empty();
  LiveInput input;
  input.head = args.map.input;
  input.baud = args.baud;
  input.format = format;
  input.drive = !args.head.listen_only;
  input.settings = toHeadSettings(args.head);
  input.nav = args.nav_stream;
  input.idle_timeout_s = args.idle_timeout_s;
  ConsoleObserver console(args.map.quiet);
  requireGeoTiffPlace(args, outputsOf(args));
  LiveSession session(std::move(input), outputsOf(args),
                      mappingOptions(args, sonar_options, sonar_to_body, with_nav, known_fixes, origin_resolution_m),
                      known_fixes, &console);
  runSession(args, session, console, with_nav);
}

/// `live` on a recorded log (a ROS log, a Ping Viewer log): its beams, as `map` reads them, fed in
/// order with their recorded times at --rate, its own navigation (or --nav's, any file `map --nav`
/// reads, joined by its clock) known from the start, mapped with `map`'s options for the log
/// (mappingOptionsForLog): `map`'s map byte for byte.
void runReplay(const LiveArgs& args, const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body) {
  const LogFormat format = inputFormat(args.map.input, args.map.format);
  // Read beam by beam: a replay holds no more of the log than a sonar on the wire would send.
  std::unique_ptr<BeamSource> source = openBeamSource(args.map.input, format, args.map.log_read);
  const MapperOptions sonar_options = withSonarBeam(options, args.map, nominalBeam(format, source->header()));
  const std::optional<AlignedNavigation> navigation = navigationFor(
      args.map.input, format, source->header(), args.map.nav_file, args.map.nav_topic, args.map.nav_time_offset_s);
  // One pass before anything is mapped or written: the file's errors and skips, as reading it
  // whole found them, and the clocks' overlap.
  const BeamPass pass = passOver(*source);
  const LogSurvey survey = surveyLog(pass, 1, spanOf(navigation));
  // `map`'s options for the log: its resolution follows the range scale most of its beams use (a
  // head's stream can follow only the scales seen so far), its work budget checked.
  const MapperOptions log_options = survey.beams > 0 ? mappingOptionsForLog(sonar_options, survey) : sonar_options;
  const double origin_resolution_m = log_options.resolution_m.value_or(autoResolution_m(log_options.max_range_m));
  NavTrack known_fixes;
  std::optional<LocalOrigin> origin;
  if (navigation) {
    printNavigationSource(*navigation, args.map.nav_file);
    requireClockOverlap(survey, source->header().clock_utc_s, *navigation);
    known_fixes = navigation->source.track;
    NavTrack moved = known_fixes;
    origin = moveTrackToOrigin(moved, args.map.origin, origin_resolution_m,
                               std::min(survey.reach_m, sonar_options.max_range_m));
  }
  const Eigen::Isometry3d mounting =
      mountingFor(args.map.input, format, source->header(), navigation, !args.map.mounting.empty(), sonar_to_body);
  LiveMappingOptions mapping =
      mappingOptions(args, log_options, mounting, navigation.has_value(), known_fixes, origin_resolution_m);
  mapping.origin = origin;
  LiveInput input;
  input.replay = std::move(source);
  input.rate = args.rate;
  ConsoleObserver console(args.map.quiet);
  LiveOutputs outputs = outputsOf(args);
  if (!outputs.geodetic_origin && navigation) outputs.geodetic_origin = navigation->source.geodetic_origin;
  requireGeoTiffPlace(args, outputs);
  LiveSession session(std::move(input), std::move(outputs), std::move(mapping), known_fixes, &console);
  runSession(args, session, console, navigation.has_value());
}

}  // namespace

bool isReplay(const LiveArgs& args) {
  const std::optional<LogFormat> format =
      args.map.format != "auto" ? std::optional(parseLogFormat(args.map.format)) : logFormatOfPath(args.map.input);
  if (!format) return false;
  return isRosLog(*format) || (*format == LogFormat::kPing360 && isPingViewerLogFile(args.map.input));
}

void runLive(const LiveArgs& args, const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body) {
  // GDAL's plugin, loaded before anything is read or driven: if it is missing, not at the first write
  if (!args.map.geotiff.empty()) loadGeoTiffWriter();
  // The outputs are written at the dive's end (and -o periodically): a folder that is missing or
  // cannot be written is said now, as --record's is, not when the dive is over.
  for (const std::string* output : {&args.map.output_bt, &args.map.geotiff, &args.map.trajectory_out}) {
    if (!output->empty()) checkWritable(*output);
  }
  if (isReplay(args)) {
    runReplay(args, options, sonar_to_body);
  } else {
    runOnHead(args, options, sonar_to_body);
  }
}

}  // namespace sonarmap::cli

#pragma once
/// @file live_session.hpp
/// A live run: a sonar head driven over its link (devices/head_driver.hpp) or listened to, the
/// vehicle's navigation streamed (MAVLink or CSV rows), a recorded log replayed at its own pace, the
/// beams mapped as they arrive (live_mapping.hpp), what was received recorded (dive_recorder.hpp),
/// and everything told to an observer (the page of `live --serve`, web_server.hpp).
///
/// Clocks. The protocols carry no time: a beam's time is its arrival, a navigation fix's its
/// autopilot's clock put on the arrival clock. Both are then seconds since 1970 on this computer's
/// clock as a recording stores them (DiveRecorder::recordedTime), so the map `map` makes of the
/// recording is the live map. A replayed log keeps its own times.
///
/// Threads: run() feeds the mapper on the calling thread; requestReset() and requestSave() may be
/// called from any thread (the page's server) and are carried out by run() within one poll period
/// (≤ 50 ms).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/devices/head_settings.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/live/live_mapping.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/beam_source.hpp"
#include "sonarmap/sonar/log_summary.hpp"

namespace sonarmap {

/// What a live run tells its observer, once a second.
struct LiveProgress {
  double elapsed_s = 0.0;          ///< since the start, steady clock
  std::size_t bytes = 0;           ///< bytes received from the head
  std::size_t beams = 0;           ///< beams received
  double beams_per_s = 0.0;        ///< over the last status period
  std::size_t skipped = 0;         ///< items the decoder skipped
  std::size_t sweeps = 0;          ///< sweeps integrated (since the last reset)
  std::size_t map_nodes = 0;
  std::size_t fixes = 0;           ///< navigation fixes received
  double shown_latency_s = 0.0;    ///< median, arrival → map as shown, over the period (NaN: none)
  double committed_latency_s = 0.0;  ///< median, arrival → committed map, over the period (NaN: none)
};

/// Receives what a live run does, on run()'s thread. Every method has an empty default.
class LiveObserver {
 public:
  virtual ~LiveObserver() = default;
  /// The head's identity and applied settings (once known, and again when they change).
  virtual void headSettings(const std::string& /*device*/, const AppliedSettings& /*settings*/) {}
  /// Beam number `sequence` (from 0) arrived at `arrival_s` (steady, since the start), its sonar
  /// placed at `sonar_to_map` (the latest fix's pose: for display; the map uses the interpolated one).
  virtual void beam(std::size_t /*sequence*/, const Beam& /*beam*/, double /*arrival_s*/,
                    const Eigen::Isometry3d& /*sonar_to_map*/) {}
  /// After a beam was mapped: beams 0 … beams_shown − 1 are in the map as shown (those before a
  /// reset count as shown), `sweeps` integrated since the last reset.
  virtual void mapped(std::size_t /*beams_shown*/, std::size_t /*sweeps*/) {}
  /// A navigation fix, moved to the map's origin (NED).
  virtual void fix(const NavSample& /*fix*/) {}
  virtual void status(const LiveProgress& /*status*/) {}
  /// A line for the user (a command repeated, the head's refusal, a recorder flush failing).
  virtual void note(const std::string& /*line*/) {}
  /// The map was started again.
  virtual void reset() {}
};

/// Where a live run's beams come from.
struct LiveInput {
  /// A head's link (byte_link.hpp); empty with `replay`.
  std::string head;
  unsigned baud = 115200;
  LogFormat format = LogFormat::kPing360;  ///< kPing360 or kSeaNet
  /// Drive the head (send it commands: devices/head_driver.hpp); false: only listen to what another
  /// program makes it send.
  bool drive = true;
  HeadSettings settings;
  /// A navigation link sending MAVLink or navigation CSV rows, told apart by their bytes; empty: none.
  std::string nav;
  /// A recorded log replayed beam by beam with its own times (instead of `head`).
  std::unique_ptr<BeamSource> replay;
  /// Replay pace: 1 plays the log at its own pace, 2 twice as fast; 0 as fast as possible.
  double rate = 0.0;
  /// End after this many seconds without a byte from the head (0: never).
  double idle_timeout_s = 0.0;
};

/// Where a live run's outputs go.
struct LiveOutputs {
  std::string map_path;  ///< rewritten every write_every_s from the map as shown, and at the end
  MapFrame map_frame = MapFrame::kNwu;
  /// Rewritten with the map (every write_every_s, on save): its GeoTIFF (geo_raster.hpp), when
  /// geodetic_origin is known; empty: none.
  std::string geotiff_path;
  /// The navigation's NED zero on the Earth (--geo-origin, or the replayed log's latitude and
  /// longitude); the map's zero is it moved by the local origin. nullopt: unknown.
  std::optional<GeodeticPoint> geodetic_origin;
  double write_every_s = 10.0;
  std::string record_path;  ///< the received beams and fixes (dive_recorder.hpp); empty: none
  /// Metadata recorded with the dive (the command line, the program's version).
  std::map<std::string, std::string> record_metadata;
};

/// How a live run ended.
struct LiveResult {
  std::size_t bytes = 0;          ///< from the head
  std::size_t beams = 0;          ///< received (replayed)
  std::size_t fixes = 0;          ///< navigation fixes received
  std::size_t skipped = 0;        ///< items the decoder (or the replayed log's reader) skipped
  std::vector<SkipReasonGroup> skip_reasons;  ///< their reasons, grouped as they came
  std::size_t fixes_dropped = 0;  ///< fixes not after the previous one, or not finite
  std::size_t nav_skipped = 0;    ///< navigation rows or frames the stream's decoder skipped
  std::string nav_skip_reason;    ///< the decoder's last note (why the last was skipped)
  std::string nav_protocol;       ///< what the navigation stream turned out to be
  std::size_t resets = 0;
  bool stopped = false;           ///< ended by the stop request (a signal), not the stream's end
  std::string device;             ///< the head's identity, when it said
  AppliedSettings settings;       ///< as applied (driving), or empty
  std::string recorded;           ///< the recording's path, when there is one
  double seconds = 0.0;
};

/// One live run (see the file's comment).
class LiveSession {
 public:
  /// Opens the links and the recording.
  /// `known_fixes`: navigation known at the start (a --nav file or a replayed log's own), on the
  /// beams' clock and moved to mapping.origin; with a head (not a replay) their times are seconds
  /// since the start and are put on the clock of the run.
  /// @throws ValueError for inconsistent inputs (neither a head nor a replay, a rate < 0);
  ///         FileError when a link or the recording cannot be opened.
  LiveSession(LiveInput input, LiveOutputs outputs, LiveMappingOptions mapping, NavTrack known_fixes = {},
              LiveObserver* observer = nullptr);
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  /// Runs until the head's stream ends (end of file, a closed connection, the idle timeout), the
  /// replay ends, or `stop_requested()` returns true (checked at least every 50 ms; a signal
  /// handler's flag). Then tells the head to stop (where its protocol can), integrates the held
  /// sweeps, writes the map and finishes the recording.
  /// @throws FileError when the head or the navigation link fails, or an output cannot be written
  ///         (the recording is then left as its .part file); ValueError from the mapper.
  LiveResult run(const std::function<bool()>& stop_requested);

  /// Asks run() to start the map again (from the page) and waits until it did (at most 2 s; after
  /// run() returned, at once). Any thread.
  void resetNow();
  /// Writes the map as shown now and asks run() to flush the recording; returns what was written,
  /// ("map", path) and ("recording", path of the file being written). Any thread.
  /// @throws FileError when the map cannot be written.
  std::vector<std::pair<std::string, std::string>> saveNow();
  /// Tells `observer` (null: nobody) what happens from now on. Call before run() or from its thread.
  void setObserver(LiveObserver* observer) { observer_ = observer != nullptr ? observer : &silent_; }

  /// The mapper (feeding thread; after run(), the final map and trajectory).
  LiveMapping& mapping() { return *mapping_; }
  /// The run's clock zero (steady).
  std::chrono::steady_clock::time_point start() const { return start_; }
  /// "/dev/ttyUSB0 at 115200 baud (driving the head)", "a replayed log".
  std::string headDescription() const;
  /// The navigation link as opened ("udp://:14550"); empty without one.
  std::string navDescription() const;
  /// Where the run writes (as constructed).
  const LiveOutputs& outputs() const { return outputs_; }

 private:
  struct Inputs;
  void feedBeam(Beam beam, double arrival_s, double time_s);
  void feedFix(NavSample fix, double arrival_s);
  void serviceRequests();
  void report(double now_s, LiveResult& result);
  /// The head's notes and skip lines to the observer and the result; its settings when they changed.
  void takeHeadNotes(LiveResult& result);
  /// Feeds the replayed beams that are due (a batch, as fast as possible without a rate); false at
  /// the log's end.
  bool replayStep(double now_s);
  double secondsSinceStart() const;
  /// A time on the arrival clock (seconds since the start) as the beams' clock gives it: seconds
  /// since 1970 as a recording stores them.
  double beamClock(double arrival_s) const;

  LiveOutputs outputs_;
  LiveObserver* observer_;
  LiveObserver silent_;
  std::chrono::steady_clock::time_point start_;
  double epoch_at_start_s_ = 0.0;  ///< this computer's clock at start_, seconds since 1970
  std::unique_ptr<Inputs> inputs_;
  std::unique_ptr<LiveMapping> mapping_;
  std::atomic<bool> reset_requested_{false};
  std::atomic<bool> running_{false};
  std::condition_variable reset_done_;
  std::atomic<bool> flush_requested_{false};
  std::mutex saving_;
  std::size_t resets_ = 0;
  std::size_t beams_at_status_ = 0;
  double last_status_s_ = 0.0;
};

}  // namespace sonarmap

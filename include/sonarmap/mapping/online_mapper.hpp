#pragma once
/// @file online_mapper.hpp
/// Mapping beams as they arrive from a sonar: the one mapping path. The batch mapSonarLog
/// (sonar_mapper.hpp) is a loop over an OnlineMapper fed the log's beams, so a live run and a log
/// give the same map.
///
/// Fed one beam at a time (in recording order) and, for a moving vehicle, navigation fixes as they
/// arrive, the mapper forms sweeps itself with splitSweeps' rules (SweepSplitter: a full turn, a
/// sector head's reversal, a change of range scale or gain) and mergeShortSweeps' joining of short
/// fragments of one head setting (SweepGrouper: a sweep is final once the next one has the
/// detector's min_beams beams, once the setting changes, or at finish()). A final group of fewer
/// than min_beams beams (a range scale the user passed through) is detected with the calibration
/// of the last whole sweep of its setting (detectRows) or, without one, not mapped and counted
/// (MappingStats::beams_uncalibrated): a handful of bearings gives no background. A final sweep is detected (calibration, cleaning, first obstacle per beam: the
/// detector needs the whole sweep for its per-sweep background) and integrated as soon as the
/// navigation covers its last beam (a fix at or after its time), or at finish(). Detection runs on
/// other threads while the previous sweep is integrated when MapperOptions::pipeline_detection
/// is set (the batch's throughput; a sweep is then integrated when the next one is final, or the
/// next few: setDetectionsAhead);
/// without it each final sweep is detected and integrated at once (the least latency).
///
/// With OnlineIntegration::kProvisionalBeams each beam is also shown at once on a provisional layer
/// until its sweep is committed (see the enum): the committed map is at every moment mapSonarLog's
/// map of the sweeps final so far, and the final map is mapSonarLog's.
///
/// Another thread may read the map at any time through mapSnapshot() / shownSnapshot() /
/// statsSnapshot(): they copy under a shared lock that the feeding thread holds exclusively only
/// while it integrates one sweep or one provisional beam.
#include <cstddef>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/mapping/detected_log.hpp"
#include "sonarmap/mapping/provisional_beams.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {

/// What an OnlineMapper shows before a sweep is final.
enum class OnlineIntegration {
  /// Nothing: each sweep is integrated once it is final (see the file's comment), mapSonarLog's
  /// map byte for byte; a beam waits for the end of its sweep and min_beams beams of the next one
  /// to be in the map.
  kSweep,
  /// kSweep's map (the committed map: mapSnapshot), and each beam shown at once on a provisional
  /// layer (shownSnapshot; ProvisionalBeams) until its sweep is committed: detected with the
  /// calibration of the last whole sweep of its head setting (SonarMapper::detectRows: its water
  /// background, threshold and near field) and integrated on its own. A beam waits for a first
  /// whole sweep of its setting (no calibration before); with navigation, a beam after the last fix
  /// (by at most 1 s; later ones wait for a fix) is shown at that fix's pose, held, since the
  /// navigation lags the sonar; beams are shown in recording order. Detection is never pipelined: a sweep is
  /// committed as soon as it is final, and the provisional beams it held are dropped then. Live
  /// mapping: a beam's latency on screen, and the batch's map at the end.
  kProvisionalBeams,
};

class OnlineMapper {
 public:
  /// Called on the feeding thread after each sweep is integrated, with the count so far.
  using SweepCallback = std::function<void(std::size_t sweeps_integrated)>;
  /// Receives each detected sweep instead of the map (detectOnly).
  using DetectedSweepSink = std::function<void(DetectedSweep&& sweep)>;

  /// A static sonar at the map origin (identity pose), as mapSonarLog without navigation.
  /// @throws ValueError when `options` is invalid (MapperOptions::validate).
  explicit OnlineMapper(const MapperOptions& options, OnlineIntegration integration = OnlineIntegration::kSweep,
                        SweepCallback on_sweep = {});
  /// A moving vehicle: each beam placed at nedToMap() · bodyToNed(t) · sonar_to_body, bodyToNed
  /// interpolated from the fixes given to addNavFix (as mapSonarLog with a NavTrack); a beam
  /// outside the fixes' time span is skipped and counted (MappingStats::beams_without_nav).
  /// @param sonar_to_body  the sonar's mounting: sonar frame (beam.hpp) → body frame (FRD).
  /// @throws ValueError when `options` is invalid or the mounting is not finite.
  OnlineMapper(const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body,
               OnlineIntegration integration = OnlineIntegration::kSweep, SweepCallback on_sweep = {});
  ~OnlineMapper();
  OnlineMapper(const OnlineMapper&) = delete;
  OnlineMapper& operator=(const OnlineMapper&) = delete;

  /// The next navigation fix (NED, body FRD; navigation.hpp), on the beams' clock; may integrate
  /// sweeps that were waiting for it. Only with the navigation constructor.
  /// @throws ValueError for a fix that is not finite or not strictly after the previous one, or
  ///         without the navigation constructor; rethrows what integrating a waiting sweep threw.
  void addNavFix(const NavSample& fix);
  /// The next beam in recording order (time_s, bearing_rad, bin_length_m > 0, intensities, and
  /// what the head recorded of its settings: intensity_span_db, gain_setting, pulse_length_m; the
  /// gain splits sweeps and calibrations, the pulse bounds the echo length asked for, the span
  /// converts dB to counts); may integrate a sweep it completes. A beam given without a field the
  /// reader of its log fills is not the log's beam: its map may differ from mapSonarLog's.
  /// kProvisionalBeams: shows it, or the beams before it, if it can (see the enum).
  /// @throws ValueError for a beam whose bin length is not finite and > 0, whose intensity span or
  ///         pulse length is set and not finite and > 0, after finish(), on a mapper given beams to
  ///         show (showBeam), or what detecting or integrating a sweep threw (a sweep that mixes bin
  ///         lengths).
  void addBeam(Beam beam);
  /// With MapperOptions::pipeline_detection: how many final sweeps may be in detection, each on its
  /// own thread, while the oldest of them waits to be integrated here. 1 (the default): a sweep is
  /// integrated once the next one is final, the least lag for live mapping. More keeps every core
  /// detecting when detection is the slower stage (mapSonarLog: one per hardware thread; CRAS in
  /// 2D on two cores maps in 31 ms instead of 36, docs/performance.md). Sweeps are integrated in
  /// order, so the map is the same for any number. Set it before the first beam.
  /// @throws ValueError for 0.
  void setDetectionsAhead(std::size_t sweeps);
  /// The end of the stream: the last sweep is final, every held sweep is integrated (beams beyond
  /// the last fix counted without navigation). Further beams are refused. Idempotent.
  /// @throws ValueError  what detecting or integrating a sweep threw.
  void finish();

  /// The sonar has stopped (a live stream silent for a while: the ROS node's `idle_commit_s`): the
  /// beams held are final as finish() would make them (the sweep being received ends here, joined
  /// to its group), and every final sweep is integrated, pipelined detections included; with
  /// `navigation_ended`, a sweep still waiting for navigation too, with the fixes given so far (its
  /// beams beyond the last fix counted without navigation, as at finish()), else it waits for its
  /// fix. Unlike finish(), beams may follow: the next one starts a new sweep (so a stream that
  /// resumes is mapped as two streams, not as mapSonarLog maps it whole). Called at the end of a
  /// stream, the map is finish()'s, that is mapSonarLog's. Nothing held: nothing happens.
  /// @throws ValueError  what detecting or integrating a sweep threw.
  void commitHeld(bool navigation_ended);

  /// From now on each final sweep, once detected, goes to `sink` (on the feeding thread, in
  /// recording order) and is not integrated: the detection stage alone (detectSonarLog). The
  /// calibrations, the short groups' handling and MappingStats::beams_uncalibrated are as when
  /// mapping; the map stays empty. Call before the first beam.
  /// @throws ValueError with OnlineIntegration::kProvisionalBeams (nothing is shown), after the
  ///         first beam, or for an empty sink.
  void detectOnly(DetectedSweepSink sink);
  /// Integrates a sweep detected by another OnlineMapper with the same options (detectOnly), placed
  /// with the fixes given so far (navigation mode; a beam beyond them is counted without
  /// navigation): what integrating it there would have done. The beams it holds (sweep.first_beam
  /// and on) leave the provisional layer.
  /// @throws ValueError when the detections and the polar image differ in length, or in detect-only
  ///         mode.
  void addDetectedSweep(const DetectedSweep& sweep);

  /// For a mapper fed detected sweeps (addDetectedSweep) with kProvisionalBeams: `sweep`'s
  /// calibration becomes its head setting's, what the beams of that setting given to showBeam are
  /// detected with (a mapper fed beams by addBeam keeps those of its own sweeps). A copy is kept
  /// (with the evidence detector's water, about 2 KB a column).
  void calibrateWith(const DetectedSweep& sweep);
  /// For a mapper fed detected sweeps (addDetectedSweep) with kProvisionalBeams: beam `index` of the
  /// stream (DetectedSweep::first_beam counts the same beams), shown on the provisional layer as
  /// soon as its setting is calibrated (calibrateWith) and the navigation covers it, until the
  /// detected sweep that holds it is added. Give calibrateWith each sweep as soon as it is
  /// detected, before the beams after it: a beam still without a calibration when a beam of
  /// another setting is given is taken for a group too short to calibrate on, and never shown.
  /// @throws ValueError without kProvisionalBeams, after addBeam was used (a mapper fed beams shows
  ///         them itself), for an index not after the previous one, a beam addBeam refuses, or
  ///         after finish().
  void showBeam(std::size_t index, Beam beam);

  /// Sweeps integrated so far.
  std::size_t sweepsIntegrated() const;
  /// Beams received and not yet integrated into the committed map (feeding thread only).
  std::size_t beamsPending() const { return held_.size() + waiting_beams_; }
  /// Beams received and shown neither on the provisional layer nor in the committed map: the
  /// newest ones (beams are shown in order). kSweep: beamsPending(). Feeding thread only.
  std::size_t beamsUnshown() const { return provisional_ ? unshown_.size() : beamsPending(); }

  /// A copy of the committed map (as of the last integrated sweep); safe from any thread.
  OcTree16 mapSnapshot() const;
  /// A copy of the map as shown: the committed map with the provisional beams' log-odds added
  /// (ProvisionalBeams::overlay); kSweep: mapSnapshot(). Safe from any thread.
  OcTree16 shownSnapshot() const;
  /// The map as shown in `box_m` (map frame, metres; clipped to the map's extent), read in place:
  /// calls visit(committed map, the box's voxels the provisional layer changes: ProvisionalBeams::
  /// shownVoxels) under the shared lock, without copying the map. Safe from any thread; `visit`
  /// must not call the mapper, and holds back the feeding thread while it runs.
  void visitShown(const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) const;
  /// A copy of the counts as of the last integrated sweep; safe from any thread.
  MappingStats statsSnapshot() const;
  /// A copy of the options mapped with; safe from any thread. With the resolution on "auto" its
  /// resolution_m is unset until the first sweep is integrated, and grows with a longer range
  /// scale (SonarMapper).
  MapperOptions optionsSnapshot() const;
  /// The mapper itself: only on the feeding thread (no lock).
  const SonarMapper& mapper() const { return mapper_; }
  SonarMapper& mapper() { return mapper_; }
  /// Moves the mapper out (after finish()); the OnlineMapper is then empty.
  SonarMapper release() &&;

 private:
  /// A final group of beams; `cut`: it ended at a change of head setting or at the end of the
  /// stream, not at the end of a sweep.
  struct ReadyGroup {
    std::vector<Beam> beams;
    bool cut = false;
    std::size_t first_beam = 0;  ///< index of its first beam in the stream
  };
  void emitGroup(std::size_t beams, bool cut);
  void processReady();
  /// A final group of fewer than min_beams beams (a head setting used for fewer beams), or a cut
  /// group of fewer than half the beams of the sweep its setting was last calibrated on.
  void processShortGroup(ReadyGroup group);
  /// Whether `group` is detected with its setting's calibration instead of its own (see above).
  bool detectedAsShort(const ReadyGroup& group);
  /// Integrates a detected sweep (or hands it to the detect-only sink); `calibrates`: its
  /// calibration becomes its setting's.
  void integrate(DetectedSweep sweep, bool calibrates = true);
  /// Records and integrates `sweep` into the map with its beams' poses, and counts it; its beams
  /// leave the provisional layer.
  void integrateIntoMap(const DetectedSweep& sweep);
  /// Under map_mutex_: the beams before `end` are in the committed map (or never will be): they
  /// leave the provisional layer and the beams waiting to be shown.
  void committedBefore(std::size_t end);
  /// kProvisionalBeams: shows the waiting beams that can be shown, in order (see the enum).
  void showWaitingBeams();
  const SweepCalibration* calibrationOf(const HeadSetting& setting) const;
  /// Keeps `calibration`, measured on a sweep of `beams` beams, as its setting's.
  void keepCalibration(const HeadSetting& setting, SweepCalibration calibration, std::size_t beams);
  bool navigationCovers(double time_s) const;
  /// The poses of `times_s` (navigation mode: nullopt outside the fixes).
  std::vector<std::optional<Eigen::Isometry3d>> posesAt(const std::vector<double>& times_s) const;

  SonarMapper mapper_;
  OnlineIntegration integration_;
  SweepCallback on_sweep_;
  std::optional<Eigen::Isometry3d> sonar_to_body_;  ///< set: navigation mode
  NavTrack fixes_;
  SweepSplitter splitter_;
  SweepGrouper grouper_;
  std::deque<Beam> held_;                        ///< beams of groups not yet final
  std::deque<ReadyGroup> ready_;                 ///< final groups waiting for navigation
  std::size_t waiting_beams_ = 0;                ///< beams of final groups not yet integrated
  std::deque<std::future<DetectedSweep>> in_flight_;  ///< detections running beside integration, oldest first
  std::size_t detections_ahead_ = 1;                  ///< setDetectionsAhead
  /// Integrates the oldest sweep in detection, once detected.
  void integrateOldest();
  /// Integrates every sweep still in detection, in order.
  void integrateInFlight();
  /// Waits for every detection still running, without integrating it.
  void waitForDetections();
  std::size_t sweeps_ = 0;
  std::size_t beams_grouped_ = 0;  ///< beams handed to final groups so far
  bool finished_ = false;
  bool navigation_ended_ = false;  ///< commitHeld(true) in progress: navigation taken as complete
  DetectedSweepSink detect_only_;  ///< set: detection alone (detectOnly)
  /// The calibration of the last whole sweep of each head setting seen (few: a range knob's stops).
  struct KeptCalibration {
    HeadSetting setting;
    SweepCalibration calibration;
    std::size_t beams = 0;  ///< of the sweep it was measured on
  };
  std::vector<KeptCalibration> calibrations_;
  // kProvisionalBeams
  struct UnshownBeam {
    std::size_t index = 0;  ///< in the stream
    bool starts_sweep = false;
    Beam beam;
  };
  std::unique_ptr<ProvisionalBeams> provisional_;  ///< set: kProvisionalBeams
  std::deque<UnshownBeam> unshown_;                ///< received, neither shown nor committed
  std::size_t beams_added_ = 0;                    ///< beams given to addBeam
  bool shows_given_beams_ = false;                 ///< showBeam was used
  std::size_t last_shown_index_ = 0;               ///< the last index given to showBeam
  std::size_t committed_end_ = 0;                  ///< every beam before it is committed
  mutable std::shared_mutex map_mutex_;  ///< exclusive while a sweep is integrated
};

}  // namespace sonarmap

#pragma once
/// @file online_mapper.hpp
/// Mapping beams as they arrive from a sonar (issue 12): the one mapping path. The batch
/// mapSonarLog (sonar_mapper.hpp) is a loop over an OnlineMapper fed the log's beams, so a live
/// run and a log give the same map.
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
/// a second thread while the previous sweep is integrated when MapperOptions::pipeline_detection
/// is set (the batch's throughput; a sweep is then integrated when the next one is final);
/// without it each final sweep is detected and integrated at once (the least latency).
///
/// Another thread may read the map at any time through mapSnapshot() / statsSnapshot(): they copy
/// under a shared lock that the feeding thread holds exclusively only while it integrates one sweep.
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
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {

/// When an OnlineMapper integrates what it receives.
enum class OnlineIntegration {
  /// Each sweep once it is final (see the file's comment): mapSonarLog's map, byte for byte; a
  /// beam waits up to a turn of the head.
  kSweep,
  /// Each beam as it arrives (and the navigation covers it): detected with the calibration of the
  /// last whole sweep (SonarMapper::detectRows: its water background, threshold and near field),
  /// integrated on its own (SonarMapper::integrateBeams: a cell is updated once per beam, so the
  /// overlap of neighbouring wedges is updated twice, unlike a sweep). The calibration is kept per
  /// head setting (range scale and gain): the first sweep of a setting not seen before is
  /// integrated whole once it ends, to calibrate, and a return to an earlier setting is mapped beam
  /// by beam again at once; a whole sweep shorter than the detector's min_beams joins the next one
  /// of its setting, or is detected as a short group (above). Detection is never pipelined. Live
  /// mapping: the latency of a beam, not of a turn.
  kBeam,
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
  /// The next beam in recording order (time_s, bearing_rad, bin_length_m > 0, intensities); may
  /// integrate a sweep it completes.
  /// @throws ValueError for a beam whose bin length is not finite and > 0,
  ///         after finish(), or what detecting or integrating a sweep threw (a sweep that mixes
  ///         bin lengths).
  void addBeam(Beam beam);
  /// The end of the stream: the last sweep is final, every held sweep is integrated (beams beyond
  /// the last fix counted without navigation). Further beams are refused. Idempotent.
  /// @throws ValueError  what detecting or integrating a sweep threw.
  void finish();

  /// From now on each final sweep, once detected, goes to `sink` (on the feeding thread, in
  /// recording order) and is not integrated: the detection stage alone (detectSonarLog). The
  /// calibrations, the short groups' handling and MappingStats::beams_uncalibrated are as when
  /// mapping; the map stays empty. Call before the first beam.
  /// @throws ValueError with OnlineIntegration::kBeam (beams are detected one by one there), after
  ///         the first beam, or for an empty sink.
  void detectOnly(DetectedSweepSink sink);
  /// Integrates a sweep detected by another OnlineMapper with the same options (detectOnly), placed
  /// with the fixes given so far (navigation mode; a beam beyond them is counted without
  /// navigation): what integrating it there would have done. Its calibration becomes its
  /// setting's (kBeam: the beams given after it are detected with it).
  /// @throws ValueError when the detections and the polar image differ in length, or in detect-only
  ///         mode.
  void addDetectedSweep(const DetectedSweep& sweep);

  /// Sweeps integrated so far (kBeam: sweeps whose beams are all integrated).
  std::size_t sweepsIntegrated() const;
  /// Beams received and not yet integrated (feeding thread only).
  std::size_t beamsPending() const { return held_.size() + waiting_beams_ + beam_queue_.size() + (live_whole_ ? live_sweep_.size() : 0); }

  /// A copy of the map as of the last integrated sweep; safe from any thread.
  OcTree16 mapSnapshot() const;
  /// A copy of the counts as of the last integrated sweep; safe from any thread.
  MappingStats statsSnapshot() const;
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
  /// Records and integrates `sweep` into the map with its beams' poses, and counts it.
  void integrateIntoMap(const DetectedSweep& sweep);
  const SweepCalibration* calibrationOf(const HeadSetting& setting) const;
  /// Keeps `calibration`, measured on a sweep of `beams` beams, as its setting's.
  void keepCalibration(const HeadSetting& setting, SweepCalibration calibration, std::size_t beams);
  bool navigationCovers(double time_s) const;
  /// The poses of `times_s` (navigation mode: nullopt outside the fixes).
  std::vector<std::optional<Eigen::Isometry3d>> posesAt(const std::vector<double>& times_s) const;
  // kBeam
  void addLiveBeam(Beam beam, bool starts_sweep);
  /// Ends the sweep being received; `next`: the setting of the beam that starts the next one
  /// (nullopt at the end of the stream).
  void closeLiveSweep(const std::optional<HeadSetting>& next);
  void processBeamQueue();
  void integrateLiveBeam(const Beam& beam);

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
  std::unique_ptr<std::future<DetectedSweep>> in_flight_;  ///< detection running beside integration
  std::size_t sweeps_ = 0;
  std::size_t beams_grouped_ = 0;  ///< beams handed to final groups so far
  bool finished_ = false;
  DetectedSweepSink detect_only_;  ///< set: detection alone (detectOnly)
  /// The calibration of the last whole sweep of each head setting seen (few: a range knob's stops).
  struct KeptCalibration {
    HeadSetting setting;
    SweepCalibration calibration;
    std::size_t beams = 0;  ///< of the sweep it was measured on
  };
  std::vector<KeptCalibration> calibrations_;
  // kBeam: the raw sweep being received, the beams waiting for navigation.
  std::vector<Beam> live_sweep_;
  bool live_whole_ = false;  ///< the sweep being received is integrated whole when it ends
  std::deque<Beam> beam_queue_;
  mutable std::shared_mutex map_mutex_;  ///< exclusive while a sweep is integrated
};

}  // namespace sonarmap

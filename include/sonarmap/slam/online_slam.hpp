#pragma once
/// @file online_slam.hpp
/// Live mapping with localization (`sonarmap live --slam`): beams and dead-reckoning fixes arrive
/// one at a time; each sweep is detected once, as the batch detects it (an OnlineMapper in
/// detect-only mode: detected_log.hpp), and becomes a scan (scan_forming.hpp) for the Localizer
/// (localizer.hpp). The map (an OnlineMapper given the dead reckoning corrected by the latest
/// scan's correction) integrates those detected sweeps once the navigation covers them (the
/// committed map); with OnlineIntegration::kProvisionalBeams each beam is also shown at once on
/// its provisional layer (OnlineMapper::showBeam), detected with its setting's last calibration,
/// until its sweep is integrated. When a loop closure moves the past poses (a scan by more than
/// half a voxel at its reach, since the map was last built), the map is rebuilt from the detected
/// sweeps so far with the corrected trajectory (no detection again; the beams after the last
/// integrated sweep are shown again) as soon as the sweeps since the last rebuild have paid for it
/// (two sweeps' worth of integration each): early in a log after each loop closure, later each time
/// the log has grown by half, so that rebuilding costs at most twice the log's own integration and
/// the time stays linear in the log's length. After finish() the
/// map and trajectory are those of the batch path (mapSonarLogWithSlam) on the same beams and
/// fixes, in either integration.

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/slam/localizer.hpp"

namespace sonarmap {

class OnlineSlam {
 public:
  /// @param navigation  whether dead-reckoning fixes will be given (addNavFix); without, the
  ///        vehicle is believed still and its motion comes from the scans alone (localize).
  /// @throws ValueError for invalid options or mounting.
  OnlineSlam(const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body, bool navigation,
             const SlamOptions& slam = {},
             OnlineIntegration integration = OnlineIntegration::kProvisionalBeams);
  /// The localization's options from the navigation received so far (a class stated as `auto`:
  /// odometry_noise.hpp's navigationClassOf, and the fixes' period: withNavigationPeriod).
  using SlamOptionsFromFixes = std::function<SlamOptions(const NavTrack& fixes)>;
  /// As above, the options decided when the first sweep completes, from the fixes received by then
  /// (a stream's navigation is not known at the start: a vehicle without a DVL sends north and
  /// east 0, which `map --slam` of the recording takes as heading only).
  /// @throws ValueError as above, and when `decide` is empty.
  OnlineSlam(const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body, SlamOptionsFromFixes decide,
             OnlineIntegration integration = OnlineIntegration::kProvisionalBeams);

  /// The next dead-reckoning fix (NED, on the beams' clock), strictly after the previous one.
  /// @throws ValueError for a fix that is not finite or not after the previous one, or without
  ///         navigation.
  void addNavFix(const NavSample& fix);
  /// The next beam in recording order; may complete a sweep (a scan for the localizer, and a map
  /// rebuild when it closes a loop).
  /// @throws ValueError as OnlineMapper::addBeam, or after finish().
  void addBeam(Beam beam);
  /// The end of the stream: the last sweep's scan, the final optimisation, and the map rebuilt
  /// with the final trajectory. Idempotent.
  void finish();

  /// A copy of the current committed map; safe from any thread.
  OcTree16 mapSnapshot() const;
  /// A copy of the current map as shown (OnlineMapper::shownSnapshot); safe from any thread.
  OcTree16 shownSnapshot() const;
  /// OnlineMapper::visitShown of the current map; safe from any thread.
  void visitShown(const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) const;
  /// Sweeps integrated into the current map; safe from any thread.
  std::size_t sweepsIntegrated() const;
  /// Beams received and not yet in the committed map (feeding thread only).
  std::size_t beamsPending() const;
  /// Beams received and not yet shown (OnlineMapper::beamsUnshown; feeding thread only).
  std::size_t beamsUnshown() const;
  /// The current mapper (feeding thread only).
  OnlineMapper& mapper() { return *mapper_; }
  const Localizer& localizer() const { return localizer_; }
  /// The trajectory the localizer currently believes (Localizer::correctedTrack of the fixes so
  /// far, or of none).
  NavTrack trajectory() const;
  /// The latest scan's correction of the dead reckoning (NED, metres and radians): the pose the
  /// localizer gives it ∘ its dead-reckoning pose⁻¹, so that corrected = correction ∘ dead reckoning
  /// (ROS's map → odom, REP 105). Identity before the first scan (feeding thread only).
  const Pose2& correction() const { return correction_; }
  std::size_t rebuilds() const { return rebuilds_; }
  /// Sweeps integrated again by the rebuilds so far: at most twice the sweeps detected before the
  /// last one, and all of them once more at finish().
  std::size_t sweepsRebuilt() const { return sweeps_rebuilt_; }

 private:
  /// A sweep the detector finished: its scan to the localizer, the sweep kept; may rebuild the map.
  void addSweep(DetectedSweep&& sweep);
  /// Integrates the kept sweeps not yet in `mapper` whose last beam the navigation covers (all of
  /// them after finish()).
  void mapCoveredSweeps(OnlineMapper& mapper);
  /// kProvisionalBeams, into a rebuilt `mapper`: each head setting's newest calibration, and the
  /// beams shown so far after the last integrated sweep.
  void showUnmappedBeams(OnlineMapper& mapper) const;
  /// Maps the detected sweeps so far with the current trajectory into a new OnlineMapper (and
  /// shows the beams after them) and swaps it in.
  void rebuild();
  /// Whether a scan's pose moved since the map was last rebuilt by more than half a voxel at its
  /// reach (position, plus reach × heading change): less changes no cell worth a rebuild.
  bool movedSinceRebuild() const;
  NavSample corrected(const NavSample& fix) const;

  MapperOptions options_;
  Eigen::Isometry3d sonar_to_body_;
  bool navigation_ = true;
  SlamOptions slam_;
  SlamOptionsFromFixes decide_;  ///< set: slam_ decided at the first sweep
  OnlineIntegration integration_;
  Localizer localizer_;
  SonarLog beams_;        ///< every beam so far
  NavTrack dead_reckoning_;
  std::unique_ptr<OnlineMapper> detector_;  ///< detect-only: the batch's sweeps and detections
  std::vector<DetectedSweep> sweeps_;       ///< every sweep detected so far
  std::size_t sweeps_mapped_ = 0;           ///< of sweeps_, those in the current map
  std::size_t beams_shown_ = 0;             ///< kProvisionalBeams: beams given to the mapper to show
  std::size_t accepted_loops_ = 0;
  std::size_t rebuilds_ = 0;
  /// Sweeps' worth of integration the rebuilds may spend: each detected sweep earns
  /// kRebuildSweepsPerSweep, a rebuild of n sweeps spends n. The rebuilds then cost at most that
  /// many times the log's own integration, and live --slam stays linear in the log's length (a
  /// rebuild at each loop closure would be quadratic: every lap after the first closes loops).
  static constexpr std::size_t kRebuildSweepsPerSweep = 2;
  std::size_t rebuild_budget_ = 0;
  std::size_t sweeps_rebuilt_ = 0;
  bool rebuild_wanted_ = false;  ///< a loop closure moved the past poses since the last rebuild
  bool finished_ = false;
  Pose2 correction_;  ///< the latest scan's: optimised ∘ dead reckoning⁻¹
  /// The scans' poses the current map was built with: each scan's as it was when the next one came,
  /// or all of them as of the last rebuild.
  std::vector<Pose2> mapped_poses_;
  mutable std::shared_mutex swap_mutex_;  ///< exclusive while the mapper is swapped
  std::unique_ptr<OnlineMapper> mapper_;
};

}  // namespace sonarmap

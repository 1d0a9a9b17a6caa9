#pragma once
/// @file live_mapping.hpp
/// The mapper of a live run: beams and navigation fixes as they arrive, mapped by an OnlineMapper
/// (mapping/online_mapper.hpp) or, with SLAM, an OnlineSlam (slam/online_slam.hpp), with each
/// beam's latency to the map as shown and to the committed map kept (stage_latencies.hpp), the
/// map's local origin decided at the first fix, and a reset that starts the map again.
///
/// Threads: every call but shownSnapshot(), sweepsIntegrated() and beamsShown() is made on one
/// thread, the one that feeds it (the live session's); those three are safe from any thread.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/live/stage_latencies.hpp"
#include "sonarmap/mapping/local_origin.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/slam/online_slam.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// How a live run maps.
struct LiveMappingOptions {
  MapperOptions mapper;  ///< the sonar's beam set (withSonarBeam) and the mapping options
  /// The sonar's mounting: sonar frame → body frame (FRD).
  Eigen::Isometry3d sonar_to_body = defaultSonarToBody();
  OnlineIntegration integration = OnlineIntegration::kProvisionalBeams;
  /// Whether navigation fixes come at all (a file known at the start, or a stream); without, the
  /// sonar is mapped as static at the origin.
  bool navigation = false;
  /// Set: the navigation is corrected by scan matching as sweeps complete (OnlineSlam).
  std::optional<SlamOptions> slam;
  /// Set (with `navigation`): as `slam`, its options decided at the first sweep from the fixes
  /// received by then (OnlineSlam::SlamOptionsFromFixes: a stream's navigation class and period);
  /// takes the place of `slam`.
  OnlineSlam::SlamOptionsFromFixes slam_from_fixes;
  /// The map's zero in the navigation's frame when the caller chose it (a replayed log's, from its
  /// whole track and reach); unset: chosen from the fixes known at the start, else at the first
  /// fix (chooseLocalOrigin at origin_resolution_m, given_origin when set).
  std::optional<LocalOrigin> origin;
  std::optional<Eigen::Vector3d> given_origin;  ///< --origin
  double origin_resolution_m = 0.1;             ///< > 0
};

/// The mapper fed by a live run (see the file's comment). Times are the beams' clock (seconds);
/// arrivals are the session's steady clock (seconds since its start).
class LiveMapping {
 public:
  /// `known_fixes`: the fixes known at the start, in the navigation's own frame (moved to the
  /// map's origin here), given to the mapper first. `start`: the zero of the arrival clock
  /// (latencies are measured on it).
  /// @throws ValueError as OnlineMapper's and OnlineSlam's constructors.
  LiveMapping(LiveMappingOptions options, std::chrono::steady_clock::time_point start, const NavTrack& known_fixes = {});
  ~LiveMapping();

  /// Maps `beam` (its time on the fixes' clock), which arrived at `arrival_s`.
  /// @throws ValueError as OnlineMapper::addBeam.
  void addBeam(Beam beam, double arrival_s);
  /// Adds a fix in the navigation's own frame (moved to the map's origin here; the origin is
  /// chosen at the first fix when not known). A fix not after the previous one is dropped and
  /// counted (fixesDropped()).
  void addFix(NavSample fix, double arrival_s);
  /// The end of the stream: the held sweeps integrated. The beams mapped only now are not timed.
  void finish();
  /// Starts an empty map: the beams so far are forgotten, the fixes kept (a reset asked from the
  /// page). Returns the beams dropped from the map.
  std::size_t reset();

  /// The current mapper (with SLAM, rebuilt when a loop closes). Feeding thread only.
  OnlineMapper& mapper();
  const OnlineSlam* slam() const { return slam_.get(); }
  /// The sonar's mounting (sonar frame → body FRD).
  const Eigen::Isometry3d& sonarToBody() const { return options_.sonar_to_body; }
  /// A copy of the map as shown (the provisional beams over the committed map); any thread.
  OcTree16 shownSnapshot() const;
  /// OnlineMapper::visitShown of the map as shown; safe from any thread.
  void visitShown(const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) const;
  /// Sweeps integrated so far (since the last reset); any thread.
  std::size_t sweepsIntegrated() const;
  /// Beams given since the start, and those shown in the map (since the last reset); any thread.
  std::size_t beams() const { return beams_.load(); }
  std::size_t beamsShown() const { return beams_shown_.load(); }
  /// Beams given and not yet in the map as shown (the newest). Feeding thread.
  std::size_t beamsUnshown() const { return beams_ - beams_at_reset_ - beams_shown_; }
  /// The map's zero in the navigation's frame (zero before any fix); any thread.
  LocalOrigin origin() const;
  /// The last fix given, moved to the map's origin (NED); nullopt before the first.
  const std::optional<NavSample>& lastFix() const { return last_fix_; }
  std::size_t fixes() const { return fixes_.size(); }
  std::size_t fixesDropped() const { return fixes_dropped_; }
  StageLatencies& shown() { return shown_; }
  StageLatencies& committed() { return committed_; }

 private:
  void build();
  /// Settles the latencies of the beams that reached a stage by now.
  void collect();

  LiveMappingOptions options_;
  std::chrono::steady_clock::time_point start_;
  /// Held by the readers from other threads while the mapper is replaced (build()); the feeding
  /// thread's own calls need it not, as only it replaces the mapper.
  mutable std::mutex replacing_;
  mutable std::mutex origin_mutex_;  ///< origin_ is chosen on the feeding thread, read from any
  std::unique_ptr<OnlineMapper> mapper_;
  std::unique_ptr<OnlineSlam> slam_;  ///< with SLAM, instead of mapper_
  NavTrack fixes_;                    ///< every fix given, in the map's origin (for a reset)
  std::optional<NavSample> last_fix_;
  std::optional<LocalOrigin> origin_;
  StageLatencies shown_, committed_;
  std::atomic<std::size_t> beams_{0}, beams_shown_{0};
  std::size_t beams_at_reset_ = 0;
  std::size_t fixes_dropped_ = 0;
};

}  // namespace sonarmap

#pragma once
/// @file localizer.hpp
/// Sonar-aided navigation (the "L" of the paper's SLAM, §9): scans (scan_forming.hpp) matched against the
/// scans just before them and against scans seen long before near the current estimate (loop
/// closures), on a pose graph (pose_graph.hpp) with dead reckoning's odometry. A loop closure is
/// accepted only when the matcher finds it unambiguous, it agrees with dead reckoning within the
/// drift dead reckoning may have had (a χ² gate), and it agrees with every loop closure accepted
/// before it (pairwise consistency: Mangelson et al. 2018, "Pairwise consistent measurement set
/// maximization for robust multi-robot map merging", ICRA; used for sonar by Bruce SLAM, Wang et
/// al. 2022). The corrected trajectory moves each dead-reckoning fix by the correction of the
/// scans around it, interpolated in time.
///
/// A loop closure is sought for every scan among the scans older than its submap
/// (SlamOptions::loop_search_radius_m, loop_min_travel_m).
///
/// With the heading alone (OdometryNoise::position_measured false: an AHRS or compass without a
/// DVL), each scan is predicted at the velocity over the ground of the two scans before it, its
/// points moved by that velocity to their scan's reference time (the motion compensation a
/// position would have given), and matched with a correlative search over the unknown motion's
/// window; no loop closure is sought (the gates assume dead reckoning's drift, not the scans').
///
/// One path for batch (localize) and live mapping (Localizer fed scan by scan).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/pose_graph.hpp"
#include "sonarmap/slam/scan_forming.hpp"
#include "sonarmap/slam/scan_matcher.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Options of the localization, in physical units.
struct SlamOptions {
  ScanFormingOptions forming;  ///< the odometry noise model and the points' uncertainty
  ScanMatchOptions matching;
  PoseGraphOptions graph;
  std::size_t submap_scans = 3;  ///< scans before a scan that it is matched against, ≥ 1
  /// Estimate the odometry's scale factor with the poses (PoseGraph::estimateOdometryScale, prior
  /// 1 ± forming.odometry.scale_sigma; the odometry edges then keep a fifth of that σ) where the
  /// scans constrain it: once the last scan is in (Localizer::optimize), its marginal σ is
  /// computed, and unless the scans carry at least the prior's information on it (σ ≤ the prior's
  /// / √2), it is fixed at 1 and the graph solved again with the full scale error in each edge
  /// (the observability test; SlamReport::odometry_scale_observed). false: the odometry's scale is
  /// trusted, its error left in each edge's covariance.
  bool estimate_odometry_scale = true;
  /// A loop closure is sought among the scans whose estimated reference position lies within this
  /// of the new scan's, metres, ≥ 0; 0: automatic, for each older scan the nearer of half the
  /// scans' median reach and where its true neighbour can be (half the old scans' spacing along
  /// the path plus 3σ of dead reckoning's drift since, Localizer::pathCovariance): a view of the
  /// place from farther away sees small targets from another side (a pile's echo comes from the
  /// side facing the sonar), and a later scan passes nearer.
  double loop_search_radius_m = 0.0;
  /// ... and that the vehicle left at least this far back along its path, metres, ≥ 0; 0:
  /// automatic, twice the scans' median reach (so that a loop closure is not just the last turn),
  /// unless it has travelled no farther than the search radius since (a hovering or static
  /// vehicle: its scans older than the submap are loop closures too).
  double loop_min_travel_m = 0.0;
  /// Gate of a loop closure against the current estimate: its squared Mahalanobis distance with the
  /// covariance dead reckoning accumulates along the path between the two scans plus the match's,
  /// 3 degrees of freedom; 11.34 is χ²₃'s 99 % quantile. > 0.
  double loop_gate_chi2 = 11.34;
  /// Gate of the pairwise consistency of two loop closures (the cycle they close with the
  /// estimate between their ends), χ²₃. > 0.
  double consistency_chi2 = 11.34;

  /// @throws ValueError naming the field when out of range.
  void validate() const;
};

/// A loop closure the localizer tried.
struct LoopClosure {
  std::size_t from = 0;  ///< the older scan
  std::size_t to = 0;    ///< the newer scan
  Pose2 measurement;     ///< `to` in `from`'s frame, as matched
  bool accepted = false;
  std::string reason;    ///< why refused; empty when accepted
  std::size_t pairs = 0;    ///< the match's pairs (0: proposed from elsewhere)
  double peak_ratio = 0.0;  ///< the correlative search's best over its best distinct peak (ScanMatch)
};

/// What the localization did.
struct SlamReport {
  std::size_t scans = 0;
  std::size_t scans_with_points = 0;  ///< scans with enough detected obstacles to match
  std::size_t matches_accepted = 0;   ///< scans matched to the scans before them
  std::size_t matches_refused = 0;   ///< every match refused, those beyond the limits among them
  /// Matches refused because the motion they need is beyond the vehicle's limits where no position
  /// is measured (OdometryNoise::max_speed_mps, and max_turn_rate_radps without navigation).
  std::size_t matches_beyond_limits = 0;
  std::vector<LoopClosure> loop_closures;  ///< every loop closure matched, in order
  /// The odometry's scale factor the graph estimated (PoseGraph::odometryScale; 1 without
  /// navigation): 0.97 says the dead reckoning's distances were 3 % too long.
  double odometry_scale = 1.0;
  /// Its marginal σ when it was estimated (0: not estimated or not computable).
  double odometry_scale_sigma = 0.0;
  /// Whether the scans constrained the scale (SlamOptions::estimate_odometry_scale's test); false:
  /// odometry_scale is 1, the navigation's own.
  bool odometry_scale_observed = false;
  /// The navigation gave the heading only (OdometryNoise::position_measured false): the position
  /// came from the scans, and no loop closure was sought.
  bool heading_only = false;
  /// Point scans (localizePointScans): rows left out as lying behind their echo's leading edge
  /// (formPointScans), over every scan; 0 for a sonar log's own detections.
  std::size_t points_behind_echoes = 0;
  std::size_t loopClosuresAccepted() const;
};

/// The localization fed scan by scan (batch and live).
class Localizer {
 public:
  /// @param navigation_known  false: the scans were formed without navigation (the vehicle believed
  ///        still), so odometry uses OdometryNoise's unknown-motion model.
  /// @throws ValueError for invalid options.
  explicit Localizer(const SlamOptions& options, bool navigation_known = true);
  /// Adds the next scan (scans in time order): an odometry edge from the scan before, a match
  /// against the submap of the scans before, a loop closure when one is found and passes the gates
  /// (then the graph is optimised).
  void addScan(SonarScan scan);
  /// Offers a loop closure found elsewhere (or by closeLoop's match): scan `to` measured at
  /// `measurement` in scan `from`'s frame with `information` (in from's frame). It passes the same
  /// gates as the matcher's (the vehicle's limits where no position is measured, against the
  /// estimate with dead reckoning's drift along the path, and pairwise consistency with every
  /// accepted loop closure); accepted, it joins the graph, which is
  /// optimised. Recorded in report() either way. Returns whether it was accepted.
  /// @throws ValueError unless from < to < scans().size() and the values are finite.
  bool proposeLoopClosure(std::size_t from, std::size_t to, const Pose2& measurement, const Eigen::Matrix3d& information);
  /// Optimises the graph with every edge (call once the last scan is in), with the odometry
  /// scale's observability test (SlamOptions::estimate_odometry_scale).
  void optimize();

  const std::vector<SonarScan>& scans() const { return scans_; }
  const PoseGraph& graph() const { return graph_; }
  const SlamReport& report() const { return report_; }

  /// The corrected trajectory: each dead-reckoning fix moved by the correction (optimised pose ∘
  /// dead-reckoning pose⁻¹ of the scans, NED's plane) interpolated between the two scans around its
  /// time (the first's before the first scan, the last's after the last); depth, roll and pitch
  /// kept. With an empty `dead_reckoning`: one fix per scan at its start, reference and end times,
  /// poses from the graph (depth, roll and pitch 0). Empty when there is no scan.
  NavTrack correctedTrack(const NavTrack& dead_reckoning) const;

 private:
  /// Points of scans [first, last) placed with their current poses, in NED moved by `ned_to_frame`
  /// (identity: in NED).
  std::vector<ScanPoint> placedPoints(std::size_t first, std::size_t last, const Pose2& ned_to_frame = {}) const;
  /// Covariance of dead reckoning's relative pose from scan a to scan b (a < b), composed along the
  /// odometry edges.
  Eigen::Matrix3d pathCovariance(std::size_t a, std::size_t b) const;
  /// pathCovariance(a, b) for every a ≤ b (index a; zero at b), in one pass.
  std::vector<Eigen::Matrix3d> pathCovariancesTo(std::size_t b) const;
  /// The navigation measures the heading only (OdometryNoise::position_measured false).
  bool headingOnly() const { return navigation_known_ && !options_.forming.odometry.position_measured; }
  /// Whether `motion` (scan `to`'s pose in scan `from`'s frame) needs the vehicle to move or turn
  /// faster than its limits (OdometryNoise::max_speed_mps, max_turn_rate_radps) between the two
  /// scans' times, where the navigation measures no position.
  bool beyondLimits(std::size_t from, std::size_t to, const Pose2& motion) const;
  /// With the heading only: scan k (`duration_s` after scan k − 1, turned by `predicted`'s yaw) is
  /// predicted to move at the velocity over the ground (NED) of the last two scans' estimated
  /// poses (predicted's translation, metres in scan k − 1's frame), and its points, placed with
  /// the heading alone, are moved by that velocity times their ScanPoint::time_offset_s: the
  /// motion compensation a position would have given. Unchanged for k < 2.
  void continueAtLastVelocity(std::size_t k, double duration_s, Pose2& predicted, SonarScan& scan) const;
  void matchToSubmap(std::size_t k);
  void closeLoop(std::size_t k);
  /// Whether `loop` is consistent with every accepted loop closure.
  bool consistentWithAccepted(const LoopClosure& loop, const Eigen::Matrix3d& covariance) const;

  SlamOptions options_;
  bool navigation_known_ = true;
  std::vector<SonarScan> scans_;
  PoseGraph graph_;
  std::vector<Pose2> odometry_;                ///< dead-reckoning motion from scan k−1 to k (k ≥ 1)
  std::vector<Eigen::Matrix3d> odometry_cov_;  ///< its covariance
  std::vector<double> travelled_m_;            ///< dead-reckoning path length at each scan
  std::vector<Eigen::Matrix3d> loop_cov_;      ///< covariance of each accepted loop's measurement
  std::vector<std::size_t> accepted_loops_;    ///< indices into report_.loop_closures
  SlamReport report_;
};

/// The result of a batch localization.
struct SlamResult {
  NavTrack trajectory;          ///< Localizer::correctedTrack of the dead reckoning
  std::vector<Pose2> scan_poses;  ///< each scan's optimised reference pose (NED's plane)
  std::vector<double> scan_times_s;
  SlamReport report;
};

/// Forms the scans of a detected log (formScans) with `dead_reckoning` (empty: none; the vehicle
/// believed still), localizes them in order and optimises the graph. Deterministic. The
/// odometry's velocity-reading period is the navigation's median fix spacing.
/// @throws ValueError for invalid options or an invalid navigation track.
SlamResult localize(const DetectedLog& detected, const NavTrack& dead_reckoning, const Eigen::Isometry3d& sonar_to_body,
                    const SlamOptions& slam = {});

/// `slam` with the odometry's velocity-reading period (OdometryNoise::nav_period_s) set to the
/// navigation's median fix spacing; unchanged for fewer than two fixes.
SlamOptions withNavigationPeriod(SlamOptions slam, const NavTrack& dead_reckoning);

/// Localizes formed scans (in time order) with a Localizer, optimises the graph and corrects
/// `dead_reckoning` (empty: the scans were formed without navigation). Deterministic.
/// @throws ValueError for invalid options.
SlamResult localizeScans(std::vector<SonarScan> scans, const NavTrack& dead_reckoning, const SlamOptions& slam = {});

/// localize(detectSonarLog(log, options), ...).
/// @throws ValueError as detectSonarLog and the overload above.
SlamResult localize(const SonarLog& log, const NavTrack& dead_reckoning, const Eigen::Isometry3d& sonar_to_body,
                    const MapperOptions& options, const SlamOptions& slam = {});

}  // namespace sonarmap

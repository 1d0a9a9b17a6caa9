#pragma once
/// @file localizer.hpp
/// Sonar-aided navigation (the "L" of the paper's SLAM, §9): scans (scan_forming.hpp) matched against the
/// scans just before them and against scans seen long before near the current estimate (loop
/// closures), on a pose graph (pose_graph.hpp) with dead reckoning's odometry. Every unambiguous
/// loop-closure match is a candidate; the accepted ones are the largest set that agree pairwise
/// (the cycle two of them close with the dead reckoning between their ends: Mangelson et al. 2018,
/// "Pairwise consistent measurement set maximization for robust multi-robot map merging", ICRA;
/// used for sonar by Bruce SLAM, Wang et al. 2022; consistency_graph.hpp), a lone one only when the
/// dead reckoning along its path confirms it. Wrong loop closures rarely agree with each other, so
/// no bound on the dead reckoning's drift decides. The corrected trajectory moves each
/// dead-reckoning fix by the correction of the scans around it, interpolated in time.
///
/// A loop closure is sought for every scan among the scans older than its submap
/// (SlamOptions::loop_search_radius_m, loop_min_travel_m).
///
/// With navigation, how far the dead reckoning and the matches can be trusted is measured on the
/// log as it comes (navigation_calibration.hpp): each scan is also matched alone to the two scans
/// before it, without the dead reckoning's pull. Their turns against the compass's give a magnetic
/// compass's deviation (modelled, and estimated in the graph, once the matches show one); triangles
/// of them give the matches' own noise; at the end the accepted loop closures against the dead
/// reckoning give the odometry's noise, never below the stated class, and the candidates are
/// decided again with it (optimize).
///
/// Where no position is measured (the heading alone, OdometryNoise::position_measured false, or no
/// navigation) the scans are the odometry: each step as matched, with the match's information
/// joined with the motion model's (along a wall, or a corridor's two walls, the match measures only
/// across it, and the motion model decides along it with its own uncertainty), or the motion
/// model's alone where no match held. That chain is the dead reckoning the loop closures are
/// sought with and gated against, so the search radius grows with what the scans left uncertain
/// since the start. With the heading alone, each scan is predicted at the velocity over the ground
/// of the two scans before it, its points moved by that velocity to their scan's reference time
/// (the motion compensation a position would have given), matched with a correlative search over
/// the unknown motion's window, and joined to the scan before by that prediction (a vehicle's
/// speed does not jump); the compass's deviation (its prior) bends every path the chain gives, and
/// the matches estimate it. Without navigation the vehicle is believed still, and a match moves it
/// only when the scans fit the moved pose better than the still one beyond chance
/// (stillUnlessShown).
///
/// One path for batch (localize) and live mapping (Localizer fed scan by scan).

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/consistency_graph.hpp"
#include "sonarmap/slam/navigation_calibration.hpp"
#include "sonarmap/slam/odometry_chain.hpp"
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
  /// Measure on the log how far the navigation and the matches can be trusted
  /// (navigation_calibration.hpp): the matches' noise from triangles of matches, the odometry's
  /// from the accepted loop closures (never below the stated class). false: the stated class and
  /// the matches' pairs' information as they are. A compass's deviation is measured either way
  /// (OdometryNoise::deviation_sigma_rad 0 turns it off).
  bool calibrate_navigation = true;
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
  /// A loop closure no other agrees with stands only when the dead reckoning confirms it: its
  /// squared Mahalanobis distance from the dead reckoning's relative pose, with the covariance dead
  /// reckoning accumulates along the path between the two scans plus the match's, 3 degrees of
  /// freedom; 11.34 is χ²₃'s 99 % quantile. > 0.
  double loop_gate_chi2 = 11.34;
  /// Two loop closures agree when the cycle they close with the dead reckoning between their ends
  /// is within this χ²₃ of the identity. > 0.
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
  /// came from the scans, which are then the loop closures' dead reckoning too.
  bool heading_only = false;
  /// Point scans (localizePointScans): rows left out as lying behind their echo's leading edge
  /// (formPointScans), over every scan; 0 for a sonar log's own detections.
  std::size_t points_behind_echoes = 0;
  /// The odometry noise the localization used in the end: the stated class's revised on the log
  /// (calibrateOdometryNoise; the stated one where the log gave too little to measure it).
  OdometryNoise odometry_noise;
  /// The scan matches' noise beyond their pairs' information measured on the log
  /// (calibrateMatchNoise; zero where the log gave too little).
  MatchNoise match_noise;
  /// The heading sensor's deviation δ(ψ) = a cos ψ + b sin ψ the localization found, (a, b) in
  /// radians (PoseGraph::headingDeviation), when the matches showed one (heading_deviation_observed;
  /// otherwise zero: the heading taken as it is).
  Eigen::Vector2d heading_deviation_rad = Eigen::Vector2d::Zero();
  bool heading_deviation_observed = false;
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
  /// the graph's poses at the reference times and linearly interpolated between them (the yaw
  /// along the shorter arc; held before the first and after the last), so no step between two
  /// rows implies more speed or turn rate than the two scans' poses around it do in their time
  /// (depth, roll and pitch 0). Empty when there is no scan.
  NavTrack correctedTrack(const NavTrack& dead_reckoning) const;

 private:
  /// A loop closure the matcher found, within the vehicle's limits: a vertex of the consistency
  /// graph and a graph edge (of zero information unless accepted).
  struct LoopCandidate {
    std::size_t report = 0;  ///< its entry in report_.loop_closures
    std::size_t edge = 0;    ///< its graph edge
    /// Its measurement's information (the match's pairs' with the match noise, restated at each
    /// calibration, or as proposed from elsewhere).
    Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
    std::optional<Eigen::Matrix3d> pairs_information;  ///< set: a match of this localizer's
  };

  /// Points of scans [first, last) placed with their current poses, in NED moved by `ned_to_frame`
  /// (identity: in NED).
  std::vector<ScanPoint> placedPoints(std::size_t first, std::size_t last, const Pose2& ned_to_frame = {}) const;
  /// Matches `source` against `target` (scans [first, last) placed in NED) from `initial` with the
  /// prior `prior_ned`. With a position measured, or none, ICP from `initial` (the search first with
  /// `search`, or where ICP fails), the search on the samples. With the heading only the search
  /// places it: on the surfaces, the source's points outside the target scans' reach left out of
  /// its score (CoverageDisc), and the information bounded by its score surface (matchScans'
  /// bound_by_surface). Measured on the St. Pere survey with its DVL, the surface's bound and the
  /// reach cost 1.89 / 1.14 → 3.04 / 2.17 m (docs/localization.md): where the DVL's prior holds a
  /// direction the pairs leave free, the ICP's MAP pose already stays at the prediction there.
  ScanMatch matchAgainst(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source, std::size_t first,
                         std::size_t last, const Pose2& initial, const Eigen::Matrix3d& prior_ned, bool search) const;
  /// The navigation measures the heading only (OdometryNoise::position_measured false).
  bool headingOnly() const { return navigation_known_ && !options_.forming.odometry.position_measured; }
  /// A match constrained along one direction only (a wall: ScanMatch's "ambiguous: constrained")
  /// as a measurement across it: along the translation's weakest direction the pose is
  /// `predicted`'s and the information none, across it and in yaw the match's.
  static ScanMatch acrossWallOnly(const ScanMatch& match, const Pose2& predicted);
  /// Without navigation the vehicle is believed still: a match (`matched`, the source frame in the
  /// target's) moves it from where that belief puts it (`expected`) only when the scans fit there
  /// better beyond chance: twice the log-likelihood ratio of the two poses (pointLikelihoods, each
  /// point's with a floor for points that fit neither) above SlamOptions::loop_gate_chi2 (χ²₃'s
  /// 99 % quantile: one pose's three parameters); else `expected`. With navigation, `matched`.
  Pose2 stillUnlessShown(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source, const Pose2& expected,
                         const Pose2& matched) const;
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
  /// The dead reckoning's motion between two scans as the localizer predicts it: its translation
  /// times the odometry scale, its turn corrected by the heading deviation measured so far.
  Pose2 predictedMotion(const Pose2& motion, double from_heading_rad, double to_heading_rad) const;
  /// Matches scan k to the scans before it; returns the match's pairs' information (in scan
  /// k − 1's frame) when the match joined the graph.
  std::optional<Eigen::Matrix3d> matchToSubmap(std::size_t k);
  /// Where no position is measured the scans are the odometry (chain_, the loop closures' dead
  /// reckoning): scan k's step as estimated has the covariance of its match's information joined
  /// with the motion model's, or the motion model's alone where no match held.
  Eigen::Matrix3d scanOdometryCovariance(std::size_t k) const;
  /// The navigation measures the position (a DVL, fixes).
  bool positionMeasured() const { return navigation_known_ && options_.forming.odometry.position_measured; }

  // The navigation measured on the log (localizer_calibration.cpp).
  /// Scan k matched alone to scan k − 1 and to scan k − 2 from the dead reckoning's motion, without
  /// its prior (matchScansFrom): with the match k − 2 → k − 1 kept from the scan before, a triangle
  /// of matches (navigation_calibration.hpp). Recalibrates the match noise when the triangles have
  /// grown by a fifth since the last calibration.
  /// `from_last` and `from_second_last` start the two matches (scan k in scan k − 1's and k − 2's
  /// frames): the dead reckoning's where it measures the position, else the scans' own estimate.
  void measureMatches(std::size_t k, const Pose2& from_last, const Pose2& from_second_last);
  /// Fits the odometry noise to the accepted loop closures (calibrateOdometryNoise); false when
  /// nothing changed (no measured position, no accepted loop closure).
  bool calibrateOdometry();
  /// Restates every odometry covariance and every odometry, match and loop-closure edge with the
  /// current noise_ and match_noise_.
  void restate();
  /// The information of a match whose pairs give `pairs_information` (in the edge's from-frame),
  /// with the match noise measured so far.
  Eigen::Matrix3d matchInformation(const Eigen::Matrix3d& pairs_information) const;
  /// The odometry edge's information for scan k's motion with the current noise (a fifth of the
  /// scale error when the graph estimates the scale).
  Eigen::Matrix3d odometryEdgeInformation(std::size_t k) const;

  // Loop closures (loop_closing.cpp).
  /// Seeks a loop closure for scan k among the old scans near its estimate and offers it.
  void closeLoop(std::size_t k);
  /// Records a loop closure the matcher found (or one proposed from elsewhere) as a candidate and
  /// decides on it: refused beyond the vehicle's limits or the gate; accepted when it agrees with
  /// every accepted loop closure, or when it forms with others a larger agreeing set than the
  /// accepted one (which it then replaces). Returns whether it is accepted.
  bool addLoopClosure(std::size_t from, std::size_t to, const Pose2& measurement, const Eigen::Matrix3d& information,
                      const std::optional<Eigen::Matrix3d>& pairs_information);
  /// The dead reckoning's relative pose from scan a to scan b (b in a's frame), corrected by the
  /// heading deviation estimated so far (deviation_, to first order: OdometryChain's sensitivity).
  Pose2 deadReckoningBetween(std::size_t a, std::size_t b) const;
  /// Its covariance: the chain's plus what the deviation's uncertainty adds.
  Eigen::Matrix3d pathCovariance(std::size_t a, std::size_t b) const;
  /// Whether the matches show a heading deviation beyond the stated heading noise
  /// (HeadingDeviationEstimate::observed with OdometryNoise::heading_sigma_rad).
  bool deviationObserved() const;
  /// The heading deviation's coefficients and their covariance where the matches show one, zero
  /// where they do not.
  Eigen::Vector2d deviationCoefficients() const;
  Eigen::Matrix2d deviationCovariance() const;
  /// Whether the dead reckoning confirms a candidate: its χ² against the dead reckoning's relative
  /// pose with the covariance along the path plus the match's (SlamOptions::loop_gate_chi2).
  bool confirmedByDeadReckoning(const LoopCandidate& candidate) const;
  /// Whether two candidates agree: the cycle they close with the dead reckoning between their ends
  /// is the identity within its covariance (SlamOptions::consistency_chi2).
  bool consistent(const LoopCandidate& a, const LoopCandidate& b) const;
  /// Makes `clique` (gated candidates' indices into candidates_, sorted) the accepted set: their
  /// edges take their information, the others' none; the report says so. Returns whether it
  /// changed.
  bool acceptSet(const std::vector<std::size_t>& clique);
  /// Decides every candidate anew with the current calibration and estimate: the gate, the
  /// consistency graph and its largest clique (optimize).
  void redecideLoopClosures();

  SlamOptions options_;
  bool navigation_known_ = true;
  std::vector<SonarScan> scans_;
  PoseGraph graph_;
  std::vector<Pose2> odometry_;                ///< dead-reckoning motion from scan k−1 to k (k ≥ 1)
  std::vector<double> durations_s_;            ///< time from scan k−1 to k, s
  std::vector<Eigen::Matrix3d> odometry_cov_;  ///< its covariance with the current noise_
  /// Where no position is measured: scan k's match's pairs' information (scanOdometryCovariance).
  std::vector<std::optional<Eigen::Matrix3d>> scan_odometry_information_;
  OdometryChain chain_;                        ///< the same as a chain, for any path's covariance
  std::vector<double> travelled_m_;            ///< dead-reckoning path length at each scan
  OdometryNoise noise_;                        ///< the odometry noise: stated, then revised on the log
  MatchNoise match_noise_;                     ///< the matches' noise measured on the log
  /// The pairs' information of each scan-match edge of the graph (in its from-frame), by edge
  /// index (nullopt for other edges): its information is matchInformation of it.
  std::vector<std::optional<Eigen::Matrix3d>> edge_pairs_information_;
  /// The heading sensor's deviation measured on the matches to the scan before (with a measured
  /// position and a stated deviation; otherwise zero).
  HeadingDeviationEstimate deviation_;
  std::vector<MatchTriangle> triangles_;
  /// Scan k − 1 matched alone to scan k − 2 (a triangle's first side), when it measured.
  std::optional<ScanMatch> last_pair_;
  std::size_t calibrated_triangles_ = 0;  ///< triangles_.size() at the last calibration of the matches
  /// The odometry's covariance term by term along the chain (OdometryNoise::covarianceTerms): any
  /// path's covariance for any noise parameters, for calibrating them on the loop closures.
  std::array<OdometryChain, kOdometryNoiseTerms + 1> term_chains_;
  std::vector<LoopCandidate> candidates_;
  ConsistencyGraph consistency_;            ///< over candidates_ (vertex c: candidate c)
  std::vector<std::size_t> accepted_;       ///< the accepted candidates (indices into candidates_), sorted
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

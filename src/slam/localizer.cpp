/// @file localizer.cpp
/// Localizer and localize (localizer.hpp): odometry, submap matches and loop closures on the pose
/// graph; the corrected trajectory.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Eigenvalues>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/core/statistics.hpp"
#include "sonarmap/slam/localizer.hpp"
#include "loop_gates.hpp"

namespace sonarmap {

namespace {

/// Information (in `frame`'s coordinates) of a pose whose information is stated in NED: the
/// position error rotated into the frame, yaw unchanged.
Eigen::Matrix3d informationInFrame(const Eigen::Matrix3d& information_ned, const Pose2& frame) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Identity();
  a.topLeftCorner<2, 2>() = frame.rotation();
  return a.transpose() * information_ned * a;
}

/// Linear interpolation of two planar poses (the yaw along the shorter arc).
Pose2 interpolate(const Pose2& a, const Pose2& b, double f) {
  return {a.x_m + f * (b.x_m - a.x_m), a.y_m + f * (b.y_m - a.y_m),
          wrapAngle_rad(a.yaw_rad + f * wrapAngle_rad(b.yaw_rad - a.yaw_rad))};
}

}  // namespace

void SlamOptions::validate() const {
  forming.odometry.validate();
  matching.validate();
  if (submap_scans < 1) throw ValueError("slam: submap_scans must be ≥ 1");
  if (!(std::isfinite(loop_search_radius_m) && loop_search_radius_m >= 0.0)) {
    throw ValueError("slam: loop_search_radius_m must be ≥ 0 m");
  }
  if (!(std::isfinite(loop_min_travel_m) && loop_min_travel_m >= 0.0)) throw ValueError("slam: loop_min_travel_m must be ≥ 0 m");
  if (!(std::isfinite(loop_gate_chi2) && loop_gate_chi2 > 0.0)) throw ValueError("slam: loop_gate_chi2 must be > 0");
  if (!(std::isfinite(consistency_chi2) && consistency_chi2 > 0.0)) throw ValueError("slam: consistency_chi2 must be > 0");
}

std::size_t SlamReport::loopClosuresAccepted() const {
  return static_cast<std::size_t>(std::count_if(loop_closures.begin(), loop_closures.end(),
                                                [](const LoopClosure& loop) { return loop.accepted; }));
}

Localizer::Localizer(const SlamOptions& options, bool navigation_known)
    : options_(options), navigation_known_(navigation_known) {
  options_.validate();
  report_.heading_only = headingOnly();
  if (navigation_known_ && options_.forming.odometry.position_measured && options_.estimate_odometry_scale &&
      options_.forming.odometry.scale_sigma > 0.0) {
    graph_.estimateOdometryScale(options_.forming.odometry.scale_sigma);
  }
}

std::vector<ScanPoint> Localizer::placedPoints(std::size_t first, std::size_t last, const Pose2& ned_to_frame) const {
  std::vector<ScanPoint> points;
  for (std::size_t k = first; k < last; ++k) {
    const Pose2 pose = ned_to_frame * graph_.pose(k);
    const Eigen::Matrix2d rotation = pose.rotation();
    for (const ScanPoint& point : scans_[k].points) {
      ScanPoint placed = point;
      placed.xy_m = pose * point.xy_m;
      placed.covariance_m2 = rotation * point.covariance_m2 * rotation.transpose();
      placed.toward_sonar = rotation * point.toward_sonar;
      points.push_back(placed);
    }
  }
  return points;
}

void Localizer::addScan(SonarScan scan) {
  const std::size_t k = scans_.size();
  ++report_.scans;
  if (scan.points.size() >= options_.matching.min_pairs) ++report_.scans_with_points;
  if (k == 0) {
    graph_.addNode(scan.dead_reckoning);
    odometry_.push_back({});
    odometry_cov_.push_back(Eigen::Matrix3d::Zero());
    travelled_m_.push_back(0.0);
    scans_.push_back(std::move(scan));
    return;
  }
  const SonarScan& previous = scans_.back();
  const Pose2 motion = previous.dead_reckoning.between(scan.dead_reckoning);
  const double duration_s = scan.time_s - previous.time_s;
  const Eigen::Matrix3d covariance = options_.forming.odometry.covariance(motion, duration_s, navigation_known_);
  // The edge: the scale error is the graph's own parameter (estimateOdometryScale), so the edge
  // keeps only what varies from edge to edge (a fifth of it, and the noise).
  OdometryNoise varying = options_.forming.odometry;
  if (graph_.estimatesOdometryScale()) varying.scale_sigma /= 5.0;
  const Eigen::Matrix3d edge_covariance = varying.covariance(motion, duration_s, navigation_known_);
  const double scale = graph_.odometryScale();
  Pose2 predicted{scale * motion.x_m, scale * motion.y_m, motion.yaw_rad};
  if (headingOnly()) continueAtLastVelocity(k, duration_s, predicted, scan);
  graph_.addNode(graph_.pose(k - 1) * predicted);
  graph_.addEdge({k - 1, k, motion, edge_covariance.inverse(), EdgeKind::kOdometry});
  odometry_.push_back(motion);
  odometry_cov_.push_back(covariance);
  travelled_m_.push_back(travelled_m_.back() + motion.translation().norm());
  scans_.push_back(std::move(scan));
  matchToSubmap(k);
  closeLoop(k);
}

void Localizer::continueAtLastVelocity(std::size_t k, double duration_s, Pose2& predicted, SonarScan& scan) const {
  if (k < 2) return;
  const double last_s = scans_[k - 1].time_s - scans_[k - 2].time_s;
  if (!(last_s > 0.0)) return;
  // The velocity over the ground (NED): measured, it predicts the missions' turns better than the
  // velocity in the body frame (docs/localization.md).
  const Pose2& last = graph_.pose(k - 1);
  const Eigen::Vector2d velocity_ned_mps = (last.translation() - graph_.pose(k - 2).translation()) / last_s;
  const Eigen::Vector2d step_m = last.rotation().transpose() * velocity_ned_mps * duration_s;
  predicted.x_m = step_m.x();
  predicted.y_m = step_m.y();
  const Eigen::Vector2d velocity_mps = (last * predicted).rotation().transpose() * velocity_ned_mps;  // scan k's frame
  for (ScanPoint& point : scan.points) point.xy_m += velocity_mps * point.time_offset_s;
}

void Localizer::matchToSubmap(std::size_t k) {
  const std::size_t first = k > options_.submap_scans ? k - options_.submap_scans : 0;
  const std::vector<ScanPoint> target = placedPoints(first, k);
  const Pose2 predicted = graph_.pose(k);
  Eigen::Matrix3d rotate = Eigen::Matrix3d::Identity();  // the odometry's covariance rotated into NED
  rotate.topLeftCorner<2, 2>() = graph_.pose(k - 1).rotation();
  const Eigen::Matrix3d prior_ned = rotate * odometry_cov_[k] * rotate.transpose();
  const ScanMatch match = matchScans(target, scans_[k].points, predicted, prior_ned, headingOnly(), options_.matching);
  if (!match.accepted) {
    // A match along one wall still fixes the offset across it and the heading: keep that part.
    const bool along_wall = match.reason.rfind("ambiguous: constrained", 0) == 0;
    if (!along_wall || match.pairs < options_.matching.min_pairs) {
      ++report_.matches_refused;
      return;
    }
  }
  if (beyondLimits(k - 1, k, graph_.pose(k - 1).between(match.pose))) {
    ++report_.matches_refused;
    ++report_.matches_beyond_limits;
    return;
  }
  ++report_.matches_accepted;
  graph_.setPose(k, match.pose);
  const Pose2& anchor = graph_.pose(k - 1);
  graph_.addEdge({k - 1, k, anchor.between(match.pose), informationInFrame(match.information, anchor), EdgeKind::kScanMatch});
}

bool Localizer::beyondLimits(std::size_t from, std::size_t to, const Pose2& motion) const {
  const OdometryNoise& limits = options_.forming.odometry;
  if (navigation_known_ && limits.position_measured) return false;
  const double duration_s = std::abs(scans_[to].time_s - scans_[from].time_s);
  if (motion.translation().norm() > limits.max_speed_mps * duration_s) return true;
  // With a heading measured, the turn is the heading sensor's, however fast.
  return !navigation_known_ && std::abs(motion.yaw_rad) > limits.max_turn_rate_radps * duration_s;
}

void Localizer::closeLoop(std::size_t k) {
  std::vector<double> reaches;
  for (const SonarScan& scan : scans_) reaches.push_back(scan.reach_m);
  const double reach_m = percentile(reaches, 0.5);
  const double radius_m = options_.loop_search_radius_m > 0.0 ? options_.loop_search_radius_m : reach_m / 2.0;
  const double min_travel_m = options_.loop_min_travel_m > 0.0 ? options_.loop_min_travel_m : 2.0 * reach_m;
  // With the heading alone, the track's position comes from the sequential matches, whose drift
  // along the path the gates below (dead reckoning's drift model) do not describe: measured, 64 of
  // the 76 accepted on three seeds of the simulated missions were wrong (docs/localization.md).
  if (scans_[k].points.size() < options_.matching.min_pairs || headingOnly()) return;
  // The nearest earlier scan that the vehicle left long enough ago, sought no farther than where
  // its true neighbour can be (SlamOptions::loop_search_radius_m): half the old scans' spacing
  // plus 3σ of dead reckoning's drift along the path since. Two views farther apart than that see
  // small targets from different sides (a pile's echo comes from the side facing the sonar, so
  // the two disagree by up to its radius); a later scan passes nearer.
  const std::vector<Eigen::Matrix3d> drift = pathCovariancesTo(k);
  std::size_t best = k;
  double best_distance_m = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j + options_.submap_scans < k; ++j) {
    // The vehicle left j long ago, or never left its neighbourhood (a hovering or static vehicle
    // revisits the same place all the time: its drift is bounded by matching the first scans).
    const double travelled_m = travelled_m_[k] - travelled_m_[j];
    if (travelled_m < min_travel_m && travelled_m > radius_m) continue;
    if (scans_[j].points.size() < options_.matching.min_pairs) continue;
    const double distance_m = (graph_.pose(j).translation() - graph_.pose(k).translation()).norm();
    const std::size_t before = j > 0 ? j - 1 : j;  // the scans around j (j + 1 < k here)
    const double spacing_m = (travelled_m_[j + 1] - travelled_m_[before]) / static_cast<double>(j + 1 - before);
    const double drift_sigma_m = std::sqrt(drift[j].topLeftCorner<2, 2>().eigenvalues().real().maxCoeff());
    const double reachable_m = options_.loop_search_radius_m > 0.0 ? radius_m : std::min(radius_m, spacing_m / 2.0 + 3.0 * drift_sigma_m);
    if (distance_m <= reachable_m && distance_m < best_distance_m) {
      best = j;
      best_distance_m = distance_m;
    }
  }
  if (best == k) return;
  const std::size_t j = best;
  const std::size_t first = j > 0 ? j - 1 : 0;
  const std::size_t last = std::min(j + 2, k - options_.submap_scans);
  const std::vector<ScanPoint> target = placedPoints(first, last);
  // The prior: dead reckoning's drift along the path from j to k, in NED.
  const Eigen::Matrix3d path = pathCovariance(j, k);
  Eigen::Matrix3d rotate = Eigen::Matrix3d::Identity();
  rotate.topLeftCorner<2, 2>() = graph_.pose(j).rotation();
  const Eigen::Matrix3d prior_ned = rotate * path * rotate.transpose();
  // The source: the new scan with the scans just before it, in its frame (more of the place, so a
  // match along one wall or one row of piles is told from a true fix more often).
  const std::size_t source_first = k + 1 > options_.submap_scans ? k + 1 - options_.submap_scans : 0;
  const std::vector<ScanPoint> source = placedPoints(std::max(source_first, last), k + 1, graph_.pose(k).inverse());
  const ScanMatch match = matchScans(target, source, graph_.pose(k), prior_ned, true, options_.matching);
  LoopClosure loop;
  loop.from = j;
  loop.to = k;
  loop.measurement = graph_.pose(j).between(match.pose);
  loop.pairs = match.pairs;
  loop.peak_ratio = match.peak_ratio;
  if (!match.accepted) {
    loop.reason = match.reason;
    report_.loop_closures.push_back(loop);
    return;
  }
  proposeLoopClosure(j, k, loop.measurement, informationInFrame(match.information, graph_.pose(j)));
  report_.loop_closures.back().pairs = match.pairs;  // proposeLoopClosure recorded it, accepted or not
  report_.loop_closures.back().peak_ratio = match.peak_ratio;
}

bool Localizer::proposeLoopClosure(std::size_t from, std::size_t to, const Pose2& measurement,
                                   const Eigen::Matrix3d& information) {
  if (from >= to || to >= scans_.size()) throw ValueError("slam: a loop closure joins an older scan to a newer one");
  if (!information.allFinite() || !measurement.vector().allFinite()) throw ValueError("slam: a loop closure must be finite");
  LoopClosure loop;
  loop.from = from;
  loop.to = to;
  loop.measurement = measurement;
  const Eigen::Matrix3d match_cov = (information + 1e-9 * Eigen::Matrix3d::Identity()).inverse();
  const Eigen::Matrix3d path = pathCovariance(from, to);
  const Pose2 estimated = graph_.pose(from).between(graph_.pose(to));
  if (beyondLimits(from, to, measurement)) {
    loop.reason = "faster than the vehicle's limits (its top speed or turn rate)";
  } else if (loopChi2(measurement, estimated, path + match_cov) > options_.loop_gate_chi2) {
    loop.reason = "farther from the estimate than dead reckoning can have drifted";
  } else if (!consistentWithAccepted(loop, match_cov)) {
    loop.reason = "inconsistent with an earlier loop closure";
  } else {
    loop.accepted = true;
    accepted_loops_.push_back(report_.loop_closures.size());
    loop_cov_.push_back(match_cov);
    graph_.addEdge({from, to, measurement, information, EdgeKind::kLoopClosure});
    graph_.optimize(options_.graph);
  }
  report_.loop_closures.push_back(loop);
  return loop.accepted;
}

void Localizer::optimize() {
  PoseGraphOptions final_options = options_.graph;
  final_options.scale_covariance = graph_.estimatesOdometryScale();
  graph_.optimize(final_options);
  report_.odometry_scale_observed = false;
  report_.odometry_scale_sigma = graph_.odometryScaleSigma();
  if (graph_.estimatesOdometryScale()) {
    // The scans constrain the scale when they carry at least the prior's information on it: the
    // marginal variance is then at most half the prior's. Otherwise the estimate is the prior's
    // pull and the matches' bias (a wall seen along the track has none to give), so the scale is
    // the navigation's own, its error back in each odometry edge.
    const double prior_sigma = options_.forming.odometry.scale_sigma;
    report_.odometry_scale_observed =
        report_.odometry_scale_sigma > 0.0 && report_.odometry_scale_sigma <= prior_sigma / std::sqrt(2.0);
    if (!report_.odometry_scale_observed) {
      graph_.fixOdometryScale();
      const std::vector<PoseGraphEdge>& edges = graph_.edges();
      for (std::size_t e = 0; e < edges.size(); ++e) {
        if (edges[e].kind == EdgeKind::kOdometry) graph_.setInformation(e, odometry_cov_[edges[e].to].inverse());
      }
      graph_.optimize(options_.graph);
    }
  }
  report_.odometry_scale = graph_.odometryScale();
}

NavTrack Localizer::correctedTrack(const NavTrack& dead_reckoning) const {
  NavTrack track;
  if (scans_.empty()) return track;
  if (dead_reckoning.empty()) {
    for (std::size_t k = 0; k < scans_.size(); ++k) {
      const Pose2& pose = graph_.pose(k);
      for (const double time_s : {scans_[k].start_time_s, scans_[k].time_s, scans_[k].end_time_s}) {
        if (!track.empty() && !(time_s > track.back().time_s)) continue;
        NavSample fix;
        fix.time_s = time_s;
        fix.position_ned_m = Eigen::Vector3d(pose.x_m, pose.y_m, 0.0);
        fix.yaw_rad = pose.yaw_rad;
        track.push_back(fix);
      }
    }
    return track;
  }
  // Correction of each scan: optimised ∘ dead reckoning⁻¹ (maps dead-reckoned NED to corrected NED).
  std::vector<Pose2> corrections(scans_.size());
  for (std::size_t k = 0; k < scans_.size(); ++k) corrections[k] = graph_.pose(k) * scans_[k].dead_reckoning.inverse();
  std::size_t next = 0;  // the first scan after the fix
  for (const NavSample& fix : dead_reckoning) {
    while (next < scans_.size() && scans_[next].time_s <= fix.time_s) ++next;
    Pose2 correction;
    if (next == 0) {
      correction = corrections.front();
    } else if (next == scans_.size()) {
      correction = corrections.back();
    } else {
      const double t0 = scans_[next - 1].time_s, t1 = scans_[next].time_s;
      correction = interpolate(corrections[next - 1], corrections[next], (fix.time_s - t0) / (t1 - t0));
    }
    const Pose2 corrected = correction * Pose2{fix.position_ned_m.x(), fix.position_ned_m.y(), fix.yaw_rad};
    NavSample out = fix;
    out.position_ned_m.x() = corrected.x_m;
    out.position_ned_m.y() = corrected.y_m;
    out.yaw_rad = fix.yaw_rad + wrapAngle_rad(corrected.yaw_rad - fix.yaw_rad);  // no wrap of the track's own yaw
    track.push_back(out);
  }
  return track;
}

SlamResult localize(const SonarLog& log, const NavTrack& dead_reckoning, const Eigen::Isometry3d& sonar_to_body,
                    const MapperOptions& options, const SlamOptions& slam) {
  slam.validate();
  return localize(detectSonarLog(log, options), dead_reckoning, sonar_to_body, slam);
}

SlamOptions withNavigationPeriod(SlamOptions slam, const NavTrack& dead_reckoning) {
  if (dead_reckoning.size() >= 2) {
    std::vector<double> periods;
    for (std::size_t i = 1; i < dead_reckoning.size(); ++i) periods.push_back(dead_reckoning[i].time_s - dead_reckoning[i - 1].time_s);
    slam.forming.odometry.nav_period_s = std::max(percentile(periods, 0.5), 1e-3);
  }
  return slam;
}

SlamResult localize(const DetectedLog& detected, const NavTrack& dead_reckoning, const Eigen::Isometry3d& sonar_to_body,
                    const SlamOptions& slam) {
  slam.validate();
  const SlamOptions tuned = withNavigationPeriod(slam, dead_reckoning);
  return localizeScans(formScans(detected, dead_reckoning, sonar_to_body, tuned.forming), dead_reckoning, tuned);
}

SlamResult localizeScans(std::vector<SonarScan> scans, const NavTrack& dead_reckoning, const SlamOptions& slam) {
  Localizer localizer(slam, !dead_reckoning.empty());
  for (SonarScan& scan : scans) localizer.addScan(std::move(scan));
  localizer.optimize();
  SlamResult result;
  result.trajectory = localizer.correctedTrack(dead_reckoning);
  result.scan_poses = localizer.graph().poses();
  for (const SonarScan& scan : localizer.scans()) result.scan_times_s.push_back(scan.time_s);
  result.report = localizer.report();
  return result;
}

}  // namespace sonarmap

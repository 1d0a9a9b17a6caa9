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

namespace sonarmap {

namespace {

/// The likelihood of a point that fits no target point: the floor of the mixture that compares two
/// poses of a match (stillUnlessShown), a tenth of a point that fits exactly.
constexpr double kOutlierLikelihood = 0.1;

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
    : options_(options),
      navigation_known_(navigation_known),
      noise_(options.forming.odometry),
      deviation_(navigation_known ? options.forming.odometry.deviation_sigma_rad
                                                                               : 0.0) {
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

ScanMatch Localizer::matchAgainst(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source, std::size_t first,
                                  std::size_t last, const Pose2& initial, const Eigen::Matrix3d& prior_ned, bool search) const {
  if (!headingOnly()) return matchScans(target, source, initial, prior_ned, search, options_.matching, SearchField::kSamples);
  // With the heading alone the search places every match (here and in the loop closures): its
  // walls drawn between their samples (SearchField::kSurfaces: each turn samples a straight wall at
  // the same offsets from the vehicle), the points the target scans did not hear left out, and the
  // information no more than its score surface shows (two parallel walls: none along them).
  std::vector<CoverageDisc> heard;
  for (std::size_t k = first; k < last; ++k) heard.push_back({graph_.pose(k).translation(), scans_[k].reach_m});
  return matchScans(target, source, initial, prior_ned, true, options_.matching, SearchField::kSurfaces, heard, true);
}

void Localizer::addScan(SonarScan scan) {
  const std::size_t k = scans_.size();
  ++report_.scans;
  if (scan.points.size() >= options_.matching.min_pairs) ++report_.scans_with_points;
  if (k == 0) {
    chain_ = OdometryChain(scan.dead_reckoning.yaw_rad);
    for (OdometryChain& chain : term_chains_) chain = OdometryChain(scan.dead_reckoning.yaw_rad);
    graph_.addNode(scan.dead_reckoning);
    odometry_.push_back({});
    durations_s_.push_back(0.0);
    odometry_cov_.push_back(Eigen::Matrix3d::Zero());
    travelled_m_.push_back(0.0);
    scan_odometry_information_.push_back(std::nullopt);
    scans_.push_back(std::move(scan));
    return;
  }
  const SonarScan& previous = scans_.back();
  const Pose2 motion = previous.dead_reckoning.between(scan.dead_reckoning);
  const double duration_s = scan.time_s - previous.time_s;
  odometry_.push_back(motion);
  durations_s_.push_back(duration_s);
  odometry_cov_.push_back(noise_.covariance(motion, duration_s, navigation_known_));
  if (positionMeasured()) {
    chain_.append(motion, odometry_cov_.back());
    const std::array<Eigen::Matrix3d, kOdometryNoiseTerms + 1> terms = noise_.covarianceTerms(motion, duration_s);
    for (std::size_t p = 0; p < terms.size(); ++p) term_chains_[p].append(motion, terms[p]);
    travelled_m_.push_back(travelled_m_.back() + motion.translation().norm());
  }
  Pose2 predicted = predictedMotion(motion, previous.dead_reckoning.yaw_rad, scan.dead_reckoning.yaw_rad);
  if (headingOnly()) continueAtLastVelocity(k, duration_s, predicted, scan);
  graph_.addNode(graph_.pose(k - 1) * predicted);
  // With the heading only, the motion model is the odometry: the last velocity held, the turn the
  // heading sensor's (a vehicle's speed does not jump); without navigation, a still vehicle.
  graph_.addEdge({k - 1, k, headingOnly() ? predicted : motion, odometryEdgeInformation(k), EdgeKind::kOdometry,
                  previous.dead_reckoning.yaw_rad, scan.dead_reckoning.yaw_rad});
  edge_pairs_information_.push_back(std::nullopt);
  scans_.push_back(std::move(scan));
  if (positionMeasured()) measureMatches(k, odometry_[k], odometry_[k - 1] * odometry_[k]);
  // The prediction again with the deviation measured on this scan too.
  if (!headingOnly()) graph_.setPose(k, graph_.pose(k - 1) * predictedMotion(motion, scans_[k - 1].dead_reckoning.yaw_rad,
                                                                             scans_[k].dead_reckoning.yaw_rad));
  const std::optional<Eigen::Matrix3d> matched = matchToSubmap(k);
  if (!positionMeasured()) {
    // The scans' own estimate of the motion starts the pairwise matches and is the chain's step.
    const Pose2 step = graph_.pose(k - 1).between(graph_.pose(k));
    measureMatches(k, step, graph_.pose(k >= 2 ? k - 2 : 0).between(graph_.pose(k)));
    scan_odometry_information_.push_back(matched);
    chain_.append(step, scanOdometryCovariance(k));
    travelled_m_.push_back(travelled_m_.back() + step.translation().norm());
  }
  closeLoop(k);
}

Eigen::Matrix3d Localizer::scanOdometryCovariance(std::size_t k) const {
  // How well the scans fixed the step: the match's information joined with the motion model's (a
  // match along a wall measures only across it; along it the motion model decides, with its
  // uncertainty), or the motion model's alone where no match held.
  const std::optional<Eigen::Matrix3d>& pairs = scan_odometry_information_[k];
  if (!pairs) return odometry_cov_[k];
  return (matchInformation(*pairs) + odometry_cov_[k].inverse()).inverse();
}

Pose2 Localizer::predictedMotion(const Pose2& motion, double from_heading_rad, double to_heading_rad) const {
  const double scale = graph_.odometryScale();
  const Eigen::Vector2d g(std::cos(to_heading_rad) - std::cos(from_heading_rad), std::sin(to_heading_rad) - std::sin(from_heading_rad));
  return {scale * motion.x_m, scale * motion.y_m, wrapAngle_rad(motion.yaw_rad + g.dot(deviationCoefficients()))};
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

std::optional<Eigen::Matrix3d> Localizer::matchToSubmap(std::size_t k) {
  const std::size_t first = k > options_.submap_scans ? k - options_.submap_scans : 0;
  const std::vector<ScanPoint> target = placedPoints(first, k);
  const Pose2 predicted = graph_.pose(k);
  Eigen::Matrix3d rotate = Eigen::Matrix3d::Identity();  // the odometry's covariance rotated into NED
  rotate.topLeftCorner<2, 2>() = graph_.pose(k - 1).rotation();
  Eigen::Matrix3d prior = odometry_cov_[k];  // the odometry's, and its turn's uncertainty from the deviation
  const double from_rad = scans_[k - 1].dead_reckoning.yaw_rad, to_rad = scans_[k].dead_reckoning.yaw_rad;
  const Eigen::Vector2d g(std::cos(to_rad) - std::cos(from_rad), std::sin(to_rad) - std::sin(from_rad));
  prior(2, 2) += g.dot(deviationCovariance() * g);
  const Eigen::Matrix3d prior_ned = rotate * prior * rotate.transpose();
  const ScanMatch match = matchAgainst(target, scans_[k].points, first, k, predicted, prior_ned, headingOnly());
  ScanMatch kept = match;
  if (!match.accepted) {
    // A match along one wall still fixes the offset across it and the heading: keep that part.
    const bool along_wall = match.reason.rfind("ambiguous: constrained", 0) == 0;
    if (!along_wall || match.pairs < options_.matching.min_pairs) {
      ++report_.matches_refused;
      return std::nullopt;
    }
    kept = acrossWallOnly(match, predicted);
  }
  if (beyondLimits(k - 1, k, graph_.pose(k - 1).between(kept.pose))) {
    ++report_.matches_refused;
    ++report_.matches_beyond_limits;
    return std::nullopt;
  }
  const Pose2 measured = stillUnlessShown(target, scans_[k].points, predicted, kept.pose);
  ++report_.matches_accepted;
  graph_.setPose(k, measured);
  const Pose2& anchor = graph_.pose(k - 1);
  const Eigen::Matrix3d pairs_information = informationInFrame(kept.information, anchor);
  graph_.addEdge({k - 1, k, anchor.between(measured), matchInformation(pairs_information), EdgeKind::kScanMatch});
  edge_pairs_information_.push_back(pairs_information);
  return pairs_information;
}

ScanMatch Localizer::acrossWallOnly(const ScanMatch& match, const Pose2& predicted) {
  // The translation's weak direction (along the wall) carries no measurement: the match's
  // position along it is where the search and the pairs happened to stop (a wall's samples repeat
  // at no motion), so it is the prediction's there, and its information there none.
  ScanMatch across = match;
  const Eigen::Vector2d along = match.along_m;
  const Eigen::Vector2d offset(match.pose.x_m - predicted.x_m, match.pose.y_m - predicted.y_m);
  const Eigen::Vector2d kept = offset - along.dot(offset) * along;
  across.pose.x_m = predicted.x_m + kept.x();
  across.pose.y_m = predicted.y_m + kept.y();
  Eigen::Matrix3d project = Eigen::Matrix3d::Identity();
  project.topLeftCorner<2, 2>() -= along * along.transpose();
  across.information = project * match.information * project;
  return across;
}

Pose2 Localizer::stillUnlessShown(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source, const Pose2& expected,
                                  const Pose2& matched) const {
  if (navigation_known_) return matched;
  // The log-likelihood ratio of the two poses, each point's likelihood a Gaussian's with a floor
  // for the points that fit neither (a target seen from elsewhere, clutter: a mixture with an
  // outlier share): 2 Λ against χ²₃'s 99 % quantile, the test of one pose's three parameters.
  const std::vector<std::vector<double>> likelihoods = pointLikelihoods(target, source, {expected, matched});
  double log_ratio = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    log_ratio += std::log((kOutlierLikelihood + likelihoods[1][i]) / (kOutlierLikelihood + likelihoods[0][i]));
  }
  return 2.0 * log_ratio > options_.loop_gate_chi2 ? matched : expected;
}

bool Localizer::beyondLimits(std::size_t from, std::size_t to, const Pose2& motion) const {
  const OdometryNoise& limits = options_.forming.odometry;
  if (navigation_known_ && limits.position_measured) return false;
  const double duration_s = std::abs(scans_[to].time_s - scans_[from].time_s);
  if (motion.translation().norm() > limits.max_speed_mps * duration_s) return true;
  // With a heading measured, the turn is the heading sensor's, however fast.
  return !navigation_known_ && std::abs(motion.yaw_rad) > limits.max_turn_rate_radps * duration_s;
}

void Localizer::optimize() {
  redecideLoopClosures();
  // The odometry's noise measured on the loop closures decides them again.
  if (options_.calibrate_navigation && calibrateOdometry()) redecideLoopClosures();
  report_.odometry_noise = noise_;
  report_.match_noise = match_noise_;
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
        if (edges[e].kind == EdgeKind::kOdometry) graph_.setInformation(e, odometryEdgeInformation(edges[e].to));
      }
      graph_.optimize(options_.graph);
    }
  }
  report_.odometry_scale = graph_.odometryScale();
  report_.heading_deviation_observed = graph_.estimatesHeadingDeviation();
  report_.heading_deviation_rad = graph_.headingDeviation();
}

NavTrack Localizer::correctedTrack(const NavTrack& dead_reckoning) const {
  NavTrack track;
  if (scans_.empty()) return track;
  if (dead_reckoning.empty()) {
    // The scans' poses at their reference times, the motion between two of them spread evenly over
    // the time between (constant velocity and turn rate, the yaw along the shorter arc): a row's
    // step never implies more speed or turn rate than the two scans' poses do in their time.
    // Held before the first scan's reference time and after the last's.
    const auto poseAt = [this](std::size_t next, double time_s) {
      if (next == 0) return graph_.pose(0);
      if (next == scans_.size()) return graph_.pose(next - 1);
      const double t0 = scans_[next - 1].time_s, t1 = scans_[next].time_s;
      return interpolate(graph_.pose(next - 1), graph_.pose(next), t1 > t0 ? (time_s - t0) / (t1 - t0) : 1.0);
    };
    std::size_t next = 0;  // the first scan whose reference time is after the row's
    for (std::size_t k = 0; k < scans_.size(); ++k) {
      for (const double time_s : {scans_[k].start_time_s, scans_[k].time_s, scans_[k].end_time_s}) {
        if (!track.empty() && !(time_s > track.back().time_s)) continue;
        while (next < scans_.size() && scans_[next].time_s <= time_s) ++next;
        const Pose2 pose = poseAt(next, time_s);
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

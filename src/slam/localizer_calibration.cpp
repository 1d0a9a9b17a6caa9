/// @file localizer_calibration.cpp
/// The navigation measured on the log by the Localizer (localizer.hpp): the pairwise matches that
/// give the evidence, and the recalibration that restates every edge with it
/// (navigation_calibration.hpp).

#include <cmath>
#include <vector>

#include "sonarmap/slam/localizer.hpp"

namespace sonarmap {

Eigen::Matrix3d Localizer::odometryEdgeInformation(std::size_t k) const {
  // The scale error is the graph's own parameter when it estimates it (estimateOdometryScale), so
  // the edge keeps only what varies from edge to edge (a fifth of it, and the noise).
  OdometryNoise varying = noise_;
  if (graph_.estimatesOdometryScale()) varying.scale_sigma /= 5.0;
  return varying.covariance(odometry_[k], durations_s_[k], navigation_known_).inverse();
}

Eigen::Matrix3d Localizer::matchInformation(const Eigen::Matrix3d& pairs_information) const {
  return match_noise_.information(pairs_information);
}

namespace {

/// Whether a match gives evidence: accepted, or refused only as constrained along one direction
/// (a wall: its information says which direction it measures).
bool measures(const ScanMatch& match, const ScanMatchOptions& options) {
  const bool along_wall = match.reason.rfind("ambiguous: constrained", 0) == 0;
  return (match.accepted || along_wall) && match.pairs >= options.min_pairs && match.information.allFinite();
}

}  // namespace

void Localizer::measureMatches(std::size_t k, const Pose2& from_last, const Pose2& from_second_last) {
  const ScanMatch pair = matchScansFrom(scans_[k - 1].points, scans_[k].points, from_last, options_.matching);
  const bool paired = measures(pair, options_.matching);
  if (paired && navigation_known_) {
    // The match's turn against the navigation's: evidence on the heading sensor's deviation.
    const Eigen::Matrix3d information = matchInformation(pair.information);
    const double match_variance = (information + 1e-9 * information.trace() * Eigen::Matrix3d::Identity()).inverse()(2, 2);
    deviation_.add(scans_[k - 1].dead_reckoning.yaw_rad, scans_[k].dead_reckoning.yaw_rad,
                   wrapAngle_rad(pair.pose.yaw_rad - odometry_[k].yaw_rad), match_variance + odometry_cov_[k](2, 2));
    // While the matches show a deviation, the graph estimates it with every edge.
    if (deviationObserved() != graph_.estimatesHeadingDeviation()) {
      if (deviationObserved()) {
        graph_.estimateHeadingDeviation(noise_.deviation_sigma_rad);
      } else {
        graph_.fixHeadingDeviation();
      }
    }
  }
  // Triangles of accepted matches only: along a wall a match slides freely where its information
  // is merely weak, which would read as scatter.
  if (k >= 2 && pair.accepted && last_pair_) {
    const ScanMatch skip = matchScansFrom(scans_[k - 2].points, scans_[k].points, from_second_last, options_.matching);
    if (skip.accepted) {
      triangles_.push_back({last_pair_->pose, pair.pose, skip.pose, last_pair_->information, pair.information, skip.information});
    }
  }
  last_pair_.reset();
  if (pair.accepted) last_pair_ = pair;
  // Recalibrate as the triangles grow by a fifth: often while they are few, rarely once they are not.
  if (options_.calibrate_navigation && triangles_.size() >= kMinMatchTriangles && 5 * triangles_.size() >= 6 * calibrated_triangles_ + 5) {
    calibrated_triangles_ = triangles_.size();
    match_noise_ = calibrateMatchNoise(triangles_);
    restate();
  }
}

bool Localizer::calibrateOdometry() {
  if (!navigation_known_ || !options_.forming.odometry.position_measured || accepted_.empty()) return false;
  std::vector<LoopEvidence> loops;
  for (const std::size_t c : accepted_) {
    const LoopClosure& loop = report_.loop_closures[candidates_[c].report];
    LoopEvidence evidence;
    evidence.dead_reckoning = deadReckoningBetween(loop.from, loop.to);
    for (std::size_t p = 0; p < term_chains_.size(); ++p) evidence.path_terms[p] = term_chains_[p].covariance(loop.from, loop.to);
    // The deviation's remaining uncertainty joins the fixed floor term.
    const Eigen::Matrix<double, 3, 2> g = chain_.deviationSensitivity(loop.from, loop.to);
    evidence.path_terms[kOdometryNoiseTerms] += g * deviationCovariance() * g.transpose();
    evidence.measured = loop.measurement;
    evidence.measured_information = candidates_[c].information;
    loops.push_back(evidence);
  }
  noise_ = calibrateOdometryNoise(loops, options_.forming.odometry);
  restate();
  return true;
}

void Localizer::restate() {
  for (std::size_t k = 1; k < odometry_.size(); ++k) odometry_cov_[k] = noise_.covariance(odometry_[k], durations_s_[k], navigation_known_);
  if (positionMeasured()) {
    chain_.restate(odometry_cov_);
  } else {
    std::vector<Eigen::Matrix3d> steps(scans_.size(), Eigen::Matrix3d::Zero());
    for (std::size_t k = 1; k < chain_.size(); ++k) steps[k] = scanOdometryCovariance(k);
    steps.resize(chain_.size());
    chain_.restate(steps);
  }
  const std::vector<PoseGraphEdge>& edges = graph_.edges();
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (edges[e].kind == EdgeKind::kOdometry) graph_.setInformation(e, odometryEdgeInformation(edges[e].to));
    if (edges[e].kind == EdgeKind::kScanMatch && edge_pairs_information_[e]) {
      graph_.setInformation(e, matchInformation(*edge_pairs_information_[e]));
    }
  }
  for (LoopCandidate& candidate : candidates_) {
    if (candidate.pairs_information) candidate.information = matchInformation(*candidate.pairs_information);
  }
  for (const std::size_t c : accepted_) graph_.setInformation(candidates_[c].edge, candidates_[c].information);
}

}  // namespace sonarmap

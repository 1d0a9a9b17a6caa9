/// @file loop_closing.cpp
/// Loop closures of the Localizer (localizer.hpp): sought near the estimate among the old scans,
/// gated against the estimate with the dead reckoning's drift, and kept as the largest set that
/// agrees pairwise (consistency_graph.hpp; Mangelson et al. 2018).

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

/// Squared Mahalanobis distance of a relative pose from the identity, 3 degrees of freedom.
double chi2(const Pose2& error, const Eigen::Matrix3d& covariance) {
  const Eigen::Vector3d e(error.x_m, error.y_m, wrapAngle_rad(error.yaw_rad));
  return e.dot(covariance.ldlt().solve(e));
}

Eigen::Matrix3d covarianceOf(const Eigen::Matrix3d& information) {
  return (information + 1e-9 * Eigen::Matrix3d::Identity()).inverse();
}

constexpr const char* kInconsistent = "inconsistent with the accepted loop closures";
constexpr const char* kUnconfirmed = "not confirmed: no other loop closure agrees with it";
constexpr const char* kOutvoted = "inconsistent with a larger set of loop closures that agree";

}  // namespace

void Localizer::closeLoop(std::size_t k) {
  std::vector<double> reaches;
  for (const SonarScan& scan : scans_) reaches.push_back(scan.reach_m);
  const double reach_m = percentile(reaches, 0.5);
  const double radius_m = options_.loop_search_radius_m > 0.0 ? options_.loop_search_radius_m : reach_m / 2.0;
  const double min_travel_m = options_.loop_min_travel_m > 0.0 ? options_.loop_min_travel_m : 2.0 * reach_m;
  if (scans_[k].points.size() < options_.matching.min_pairs) return;
  // The nearest earlier scan that the vehicle left long enough ago, sought no farther than where
  // its true neighbour can be (SlamOptions::loop_search_radius_m): half the old scans' spacing
  // plus 3σ of dead reckoning's drift along the path since (the scans' own chain where no position
  // is measured). Two views farther apart than that see
  // small targets from different sides (a pile's echo comes from the side facing the sonar, so
  // the two disagree by up to its radius); a later scan passes nearer.
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
    const double drift_sigma_m = std::sqrt(pathCovariance(j, k).topLeftCorner<2, 2>().eigenvalues().real().maxCoeff());
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
  const ScanMatch match = matchAgainst(target, source, first, last, graph_.pose(k), prior_ned, true);
  LoopClosure loop;
  loop.from = j;
  loop.to = k;
  loop.measurement = graph_.pose(j).between(stillUnlessShown(target, source, graph_.pose(k), match.pose));
  loop.pairs = match.pairs;
  loop.peak_ratio = match.peak_ratio;
  if (!match.accepted) {
    loop.reason = match.reason;
    report_.loop_closures.push_back(loop);
    return;
  }
  const Eigen::Matrix3d pairs_information = informationInFrame(match.information, graph_.pose(j));
  addLoopClosure(j, k, loop.measurement, matchInformation(pairs_information), pairs_information);
  report_.loop_closures.back().pairs = match.pairs;  // proposeLoopClosure recorded it, accepted or not
  report_.loop_closures.back().peak_ratio = match.peak_ratio;
}

bool Localizer::proposeLoopClosure(std::size_t from, std::size_t to, const Pose2& measurement,
                                   const Eigen::Matrix3d& information) {
  if (from >= to || to >= scans_.size()) throw ValueError("slam: a loop closure joins an older scan to a newer one");
  if (!information.allFinite() || !measurement.vector().allFinite()) throw ValueError("slam: a loop closure must be finite");
  return addLoopClosure(from, to, measurement, information, std::nullopt);
}

Pose2 Localizer::deadReckoningBetween(std::size_t a, std::size_t b) const {
  // Every step's translation times the odometry scale scales the path's translation alike.
  const Pose2 path = chain_.between(a, b);
  const double scale = graph_.odometryScale();
  const Eigen::Vector3d correction = chain_.deviationSensitivity(a, b) * deviationCoefficients();
  return {scale * path.x_m + correction.x(), scale * path.y_m + correction.y(), wrapAngle_rad(path.yaw_rad + correction.z())};
}

Eigen::Matrix3d Localizer::pathCovariance(std::size_t a, std::size_t b) const {
  const Eigen::Matrix<double, 3, 2> g = chain_.deviationSensitivity(a, b);
  return chain_.covariance(a, b) + g * deviationCovariance() * g.transpose();
}

bool Localizer::deviationObserved() const { return deviation_.observed(options_.forming.odometry.heading_sigma_rad); }

Eigen::Vector2d Localizer::deviationCoefficients() const {
  return deviationObserved() ? deviation_.coefficients() : Eigen::Vector2d::Zero();
}

Eigen::Matrix2d Localizer::deviationCovariance() const {
  // With the heading only, the compass's turns are the track's (the matches are solved about
  // them): its deviation, shown or not, bends every path by as much as its prior allows.
  if (headingOnly()) return deviation_.covariance();
  return deviationObserved() ? deviation_.covariance() : Eigen::Matrix2d::Zero();
}

bool Localizer::confirmedByDeadReckoning(const LoopCandidate& candidate) const {
  const LoopClosure& loop = report_.loop_closures[candidate.report];
  const Eigen::Matrix3d covariance = pathCovariance(loop.from, loop.to) + covarianceOf(candidate.information);
  return chi2(deadReckoningBetween(loop.from, loop.to).between(loop.measurement), covariance) <= options_.loop_gate_chi2;
}

bool Localizer::consistent(const LoopCandidate& a, const LoopCandidate& b) const {
  // The cycle of (j1 → k1, z1) and (j2 → k2, z2): z1 ∘ dr(k1 → k2) ∘ z2⁻¹ ∘ dr(j2 → j1) is the
  // identity; its covariance adds both matches' and the dead reckoning's along the two paths. The
  // dead reckoning, not the estimate, joins them, so the test does not depend on which loop
  // closures were accepted before.
  const LoopClosure& one = report_.loop_closures[a.report];
  const LoopClosure& two = report_.loop_closures[b.report];
  Pose2 cycle = one.measurement;
  Eigen::Matrix3d covariance = covarianceOf(a.information);
  const auto extend = [&](const Pose2& step, const Eigen::Matrix3d& step_covariance) {
    covariance = composeCovariance(cycle, covariance, step, step_covariance);
    cycle = cycle * step;
  };
  extend(deadReckoningBetween(one.to, two.to), pathCovariance(one.to, two.to));
  extend(two.measurement.inverse(), inverseCovariance(two.measurement, covarianceOf(b.information)));
  extend(deadReckoningBetween(two.from, one.from), pathCovariance(two.from, one.from));
  return chi2(cycle, covariance) <= options_.consistency_chi2;
}

bool Localizer::acceptSet(const std::vector<std::size_t>& clique) {
  if (clique == accepted_) return false;
  for (const std::size_t c : accepted_) {
    if (std::binary_search(clique.begin(), clique.end(), c)) continue;
    graph_.setInformation(candidates_[c].edge, Eigen::Matrix3d::Zero());
    LoopClosure& loop = report_.loop_closures[candidates_[c].report];
    loop.accepted = false;
    loop.reason = kOutvoted;
  }
  for (const std::size_t c : clique) {
    graph_.setInformation(candidates_[c].edge, candidates_[c].information);
    LoopClosure& loop = report_.loop_closures[candidates_[c].report];
    loop.accepted = true;
    loop.reason.clear();
  }
  accepted_ = clique;
  return true;
}

bool Localizer::addLoopClosure(std::size_t from, std::size_t to, const Pose2& measurement, const Eigen::Matrix3d& information,
                               const std::optional<Eigen::Matrix3d>& pairs_information) {
  LoopClosure loop;
  loop.from = from;
  loop.to = to;
  loop.measurement = measurement;
  if (beyondLimits(from, to, measurement)) {
    loop.reason = "faster than the vehicle's limits (its top speed or turn rate)";
    report_.loop_closures.push_back(loop);
    return false;
  }
  LoopCandidate candidate;
  candidate.report = report_.loop_closures.size();
  candidate.information = information;
  candidate.pairs_information = pairs_information;
  candidate.edge = graph_.edges().size();
  report_.loop_closures.push_back(loop);
  graph_.addEdge({from, to, measurement, Eigen::Matrix3d::Zero(), EdgeKind::kLoopClosure});
  edge_pairs_information_.push_back(std::nullopt);
  const std::size_t index = candidates_.size();
  std::vector<std::size_t> neighbours;
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    if (consistent(candidates_[c], candidate)) neighbours.push_back(c);
  }
  consistency_.addVertex(neighbours);
  candidates_.push_back(candidate);
  // Joins the accepted set when it agrees with all of it. Otherwise the largest agreeing set it
  // belongs to replaces the accepted one if it is larger; alone, it needs the dead reckoning's
  // confirmation and no accepted set to contradict.
  std::vector<std::size_t> clique;
  const bool agrees = std::all_of(accepted_.begin(), accepted_.end(), [&](std::size_t c) { return consistency_.joined(c, index); });
  if (agrees && !accepted_.empty()) {
    clique = accepted_;
    clique.push_back(index);
  } else {
    clique = consistency_.cliqueFrom(index);
    const bool lone_confirmed = clique.size() == 1 && accepted_.empty() && confirmedByDeadReckoning(candidates_[index]);
    if (!(clique.size() >= 2 && clique.size() > accepted_.size()) && !lone_confirmed) {
      report_.loop_closures.back().reason = accepted_.empty() && clique.size() < 2 ? kUnconfirmed : kInconsistent;
      return false;
    }
  }
  acceptSet(clique);
  graph_.optimize(options_.graph);
  return report_.loop_closures[candidates_[index].report].accepted;
}

void Localizer::redecideLoopClosures() {
  if (candidates_.empty()) return;
  consistency_ = ConsistencyGraph();
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    std::vector<std::size_t> neighbours;
    for (std::size_t other = 0; other < c; ++other) {
      if (consistent(candidates_[other], candidates_[c])) neighbours.push_back(other);
    }
    consistency_.addVertex(neighbours);
  }
  std::vector<std::size_t> clique = consistency_.largestClique();
  if (clique.size() < 2) {
    // No two agree: a lone loop closure stands when the dead reckoning confirms it and it is the
    // only one it confirms.
    clique.clear();
    for (std::size_t c = 0; c < candidates_.size(); ++c) {
      if (confirmedByDeadReckoning(candidates_[c])) clique.push_back(c);
    }
    if (clique.size() != 1) clique.clear();
  }
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    LoopClosure& loop = report_.loop_closures[candidates_[c].report];
    if (!loop.accepted && !std::binary_search(clique.begin(), clique.end(), c)) {
      loop.reason = consistency_.neighbours(c).empty() ? kUnconfirmed : kInconsistent;
    }
  }
  acceptSet(clique);
}

}  // namespace sonarmap

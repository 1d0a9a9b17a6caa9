/// @file trajectory_error.cpp
/// ATE, RPE and final drift of an estimated track against the truth (see trajectory_error.hpp).

#include "sonarmap/eval/trajectory_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void checkEstimate(const NavTrack& track) {
  if (track.empty()) throw ValueError("trajectory evaluation: the estimated track is empty");
  const std::optional<NavTrackFault> fault = findNavTrackFault(track);
  if (!fault) return;
  if (fault->kind == NavTrackFault::Kind::kNotFinite) {
    throw ValueError("trajectory evaluation: estimate fix " + std::to_string(fault->index) + " holds a non-finite value");
  }
  throw ValueError("trajectory evaluation: estimate fix " + std::to_string(fault->index) +
                   "'s time is not after the previous fix's; times must increase strictly");
}

/// Distance travelled along the truth's fixes from its first fix to `time_s` (within its span).
class TruthDistance {
 public:
  explicit TruthDistance(const NavTrack& truth) : truth_(truth), cumulative_m_(truth.size(), 0.0) {
    for (std::size_t k = 1; k < truth.size(); ++k) {
      cumulative_m_[k] = cumulative_m_[k - 1] + (truth[k].position_ned_m - truth[k - 1].position_ned_m).norm();
    }
  }

  double at(double time_s) const {
    const auto after = std::upper_bound(truth_.begin(), truth_.end(), time_s,
                                        [](double t, const NavSample& fix) { return t < fix.time_s; });
    if (after == truth_.end()) return cumulative_m_.back();
    if (after == truth_.begin()) return 0.0;
    const std::size_t b = static_cast<std::size_t>(after - truth_.begin());
    const double f = (time_s - truth_[b - 1].time_s) / (truth_[b].time_s - truth_[b - 1].time_s);
    return cumulative_m_[b - 1] + f * (cumulative_m_[b] - cumulative_m_[b - 1]);
  }

 private:
  const NavTrack& truth_;
  std::vector<double> cumulative_m_;
};

double yawOf(const Eigen::Matrix3d& rotation) { return std::atan2(rotation(1, 0), rotation(0, 0)); }

}  // namespace

TrajectoryError evaluateTrajectory(const NavTrack& estimate, const NavTrack& truth,
                                   const TrajectoryErrorOptions& options) {
  if (!(std::isfinite(options.segment_m) && options.segment_m > 0.0)) {
    throw ValueError("trajectory evaluation: segment_m must be a finite number > 0, got " +
                     std::to_string(options.segment_m));
  }
  checkEstimate(estimate);
  const NavInterpolator interpolator(truth);  // checks the truth
  const TruthDistance distance(truth);

  // Association.
  std::vector<Eigen::Isometry3d> est, tru;
  std::vector<double> travelled_m;
  for (const NavSample& fix : estimate) {
    const std::optional<Eigen::Isometry3d> pose = interpolator.bodyToNedAt(fix.time_s);
    if (!pose) continue;
    est.push_back(bodyToNed(fix));
    tru.push_back(*pose);
    travelled_m.push_back(distance.at(fix.time_s));
  }
  const std::size_t n = est.size();
  if (n < 3) {
    throw ValueError("trajectory evaluation: " + std::to_string(n) +
                     " estimate fix(es) within the truth's time span, need at least 3");
  }
  TrajectoryError result;
  result.poses = n;
  result.distance_m = travelled_m.back() - travelled_m.front();

  // ATE after a rigid alignment (Umeyama 1991), in the plane or in 3D.
  const int dims = options.se3 ? 3 : 2;
  Eigen::MatrixXd source(dims, static_cast<Eigen::Index>(n)), target(dims, static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    source.col(static_cast<Eigen::Index>(i)) = est[i].translation().head(dims);
    target.col(static_cast<Eigen::Index>(i)) = tru[i].translation().head(dims);
  }
  const Eigen::MatrixXd alignment = Eigen::umeyama(source, target, false);
  const Eigen::MatrixXd rotation = alignment.topLeftCorner(dims, dims);
  const Eigen::VectorXd shift = alignment.topRightCorner(dims, 1);
  double sum_squared = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto col = static_cast<Eigen::Index>(i);
    double squared = (rotation * source.col(col) + shift - target.col(col)).squaredNorm();
    if (!options.se3) squared += std::pow(est[i].translation().z() - tru[i].translation().z(), 2);  // unaligned depth
    sum_squared += squared;
    result.ate_max_m = std::max(result.ate_max_m, std::sqrt(squared));
  }
  result.ate_rmse_m = std::sqrt(sum_squared / static_cast<double>(n));

  // The error with the start positions matched instead of a fit: the estimate shifted so that its
  // first associated position is the truth's (north and east; with se3 the depth too), not turned.
  Eigen::Vector3d shift_m = tru.front().translation() - est.front().translation();
  if (!options.se3) shift_m.z() = 0.0;  // depth stays unaligned
  double start_squared = 0.0;
  for (std::size_t i = 0; i < n; ++i) start_squared += (est[i].translation() + shift_m - tru[i].translation()).squaredNorm();
  result.ate_start_rmse_m = std::sqrt(start_squared / static_cast<double>(n));

  // RPE over segments of segment_m travelled by the truth.
  double translation_sq = 0.0, yaw_sq = 0.0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    j = std::max(j, i + 1);
    while (j < n && travelled_m[j] - travelled_m[i] < options.segment_m) ++j;
    if (j >= n) break;
    const Eigen::Isometry3d error = (tru[i].inverse() * tru[j]).inverse() * (est[i].inverse() * est[j]);
    translation_sq += error.translation().squaredNorm();
    yaw_sq += std::pow(yawOf(error.linear()) * 180.0 / std::numbers::pi, 2);
    ++result.rpe_segments;
  }
  const double segments = static_cast<double>(result.rpe_segments);
  result.rpe_rmse_m = result.rpe_segments > 0 ? std::sqrt(translation_sq / segments) : kNaN;
  result.rpe_yaw_rmse_deg = result.rpe_segments > 0 ? std::sqrt(yaw_sq / segments) : kNaN;

  // Final drift, unaligned.
  result.final_drift_m = (est.back().translation() - tru.back().translation()).norm();
  result.final_drift_pct = result.distance_m > 0.0 ? 100.0 * result.final_drift_m / result.distance_m : kNaN;
  return result;
}

}  // namespace sonarmap

// ATE, RPE and final drift of an estimated track against the truth (eval/trajectory_error.hpp).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/trajectory_error.hpp"

namespace sonarmap {
namespace {

/// An L-shaped track: 60 m north, then 40 m east, 1 m/s, a fix every 0.5 s, yaw along travel.
NavTrack lTrack() {
  NavTrack track;
  for (int k = 0; k <= 200; ++k) {
    NavSample fix;
    fix.time_s = 0.5 * k;
    const double d = fix.time_s;
    fix.position_ned_m = d <= 60.0 ? Eigen::Vector3d(d, 0.0, 1.0) : Eigen::Vector3d(60.0, d - 60.0, 1.0);
    fix.yaw_rad = d < 60.0 ? 0.0 : 0.5 * std::numbers::pi;
    track.push_back(fix);
  }
  return track;
}

/// `track` moved rigidly: turned by `yaw_rad` about the vertical, then shifted by `shift_m`.
NavTrack moved(const NavTrack& track, double yaw_rad, const Eigen::Vector3d& shift_m) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  NavTrack out = track;
  for (NavSample& fix : out) {
    fix.position_ned_m = turn * fix.position_ned_m + shift_m;
    fix.yaw_rad += yaw_rad;
  }
  return out;
}

TEST(evalTrajectoryError, IdenticalTracksHaveNoError) {
  const NavTrack truth = lTrack();
  const TrajectoryError e = evaluateTrajectory(truth, truth);
  EXPECT_EQ(e.poses, truth.size());
  EXPECT_NEAR(e.distance_m, 100.0, 1e-9);
  EXPECT_NEAR(e.ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(e.ate_max_m, 0.0, 1e-9);
  EXPECT_NEAR(e.ate_start_rmse_m, 0.0, 1e-9);
  EXPECT_GT(e.rpe_segments, 100U);
  EXPECT_NEAR(e.rpe_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(e.rpe_yaw_rmse_deg, 0.0, 1e-9);
  EXPECT_EQ(e.final_drift_m, 0.0);
  EXPECT_EQ(e.final_drift_pct, 0.0);
}

TEST(evalTrajectoryError, RigidMotionIsAlignedAwayButDrifts) {
  const NavTrack truth = lTrack();
  const NavTrack estimate = moved(truth, 0.3, Eigen::Vector3d(5.0, -2.0, 0.0));
  for (const bool se3 : {false, true}) {
    TrajectoryErrorOptions options;
    options.se3 = se3;
    const TrajectoryError e = evaluateTrajectory(estimate, truth, options);
    EXPECT_NEAR(e.ate_rmse_m, 0.0, 1e-6) << se3;
    EXPECT_NEAR(e.ate_max_m, 0.0, 1e-6) << se3;
    EXPECT_NEAR(e.rpe_rmse_m, 0.0, 1e-9) << se3;  // relative motion unchanged
    EXPECT_NEAR(e.rpe_yaw_rmse_deg, 0.0, 1e-9) << se3;
    EXPECT_GT(e.final_drift_m, 5.0) << se3;
    EXPECT_NEAR(e.final_drift_pct, e.final_drift_m, 1e-9) << se3;  // 100 m travelled
  }
  // Shifted, the start-matched error is zero too; turned about the start (a heading bias), the fit
  // turns it away but the start does not: each point is off by the chord 2 |p| sin(1°).
  const NavTrack shifted = moved(truth, 0.0, Eigen::Vector3d(5.0, -2.0, 0.0));
  EXPECT_NEAR(evaluateTrajectory(shifted, truth).ate_start_rmse_m, 0.0, 1e-9);
  const NavTrack biased = moved(truth, 2.0 * std::numbers::pi / 180.0, Eigen::Vector3d::Zero());  // the L starts at 0
  const TrajectoryError bias = evaluateTrajectory(biased, truth);
  EXPECT_NEAR(bias.ate_rmse_m, 0.0, 1e-6);
  double expected_sq = 0.0;
  for (const NavSample& fix : truth) {
    const double chord_m = 2.0 * fix.position_ned_m.head<2>().norm() * std::sin(std::numbers::pi / 180.0);
    expected_sq += chord_m * chord_m;
  }
  EXPECT_NEAR(bias.ate_start_rmse_m, std::sqrt(expected_sq / static_cast<double>(truth.size())), 1e-9);
  EXPECT_GT(bias.ate_start_rmse_m, 1.0);
  // A depth offset stays in the SE(2) ATE (depth is not aligned), not in the SE(3) one.
  const NavTrack deeper = moved(truth, 0.0, Eigen::Vector3d(0.0, 0.0, 0.5));
  EXPECT_NEAR(evaluateTrajectory(deeper, truth).ate_rmse_m, 0.5, 1e-9);
  EXPECT_NEAR(evaluateTrajectory(deeper, truth, {true, 10.0}).ate_rmse_m, 0.0, 1e-6);
}

TEST(evalTrajectoryError, ScaleDriftOnAStraightLine) {
  NavTrack truth, estimate;
  for (int k = 0; k <= 1000; ++k) {  // 100 m north at 1 m/s, 10 Hz; the estimate reads 1 % long
    NavSample fix;
    fix.time_s = 0.1 * k;
    fix.position_ned_m = Eigen::Vector3d(fix.time_s, 0.0, 0.0);
    truth.push_back(fix);
    fix.position_ned_m.x() *= 1.01;
    estimate.push_back(fix);
  }
  const TrajectoryError e = evaluateTrajectory(estimate, truth);
  EXPECT_NEAR(e.final_drift_m, 1.0, 1e-9);
  EXPECT_NEAR(e.final_drift_pct, 1.0, 1e-9);
  EXPECT_NEAR(e.rpe_rmse_m, 0.1, 1e-3);  // 1 % of each 10 m segment
  EXPECT_NEAR(e.rpe_yaw_rmse_deg, 0.0, 1e-9);
  EXPECT_GT(e.ate_rmse_m, 0.0);
  EXPECT_LT(e.ate_rmse_m, 0.5);  // the alignment centres the stretch: ≈ 1 m / √12
  EXPECT_NEAR(evaluateTrajectory(estimate, truth, {false, 20.0}).rpe_rmse_m, 0.2, 2e-3);
}

TEST(evalTrajectoryError, AssociatesByTimeAndDropsFixesOutsideTheTruth) {
  const NavTrack truth = lTrack();  // 0 to 100 s
  NavTrack estimate;
  for (int k = -5; k <= 110; ++k) {  // every 1 s from −5 s to 110 s, at the truth's places
    const double t = k + 0.25;
    NavSample fix;
    fix.time_s = t;
    fix.position_ned_m = t <= 60.0 ? Eigen::Vector3d(t, 0.0, 1.0) : Eigen::Vector3d(60.0, t - 60.0, 1.0);
    estimate.push_back(fix);
  }
  const TrajectoryError e = evaluateTrajectory(estimate, truth);
  EXPECT_EQ(e.poses, 100U);  // 0.25 s … 99.25 s
  EXPECT_NEAR(e.ate_rmse_m, 0.0, 1e-6);
  EXPECT_NEAR(e.distance_m, 99.0, 1e-9);
}

TEST(evalTrajectoryError, TooFewCommonPosesOrBadInput) {
  const NavTrack truth = lTrack();
  NavTrack estimate(truth.begin(), truth.begin() + 2);
  EXPECT_THROW(evaluateTrajectory(estimate, truth), ValueError);
  NavTrack late = truth;
  for (NavSample& fix : late) fix.time_s += 1000.0;
  EXPECT_THROW(evaluateTrajectory(late, truth), ValueError);
  EXPECT_THROW(evaluateTrajectory({}, truth), ValueError);
  EXPECT_THROW(evaluateTrajectory(truth, {}), ValueError);
  EXPECT_THROW(evaluateTrajectory(truth, truth, {false, 0.0}), ValueError);
  // A truth shorter than one segment: no RPE (NaN), the rest still scored.
  const TrajectoryError short_run = evaluateTrajectory(truth, truth, {false, 1000.0});
  EXPECT_EQ(short_run.rpe_segments, 0U);
  EXPECT_TRUE(std::isnan(short_run.rpe_rmse_m));
}

}  // namespace
}  // namespace sonarmap

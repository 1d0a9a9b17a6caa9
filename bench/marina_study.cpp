// sonarmap_marina_study: `sonarmap localize` on a real survey with DGPS truth, the St. Pere marina
// (../shared/data/stpere_marina: the Ictineu AUV's Tritech MiniKing point scans, its DVL + compass
// dead reckoning and the DGPS track; docs/localization.md). Not a test: run it on every change to
// the localizer, beside the simulated studies (sonarmap_slam_study).
//
// Prints, for the dead reckoning and for `localize` with the default options (the CLI's: the
// navigation class the track suggests), the error from the start (TrajectoryError::ate_start_rmse_m:
// both tracks start at the DGPS's first fix) and the aligned ATE (after a rigid SE(2) fit) against
// the DGPS, the loop closures proposed, accepted and wrong, the odometry scale, and the time
// against the survey's duration. A loop closure is wrong when its relative pose differs from the
// DGPS's by more than 2 m or 5°; the DGPS's heading is the vehicle's compass (the buoy measures no
// heading), whose deviation differs by up to 11° between passes in opposite directions, so the
// closures wrong by heading alone are counted apart.
//
// With --png PATH it draws the scans placed three ways side by side: with the dead reckoning, with
// `localize`, with the DGPS positions (and the compass heading), on one grid of 0.25 m.
//
// Usage: sonarmap_marina_study [--data DIR] [--png PATH] [--verbose] [--heading-only] [--nav-class NAME]
//        [--scale-sigma PCT] [--heading-sigma DEG] [--gyro-walk DEG/SQRT(S)] [--velocity-noise M/S]
//   --data DIR: a folder holding scans.csv.gz (or scans.csv), dr_nav.csv and dgps_truth_nav.csv
//               (default: the shared data's stpere_marina; the whole survey scored aside has the same layout)
//   --verbose:  one line per loop closure tried on stderr
//   --heading-only: the compass alone (dr_nav.csv's north and east set to 0, class ahrs), as a
//               vehicle without a DVL logs it
//   --nav-class and the sigmas: the localization's odometry noise (OdometryNoise), as `localize`'s options

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/trajectory_error.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/render/point_figures.hpp"
#include "sonarmap/slam/point_scan_map.hpp"
#include "sonarmap/slam/point_scans.hpp"

namespace {

using namespace sonarmap;
using Clock = std::chrono::steady_clock;
constexpr double kDegree = std::numbers::pi / 180.0;

/// The DGPS pose at each scan's time (positions interpolated; the heading is the compass's).
std::vector<Pose2> truthPoses(const std::vector<double>& times_s, const NavTrack& truth) {
  std::vector<Pose2> poses;
  for (const double t : times_s) {
    const auto body = interpolateBodyToNed(truth, t);
    poses.push_back(body ? planarPose(*body) : Pose2{});
  }
  return poses;
}

/// The compass's deviation as the DGPS shows it: the difference between the DGPS's course over the
/// ground and the dead reckoning's (DVL + compass) over ±20 s windows in which the DGPS moved at
/// least 6 m, fitted by least squares as a + b cos ψ + c sin ψ of the compass heading ψ (one cycle
/// per turn, the classic deviation of a magnetised vehicle). Returns (a, b, c), radians.
Eigen::Vector3d compassDeviation(const NavTrack& dead_reckoning, const NavTrack& truth) {
  constexpr double kHalfWindow_s = 20.0, kMinTravel_m = 6.0;
  std::vector<Eigen::Vector3d> rows;
  std::vector<double> differences;
  for (double t = truth.front().time_s + kHalfWindow_s; t + kHalfWindow_s <= truth.back().time_s; t += 5.0) {
    const auto g0 = interpolateBodyToNed(truth, t - kHalfWindow_s), g1 = interpolateBodyToNed(truth, t + kHalfWindow_s);
    const auto d0 = interpolateBodyToNed(dead_reckoning, t - kHalfWindow_s), d1 = interpolateBodyToNed(dead_reckoning, t + kHalfWindow_s);
    const auto d = interpolateBodyToNed(dead_reckoning, t);
    if (!g0 || !g1 || !d0 || !d1 || !d) continue;
    const Eigen::Vector2d g = (g1->translation() - g0->translation()).head<2>();
    const Eigen::Vector2d r = (d1->translation() - d0->translation()).head<2>();
    if (g.norm() < kMinTravel_m) continue;
    const double psi = planarPose(*d).yaw_rad;
    rows.emplace_back(1.0, std::cos(psi), std::sin(psi));
    differences.push_back(wrapAngle_rad(std::atan2(g.y(), g.x()) - std::atan2(r.y(), r.x())));
  }
  if (rows.size() < 3) return Eigen::Vector3d::Zero();
  Eigen::MatrixXd a(rows.size(), 3);
  Eigen::VectorXd b(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    a.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
    b(static_cast<Eigen::Index>(i)) = differences[i];
  }
  return a.colPivHouseholderQr().solve(b);
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = std::string(SONARMAP_SHARED_DATA) + "/stpere_marina";
  if (const char* env = std::getenv("SONARMAP_DATA")) data = std::string(env) + "/stpere_marina";
  std::string png;
  bool verbose = false;
  bool heading_only = false;
  SlamOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    OdometryNoise& odometry = options.forming.odometry;
    if (arg == "--nav-class" && i + 1 < argc) {
      odometry = odometryNoiseOf(argv[++i]);
    } else if (arg == "--gyro-walk" && i + 1 < argc) {
      odometry.gyro_walk_rad_per_sqrt_s = std::stod(argv[++i]) * kDegree;
    } else if (arg == "--heading-sigma" && i + 1 < argc) {
      odometry.heading_sigma_rad = std::stod(argv[++i]) * kDegree;
    } else if (arg == "--scale-sigma" && i + 1 < argc) {
      odometry.scale_sigma = std::stod(argv[++i]) / 100.0;
    } else if (arg == "--velocity-noise" && i + 1 < argc) {
      odometry.velocity_noise_mps = std::stod(argv[++i]);
    } else if (arg == "--loop-gate" && i + 1 < argc) {
      options.loop_gate_chi2 = std::stod(argv[++i]);
    } else if (arg == "--data" && i + 1 < argc) {
      data = argv[++i];
    } else if (arg == "--png" && i + 1 < argc) {
      png = argv[++i];
    } else if (arg == "--heading-only") {
      heading_only = true;
    } else if (arg == "--verbose") {
      verbose = true;
    } else {
      std::fprintf(stderr, "usage: sonarmap_marina_study [--data DIR] [--png PATH] [--verbose] [--heading-only] [--nav-class NAME] "
                           "[--scale-sigma PCT] [--heading-sigma DEG] [--gyro-walk DEG/SQRT(S)] [--velocity-noise M/S]\n");
      return 2;
    }
  }
  try {
    std::string scans_path = data + "/scans.csv.gz";
    if (!std::filesystem::exists(scans_path)) scans_path = data + "/scans.csv";
    const Clock::time_point read_start = Clock::now();
    const std::vector<BodyPoint> points = readPointScansCsv(scans_path);
    const NavTrack dead_reckoning = readNavCsv(data + "/dr_nav.csv");
    // --heading-only: the compass alone, as a vehicle without a DVL logs it (north and east 0).
    NavTrack navigation = dead_reckoning;
    if (heading_only) {
      for (NavSample& fix : navigation) fix.position_ned_m.head<2>().setZero();
      options.forming.odometry = odometryNoiseOf("ahrs");
    }
    const NavTrack truth = readNavCsv(data + "/dgps_truth_nav.csv");
    const double read_s = std::chrono::duration<double>(Clock::now() - read_start).count();

    const SlamOptions slam = withNavigationPeriod(options, navigation);
    const Clock::time_point start = Clock::now();
    const SlamResult result = localizePointScans(points, navigation, PointScanOptions{}, slam);
    const double localize_s = std::chrono::duration<double>(Clock::now() - start).count();

    const TrajectoryError dr = evaluateTrajectory(dead_reckoning, truth);
    const TrajectoryError est = evaluateTrajectory(result.trajectory, truth);
    const std::vector<Pose2> truth_poses = truthPoses(result.scan_times_s, truth);
    // The same with the compass's heading corrected by its deviation as the DGPS's course shows it.
    const Eigen::Vector3d deviation = compassDeviation(dead_reckoning, truth);
    std::vector<Pose2> corrected_poses = truth_poses;
    for (Pose2& pose : corrected_poses) {
      pose.yaw_rad = wrapAngle_rad(pose.yaw_rad + deviation.dot(Eigen::Vector3d(1.0, std::cos(pose.yaw_rad), std::sin(pose.yaw_rad))));
    }
    std::size_t accepted = 0, wrong = 0, wrong_corrected = 0;
    for (const LoopClosure& loop : result.report.loop_closures) {
      const Pose2 error = truth_poses[loop.from].between(truth_poses[loop.to]).between(loop.measurement);
      const Pose2 corrected = corrected_poses[loop.from].between(corrected_poses[loop.to]).between(loop.measurement);
      const auto isWrong = [](const Pose2& e) { return e.translation().norm() > 2.0 || std::abs(wrapAngle_rad(e.yaw_rad)) > 5.0 * kDegree; };
      if (verbose) {
        std::fprintf(stderr,
                     "loop %3zu -> %3zu %-8s off the DGPS by %5.2f m, %5.1f deg (deviation removed: %5.2f m, %5.1f deg; %zu pairs, "
                     "peak ratio %.2f)%s%s\n",
                     loop.from, loop.to, loop.accepted ? "accepted" : "refused", error.translation().norm(), error.yaw_rad / kDegree,
                     corrected.translation().norm(), corrected.yaw_rad / kDegree, loop.pairs, loop.peak_ratio,
                     loop.accepted ? "" : ": ", loop.reason.c_str());
      }
      if (!loop.accepted) continue;
      ++accepted;
      if (isWrong(error)) ++wrong;
      if (isWrong(corrected)) ++wrong_corrected;
    }
    const double duration_s = result.scan_times_s.empty() ? 0.0 : result.scan_times_s.back() - result.scan_times_s.front();
    std::printf("survey: %s, %zu scans over %.0f s, %.0f m travelled (DGPS)\n", data.c_str(), result.report.scans, duration_s,
                est.distance_m);
    std::printf("| track | from the start (m) | aligned ATE (m) | final drift (%%) |\n|---|---|---|---|\n");
    std::printf("| dead reckoning | %.2f | %.2f | %.1f |\n", dr.ate_start_rmse_m, dr.ate_rmse_m, dr.final_drift_pct);
    std::printf("| localize | %.2f | %.2f | %.1f |\n", est.ate_start_rmse_m, est.ate_rmse_m, est.final_drift_pct);
    std::printf("loop closures: %zu proposed, %zu accepted, %zu wrong (2 m or 5 deg off the DGPS with the compass's heading), "
                "%zu with the compass's deviation removed (%.1f%+.1f cos + %.1f sin of the heading, deg, from the DGPS's course)\n",
                result.report.loop_closures.size(), accepted, wrong, wrong_corrected, deviation(0) / kDegree, deviation(1) / kDegree,
                deviation(2) / kDegree);
    std::printf("scan matches: %zu accepted, %zu refused; odometry scale %.4f (sigma %.4f, %s)\n", result.report.matches_accepted,
                result.report.matches_refused, result.report.odometry_scale, result.report.odometry_scale_sigma,
                result.report.odometry_scale_observed ? "observed" : "not observed");
    const OdometryNoise& noise = result.report.odometry_noise;
    std::printf("navigation measured on the log: scale %.2f %%, heading %.2f deg, velocity noise %.3f m/s, heading walk %.3f "
                "deg/sqrt(s); compass deviation %.1f cos + %.1f sin of the heading, deg%s; matches' noise %.3f m, %.2f deg\n",
                100.0 * noise.scale_sigma, noise.heading_sigma_rad / kDegree, noise.velocity_noise_mps,
                noise.gyro_walk_rad_per_sqrt_s / kDegree, result.report.heading_deviation_rad.x() / kDegree,
                result.report.heading_deviation_rad.y() / kDegree, result.report.heading_deviation_observed ? "" : " (not shown by the matches)",
                result.report.match_noise.translation_sigma_m, result.report.match_noise.yaw_sigma_rad / kDegree);
    std::printf("time: read %.2f s, localize %.2f s: %.0f x faster than the survey\n", read_s, localize_s,
                duration_s / std::max(localize_s, 1e-9));
    if (!png.empty()) {
      const SlamOptions tuned = withNavigationPeriod(options, dead_reckoning);
      const std::vector<SonarScan> scans = formPointScans(points, dead_reckoning, PointScanOptions{}, tuned.forming);
      // Each scan's points are in its body frame either way: drawn at the dead reckoning's poses.
      std::vector<Pose2> dr_poses;
      for (const SonarScan& scan : scans) dr_poses.push_back(scan.dead_reckoning);
      char title[160];
      std::vector<PointPanel> panels;
      std::snprintf(title, sizeof title, "dead reckoning: %.2f m from the start, %.2f m aligned", dr.ate_start_rmse_m, dr.ate_rmse_m);
      panels.push_back(pointPanel(title, placedScanPoints(scans, dr_poses), dead_reckoning));
      std::snprintf(title, sizeof title, "localize: %.2f m from the start, %.2f m aligned", est.ate_start_rmse_m, est.ate_rmse_m);
      panels.push_back(pointPanel(title, placedScanPoints(scans, result.scan_poses), result.trajectory));
      panels.push_back(pointPanel("DGPS positions, compass heading", placedScanPoints(scans, truth_poses), truth));
      if (!cv::imwrite(png, pointPanelsFigure(panels))) throw FileError("cannot write '" + png + "'");
      std::printf("wrote %s\n", png.c_str());
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sonarmap_marina_study: %s\n", error.what());
    return 1;
  }
  return 0;
}

// sonarmap_slam_study: the seeded localization study of docs/localization.md (not a test).
//
// For each mission (a head flying a named mission of sim/missions.hpp in its scene) and each seed:
// simulate the run with a drifting dead reckoning, localize it (slam/localizer.hpp), and score
// dead reckoning and the localization against the true navigation (eval/trajectory_error.hpp:
// ATE after an SE(2) Umeyama alignment, RPE per 10 m, final drift). Each accepted loop closure is
// checked against the truth: wrong when the relative pose it asserts is off the true one by more
// than 5 % of the head's range or 3°. With --maps, the first seed's maps (true navigation, dead
// reckoning, --slam) are scored against the scene (eval/ground_truth.hpp), the two estimated
// trajectories first aligned rigidly to the truth as ATE aligns them (a heading bias at the start
// turns the whole believed world, which no localization can observe).
//
// The error from the start (TrajectoryError::ate_start_rmse_m) is scored beside the aligned ATE:
// the worst seed's SLAM/DR ratio, and its bound: the true track turned by the dead reckoning's
// heading error at the start (what a perfect localization anchored at the dead reckoning's first
// pose gives) over dead reckoning's.
//
// Dead reckoning of seed n: a DVL scale error of ±(2…3) %, a heading bias of ±(1…2)° (signs and
// sizes drawn from the seed), a gyro walk of 0.02°/√s and DVL noise of 0.02 m/s; the simulator's
// speckle and noise are seeded with n too.
//
// Usage: sonarmap_slam_study [--seeds N] [--only SONAR:MISSION] [--maps] [--verbose] [--fixed-scale] [--stated-noise] [--true-nav]
//        [--no-nav] [--heading-only] [--nav-class NAME] [--leading-edge] [--speed M/S] [--max-speed M/S]
//        [--max-turn-rate DEG/S]
// (--fixed-scale: SlamOptions::estimate_odometry_scale false)
// (--stated-noise: SlamOptions::calibrate_navigation false, the stated class's noise and the matches'
// pairs' information as they are)
// (--true-nav: the true navigation is given as the dead reckoning, so --slam should leave it where it
// is; DR's columns are then 0 and the odometry scale's range is printed on stderr)
// (--no-nav: no navigation at all, the motion from the scans alone; DR's columns are then the
// vehicle believed still at its start)
// (--nav-class NAME: the localization's odometry noise is that class's (scan_forming.hpp,
// odometryNoiseOf), and the dead reckoning's errors below are scaled by its σ over dvl-ahrs's)
// (--leading-edge: ScanFormingOptions::leading_edge_bearing, each surface point at the bearing its
// leading edge came from)
// (--heading-only: the dead reckoning's heading alone, its north and east 0 at every fix, as a
// BlueROV2's flight log without a DVL gives it, under the "ahrs" class; DR's columns are then that
// track, the vehicle believed still)
// (--speed M/S: every mission flown at this speed instead of its own, e.g. a slow ROV whose
// motion during a sweep is small against the range)
// (--max-speed M/S, --max-turn-rate DEG/S: the localization's limits on the vehicle's motion where
// no position is measured, OdometryNoise::max_speed_mps and max_turn_rate_radps)
// (--verbose: one line per seed on stderr: its errors, both ATEs, both errors from the start, the
// estimated odometry scale with its σ and whether the scans constrained it)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/eval/trajectory_error.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"
#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/slam/slam_mapping.hpp"
#include "sonarmap/slam/scan_forming.hpp"

namespace {

using namespace sonarmap;
using Clock = std::chrono::steady_clock;

struct Mission {
  const char* sonar;
  const char* name;
  std::size_t laps;
  double speed_mps = 0.0;  ///< 0: the mission's default (defaultMissionSpeed_mps)
};

const Mission kMissions[] = {
    {"micron", "harbour-loop", 2},          {"micron", "harbour-lawnmower", 1},
    {"micron", "hull-loop", 2},             {"micron", "harbour-featureless", 1},
    {"seaking-30", "harbour-loop", 1},      {"seaking-30", "hull-loop", 1},
    {"seaking-30", "harbour-featureless", 1}, {"ping360", "harbour-loop", 1},
    {"ping360", "hull-loop", 1},            {"seaking-30", "harbour-loop", 1, 1.5}};

double seconds(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

SimulationArguments argumentsOf(const Mission& mission, std::uint64_t seed, const OdometryNoise& noise) {
  SimulationArguments args;
  args.sonar = mission.sonar;
  args.mission = mission.name;
  args.laps = mission.laps;
  args.speed_mps = mission.speed_mps;
  args.seed = seed;
  std::mt19937_64 draw(seed * 0x9E3779B97F4A7C15ULL + 12345);
  const auto unit = [&draw] { return static_cast<double>(draw() >> 11) * 0x1.0p-53; };
  // Sized for the default class (dvl-ahrs) and scaled by the class's σ over its.
  const OdometryNoise base;
  args.dvl_scale_error = (unit() < 0.5 ? -1.0 : 1.0) * (0.02 + 0.01 * unit()) * (noise.scale_sigma / base.scale_sigma);
  args.heading_bias_deg =
      (unit() < 0.5 ? -1.0 : 1.0) * (1.0 + unit()) * (noise.heading_sigma_rad / base.heading_sigma_rad);
  args.gyro_walk_deg_per_sqrt_s = 0.02 * (noise.gyro_walk_rad_per_sqrt_s / base.gyro_walk_rad_per_sqrt_s);
  args.dvl_noise_mps = 0.02 * (noise.velocity_noise_mps / base.velocity_noise_mps);
  return args;
}

/// Loop closures accepted whose relative pose is off the truth by more than 5 % of the range or 3°.
std::size_t wrongLoops(const SlamResult& slam, const NavTrack& truth, double range_m, std::uint64_t seed) {
  std::size_t wrong = 0;
  for (const LoopClosure& loop : slam.report.loop_closures) {
    if (!loop.accepted) continue;
    const auto from = interpolateBodyToNed(truth, slam.scan_times_s[loop.from]);
    const auto to = interpolateBodyToNed(truth, slam.scan_times_s[loop.to]);
    if (!from || !to) continue;
    const Pose2 true_relative = planarPose(*from).between(planarPose(*to));
    const Pose2 error = true_relative.between(loop.measurement);
    if (error.translation().norm() > 0.05 * range_m || std::abs(error.yaw_rad) > 3.0 * std::numbers::pi / 180.0) {
      ++wrong;
      std::fprintf(stderr, "seed %llu: wrong loop closure %zu -> %zu: off by %.2f m, %.1f deg (%zu pairs, peak ratio %.2f)\n",
                   static_cast<unsigned long long>(seed), loop.from, loop.to, error.translation().norm(),
                   error.yaw_rad * 180.0 / std::numbers::pi, loop.pairs, loop.peak_ratio);
    }
  }
  return wrong;
}

GroundTruthReport scoreMap(const SonarMapper& mapper, const MsisSimulation& run, const Eigen::Isometry3d& sonar_to_body) {
  GroundTruthOptions truth;
  truth.sensor_positions_m.clear();
  const NavTrack& fixes = run.nav;
  for (std::size_t i = 0; i < fixes.size(); i += std::max<std::size_t>(1, fixes.size() / 40)) {
    truth.sensor_positions_m.push_back(sonarToMap(fixes[i], sonar_to_body).translation());
  }
  return evaluateAgainstScene(mapper.map(), run.scene, truth);
}

/// `estimate` moved by the rigid SE(2) transform that best aligns it with `truth` (Umeyama 1991,
/// Eigen::umeyama; the fixes share their times): a heading bias at the start rotates the whole
/// believed world, which no localization can see, so maps are scored in the aligned frame, as ATE is.
NavTrack aligned(const NavTrack& estimate, const NavTrack& truth) {
  Eigen::Matrix2Xd from(2, estimate.size()), to(2, estimate.size());
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    from.col(static_cast<Eigen::Index>(i)) = estimate[i].position_ned_m.head<2>();
    const auto body = interpolateBodyToNed(truth, estimate[i].time_s);
    to.col(static_cast<Eigen::Index>(i)) = body ? Eigen::Vector2d(body->translation().head<2>()) : Eigen::Vector2d(estimate[i].position_ned_m.head<2>());
  }
  const Eigen::Matrix3d transform = Eigen::umeyama(from, to, false);
  const double turn_rad = std::atan2(transform(1, 0), transform(0, 0));
  NavTrack moved = estimate;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    moved[i].position_ned_m.head<2>() = transform.topLeftCorner<2, 2>() * from.col(static_cast<Eigen::Index>(i)) +
                                        transform.topRightCorner<2, 1>();
    moved[i].yaw_rad += turn_rad;
  }
  return moved;
}

/// The true track turned about its start by the dead reckoning's heading error at the start: what a
/// perfect localization anchored at the dead reckoning's first pose gives (the scans measure
/// relative poses only, so a heading error at the start stays; Localizer's first node is the dead
/// reckoning's). Its error from the start bounds what any localization can reach on that score.
NavTrack truthWithStartHeadingOf(const NavTrack& truth, const NavTrack& dead_reckoning) {
  const auto believed = interpolateBodyToNed(dead_reckoning, truth.front().time_s);
  if (!believed) return truth;
  const double error_rad = planarPose(*believed).yaw_rad - truth.front().yaw_rad;
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(error_rad).toRotationMatrix();
  NavTrack turned = truth;
  for (NavSample& fix : turned) {
    fix.position_ned_m.head<2>() = truth.front().position_ned_m.head<2>() +
                                   turn * (fix.position_ned_m - truth.front().position_ned_m).head<2>();
    fix.yaw_rad += error_rad;
  }
  return turned;
}

/// The vehicle believed still at its true start: what a map without navigation assumes.
NavTrack stillAtStart(const NavTrack& truth) {
  NavTrack still = truth;
  for (NavSample& fix : still) {
    fix.position_ned_m = truth.front().position_ned_m;
    fix.yaw_rad = truth.front().yaw_rad;
  }
  return still;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t seeds = 20;
  std::string only;
  bool maps = false;
  bool verbose = false;
  bool fixed_scale = false;
  bool stated_noise = false;
  bool true_nav = false;
  bool no_nav = false;
  bool leading_edge = false;
  std::string nav_class = "dvl-ahrs";
  double speed_mps = 0.0;
  bool heading_only = false;
  double max_speed_mps = 0.0, max_turn_rate_deg_s = 0.0;  // 0: the localization's defaults
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seeds") == 0 && i + 1 < argc) {
      seeds = static_cast<std::size_t>(std::stoul(argv[++i]));
    } else if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
      only = argv[++i];
    } else if (std::strcmp(argv[i], "--maps") == 0) {
      maps = true;
    } else if (std::strcmp(argv[i], "--verbose") == 0) {
      verbose = true;
    } else if (std::strcmp(argv[i], "--fixed-scale") == 0) {
      fixed_scale = true;
    } else if (std::strcmp(argv[i], "--stated-noise") == 0) {
      stated_noise = true;
    } else if (std::strcmp(argv[i], "--true-nav") == 0) {
      true_nav = true;
    } else if (std::strcmp(argv[i], "--no-nav") == 0) {
      no_nav = true;
    } else if (std::strcmp(argv[i], "--leading-edge") == 0) {
      leading_edge = true;
    } else if (std::strcmp(argv[i], "--nav-class") == 0 && i + 1 < argc) {
      nav_class = argv[++i];
    } else if (std::strcmp(argv[i], "--heading-only") == 0) {
      heading_only = true;
      nav_class = "ahrs";
    } else if (std::strcmp(argv[i], "--speed") == 0 && i + 1 < argc) {
      speed_mps = std::stod(argv[++i]);
    } else if (std::strcmp(argv[i], "--max-speed") == 0 && i + 1 < argc) {
      max_speed_mps = std::stod(argv[++i]);
    } else if (std::strcmp(argv[i], "--max-turn-rate") == 0 && i + 1 < argc) {
      max_turn_rate_deg_s = std::stod(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: %s [--seeds N] [--only SONAR:MISSION] [--maps] [--verbose] [--fixed-scale] [--stated-noise] [--true-nav] [--no-nav] [--heading-only] [--nav-class NAME] [--leading-edge] [--speed M/S] [--max-speed M/S] [--max-turn-rate DEG/S]\n", argv[0]);
      return 2;
    }
  }
  std::printf("| sonar | mission | length | seeds | DR ATE median (max) | SLAM ATE median (max) | worst SLAM/DR | "
              "DR / SLAM ATE from the start, median (max) | worst SLAM/DR from the start | bound/DR from the start, median (max) | "
              "SLAM final drift median (max) | loops accepted (wrong) | x real time (min) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (Mission mission : kMissions) {
    if (speed_mps > 0.0) mission.speed_mps = speed_mps;
    if (!only.empty() && only != std::string(mission.sonar) + ":" + mission.name) continue;
    std::vector<double> dr_ate, slam_ate, slam_drift, dr_start, slam_start, bound_ratio;
    double worst_ratio = 0.0, worst_start_ratio = 0.0, slowest = 1e300, length_m = 0.0;
    double scale_min = 1e300, scale_max = -1e300;
    std::size_t accepted = 0, wrong = 0;
    for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
      const SimulationArguments args = argumentsOf(mission, seed, odometryNoiseOf(nav_class));
      const MsisSimulationOptions options = toSimulationOptions(args);
      const MsisSimulation run = simulateInMissionScene(mission.name, options);
      const Clock::time_point start = Clock::now();
      SlamOptions slam_options;
      slam_options.estimate_odometry_scale = !fixed_scale;
      slam_options.calibrate_navigation = !stated_noise;
      slam_options.forming.odometry = odometryNoiseOf(nav_class);
      if (max_speed_mps > 0.0) slam_options.forming.odometry.max_speed_mps = max_speed_mps;
      if (max_turn_rate_deg_s > 0.0) slam_options.forming.odometry.max_turn_rate_radps = max_turn_rate_deg_s * std::numbers::pi / 180.0;
      slam_options.forming.leading_edge_bearing = leading_edge;
      // What `map --slam` does: each sweep detected once, localized, and mapped with the result.
      NavTrack heading_track;
      if (heading_only) {
        heading_track = true_nav ? run.nav : run.dead_reckoning;
        for (NavSample& fix : heading_track) fix.position_ned_m.head<2>().setZero();
      }
      const NavTrack& dead_reckoning = no_nav ? NavTrack{} : heading_only ? heading_track : true_nav ? run.nav : run.dead_reckoning;
      const SlamMapping mapped =
          mapSonarLogWithSlam(run.log, dead_reckoning, options.sonar_to_body, MapperOptions{}, slam_options);
      const SlamResult& slam = mapped.slam;
      const double spent_s = seconds(start);
      const double duration_s = run.log.beams.back().time_s - run.log.beams.front().time_s;
      slowest = std::min(slowest, duration_s / spent_s);
      const TrajectoryError dr = evaluateTrajectory(no_nav ? stillAtStart(run.nav) : dead_reckoning, run.nav);
      const TrajectoryError est = evaluateTrajectory(slam.trajectory, run.nav);
      length_m = dr.distance_m;
      dr_ate.push_back(dr.ate_rmse_m);
      slam_ate.push_back(est.ate_rmse_m);
      dr_start.push_back(dr.ate_start_rmse_m);
      slam_start.push_back(est.ate_start_rmse_m);
      slam_drift.push_back(est.final_drift_pct);
      if (dr.ate_rmse_m > 1e-6) worst_ratio = std::max(worst_ratio, est.ate_rmse_m / dr.ate_rmse_m);
      if (dr.ate_start_rmse_m > 1e-6) {
        worst_start_ratio = std::max(worst_start_ratio, est.ate_start_rmse_m / dr.ate_start_rmse_m);
        if (!no_nav) {
          const TrajectoryError bound = evaluateTrajectory(truthWithStartHeadingOf(run.nav, dead_reckoning), run.nav);
          bound_ratio.push_back(bound.ate_start_rmse_m / dr.ate_start_rmse_m);
        }
      }
      scale_min = std::min(scale_min, slam.report.odometry_scale);
      scale_max = std::max(scale_max, slam.report.odometry_scale);
      if (verbose) {
        std::fprintf(stderr, "%s %s seed %llu: scale error %+.4f, bias %+.2f deg: DR ATE %.3f m, SLAM ATE %.3f m, "
                     "from the start DR %.3f m, SLAM %.3f m, odometry scale %.4f ± %.4f (%s)\n", mission.sonar, mission.name, static_cast<unsigned long long>(seed),
                     args.dvl_scale_error, args.heading_bias_deg, dr.ate_rmse_m, est.ate_rmse_m, dr.ate_start_rmse_m, est.ate_start_rmse_m, slam.report.odometry_scale, slam.report.odometry_scale_sigma, slam.report.odometry_scale_observed ? "observed" : "not observed");
      }
      accepted += slam.report.loopClosuresAccepted();
      wrong += wrongLoops(slam, run.nav, options.head.range_m, seed);
      if (maps && seed == 1) {
        const SonarMapper true_map = mapSonarLog(run.log, run.nav, options.sonar_to_body, MapperOptions{});
        const SonarMapper dr_map =
            mapSonarLog(run.log, aligned(no_nav ? stillAtStart(run.nav) : dead_reckoning, run.nav), options.sonar_to_body,
                        MapperOptions{});
        const SonarMapper aligned_slam_map =
            mapSonarLog(run.log, aligned(slam.trajectory, run.nav), options.sonar_to_body, MapperOptions{});
        const GroundTruthReport t = scoreMap(true_map, run, options.sonar_to_body);
        const GroundTruthReport d = scoreMap(dr_map, run, options.sonar_to_body);
        const GroundTruthReport s = scoreMap(aligned_slam_map, run, options.sonar_to_body);
        std::fprintf(stderr, "%s %s seed 1 map P/R/free: true nav %.3f/%.3f/%.3f, DR %.3f/%.3f/%.3f, slam %.3f/%.3f/%.3f\n",
                     mission.sonar, mission.name, t.precision, t.recall, t.free_accuracy, d.precision, d.recall,
                     d.free_accuracy, s.precision, s.recall, s.free_accuracy);
      }
    }
    const auto maxOf = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
    char speed[32] = "";
    if (mission.speed_mps > 0.0) std::snprintf(speed, sizeof speed, " at %.1f m/s", mission.speed_mps);
    std::printf("| %s | %s ×%zu%s | %.0f m | %zu | %.3f (%.3f) m | %.3f (%.3f) m | %.2f | %.3f (%.3f) / %.3f (%.3f) m | "
                "%.2f | %.2f (%.2f) | %.2f (%.2f) %% | %zu (%zu) | %.0f |\n",
                mission.sonar, mission.name, mission.laps, speed, length_m, seeds, median(dr_ate), maxOf(dr_ate),
                median(slam_ate), maxOf(slam_ate), worst_ratio, median(dr_start), maxOf(dr_start), median(slam_start),
                maxOf(slam_start), worst_start_ratio, median(bound_ratio), bound_ratio.empty() ? 0.0 : maxOf(bound_ratio), median(slam_drift), maxOf(slam_drift), accepted, wrong, slowest);
    std::fflush(stdout);
    std::fprintf(stderr, "%s %s: odometry scale %.4f .. %.4f\n", mission.sonar, mission.name, scale_min, scale_max);
  }
  return 0;
}

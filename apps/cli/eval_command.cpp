#include "eval_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "eval_scoring_file.hpp"
#include "help_groups.hpp"
#include "progress.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/render/map_figures.hpp"
#include "sonarmap/sonar/png_writer.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/scene_file.hpp"

namespace sonarmap::cli {

namespace {

/// The built-in scenes' names, 2D then 3D, joined by `separator`.
std::string builtinNames(const char* separator) {
  std::string joined;
  for (const auto& names : {builtinSceneNames(), builtinScene3dNames()}) {
    for (const std::string& name : names) joined += (joined.empty() ? "" : separator) + name;
  }
  return joined;
}

constexpr double kDegree = std::numbers::pi / 180.0;

/// Sonar → map pose of one --sensor-pose: the sonar placed as a vehicle with the identity mounting
/// is at a navigation fix (NED metres, Z-Y-X angles in degrees: navigation.hpp), so a sonar at
/// rest at the origin is 0,0,0,0,0,0 and one tilted 25° down is pitch −25, as --mounting writes it.
Eigen::Isometry3d sonarToMapOfSensorPose(const double* pose) {
  NavSample fix;
  fix.position_ned_m = Eigen::Vector3d(pose[0], pose[1], pose[2]);
  fix.roll_rad = pose[3] * kDegree;
  fix.pitch_rad = pose[4] * kDegree;
  fix.yaw_rad = pose[5] * kDegree;
  return sonarToMap(fix, defaultSonarToBody());
}

}  // namespace

Command addEvalCommand(CLI::App& app, EvalArgs& args) {
  CLI::App* cmd = app.add_subcommand("eval", "Score a map (.bt/.ot) against a ground-truth scene, 2D or 3D");
  cmd->add_option("map", args.map, "Map to score: .bt or .ot")->required();
  cmd->add_option("--truth", args.truth, "Scene file, or a built-in scene: " + builtinNames(" | "))
      ->group(help_group::kInput);
  cmd->add_option("--scoring", args.scoring, "Scoring file: eval's options as JSON (demo's scoring.json)")
      ->group(help_group::kInput);
  cmd->add_option("--z-min", args.z_min_m, "Lowest voxel centre scored (m)")->group(help_group::kScoring);
  cmd->add_option("--z-max", args.z_max_m, "Highest voxel centre scored (m)")->group(help_group::kScoring);
  cmd->add_option("--tolerance", args.tolerance_m, "Match distance (m, at least a voxel diagonal)")
      ->capture_default_str()
      ->group(help_group::kScoring);
  cmd->add_option("--max-range", args.max_range_m, "Sonar reach: truth sought within it of the sonar (m)")
      ->group(help_group::kScoring);
  cmd->add_option("--sensor", args.sensor, "Sonar position x,y,z in the map frame (m); repeatable")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->group(help_group::kScoring);
  cmd->add_option("--sensor-pose", args.sensor_pose, "Sonar pose x,y,z (m, NED),roll,pitch,yaw (deg); repeatable")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->group(help_group::kScoring);
  cmd->add_option("--vertical-aperture", args.vertical_aperture_deg,
                  "With --sensor-pose: the sonar's vertical aperture (deg)")
      ->group(help_group::kScoring);
  addHeardOptions(*cmd, args.heard);
  cmd->add_option("--png", args.png, "Also write the map coloured by distance to the truth (PNG)")
      ->group(help_group::kOutput);
  cmd->add_flag("-q,--quiet", args.quiet, "No progress bar")->group(help_group::kOutput);
  struct Checked {
    GroundTruthOptions options;
    std::optional<HeardRequest> heard;
  };
  auto checked = std::make_shared<Checked>();
  return {cmd,
          [cmd, &args, checked] {
            if (!args.scoring.empty()) applyScoringFile(args.scoring, *cmd, args);
            if (args.truth.empty()) throw ValueError("eval needs --truth, or a --scoring file naming the truth");
            checked->options = toGroundTruthOptions(*cmd, args);
            checked->heard = toHeardRequest(*cmd, args.heard);
          },
          [&args, checked] { runEval(args, checked->options, checked->heard); }};
}

GroundTruthOptions toGroundTruthOptions(const CLI::App& cmd, const EvalArgs& args) {
  const auto given = [&](const std::string& flag) {
    return cmd.count(flag) > 0 ||
           std::find(args.file_options.begin(), args.file_options.end(), flag) != args.file_options.end();
  };
  GroundTruthOptions options;
  options.tolerance_m = args.tolerance_m;
  if (given("--z-min")) options.z_min_m = args.z_min_m;
  if (given("--z-max")) options.z_max_m = args.z_max_m;
  if (given("--max-range")) options.max_range_m = args.max_range_m;
  if (!args.sensor.empty() && !args.sensor_pose.empty()) {
    throw ValueError("--sensor and --sensor-pose exclude each other: give every sonar's pose with --sensor-pose");
  }
  if (!args.sensor.empty()) {
    if (args.sensor.size() % 3 != 0) throw ValueError("--sensor takes x,y,z: three numbers per position");
    options.sensor_positions_m.clear();
    for (std::size_t i = 0; i < args.sensor.size(); i += 3) {
      options.sensor_positions_m.emplace_back(args.sensor[i], args.sensor[i + 1], args.sensor[i + 2]);
    }
  }
  std::vector<Eigen::Matrix3d> orientations;
  if (!args.sensor_pose.empty()) {
    if (args.sensor_pose.size() % 6 != 0) {
      throw ValueError("--sensor-pose takes x,y,z,roll,pitch,yaw: six numbers per pose");
    }
    for (const double value : args.sensor_pose) {
      if (!std::isfinite(value)) throw ValueError("--sensor-pose: every number must be finite");
    }
    options.sensor_positions_m.clear();
    for (std::size_t i = 0; i < args.sensor_pose.size(); i += 6) {
      const Eigen::Isometry3d sonar_to_map = sonarToMapOfSensorPose(args.sensor_pose.data() + i);
      options.sensor_positions_m.push_back(sonar_to_map.translation());
      orientations.push_back(sonar_to_map.linear());
    }
  }
  if (given("--vertical-aperture")) {
    const double aperture_deg = args.vertical_aperture_deg;
    if (!(std::isfinite(aperture_deg) && aperture_deg > 0.0 && aperture_deg < 180.0)) {
      throw ValueError("--vertical-aperture must be in (0, 180) degrees, got " + std::to_string(aperture_deg));
    }
    if (orientations.empty()) throw ValueError("--vertical-aperture needs the sonars' orientations: give --sensor-pose");
    options.vertical_aperture_rad = aperture_deg * kDegree;
    options.sensor_orientations = std::move(orientations);
  }
  options.validate();
  if (options.max_range_m) {  // the truth within the reach of every sonar position, not the map's own box
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& position : options.sensor_positions_m) box.extend(position);
    options.surface_box_m = Eigen::AlignedBox3d(box.min().array() - *options.max_range_m, box.max().array() + *options.max_range_m);
  }
  return options;
}

namespace {

/// A scene file when `truth` names an existing file, else a built-in scene (2D or 3D) of that name.
Scene loadTruth(const std::string& truth) {
  std::vector<std::string> names = builtinSceneNames();
  for (std::string& name : builtinScene3dNames()) names.push_back(std::move(name));
  if (!std::filesystem::exists(truth) && std::find(names.begin(), names.end(), truth) != names.end()) {
    return builtinScene(truth);
  }
  return readScene(truth);
}

}  // namespace

void runEval(const EvalArgs& args, const GroundTruthOptions& options, const std::optional<HeardRequest>& heard) {
  // Scenes are in the internal NWU frame: the map is turned back from the frame its header names.
  const OcTree16 map = readMapFileToNwu(args.map).map;
  const Scene scene = loadTruth(args.truth);
  const auto start = std::chrono::steady_clock::now();
  const GroundTruthReport r = [&] {
    ProgressBar bar("scoring");
    return evaluateAgainstScene(map, scene, options, [&](std::size_t done, std::size_t total) {
      if (!args.quiet) bar.update(done, total);
    });
  }();
  HeardSurfaceStats heard_stats;
  const std::optional<HeardSurfaceScore> heard_score =
      heard ? std::optional(scoreHeardSurface(*heard, scene, map, r, args.quiet, heard_stats)) : std::nullopt;
  if (!args.png.empty()) {
    char title[512];
    std::snprintf(title, sizeof title, "%s vs truth %s  |  %g m voxels  |  occupied voxels by distance to the truth",
                  std::filesystem::path(args.map).filename().c_str(), std::filesystem::path(args.truth).filename().c_str(),
                  map.resolution_m());
    writeBytesAtomically(args.png, encodePng(surfaceErrorFigure(map, r, title, options.sensor_positions_m)));
  }
  const std::size_t off_surface = r.occupied_voxels - r.occupied_on_surface;
  if (off_surface == 0) {
    std::printf("precision %.4f (%zu of %zu occupied voxels on a surface)\n", r.precision, r.occupied_on_surface,
                r.occupied_voxels);
  } else {
    std::printf("precision %.4f (%zu of %zu occupied voxels on a surface; of the others, %zu in the water, %zu behind "
                "or inside a surface)\n",
                r.precision, r.occupied_on_surface, r.occupied_voxels, r.occupied_in_water, off_surface - r.occupied_in_water);
  }
  std::printf("recall %.4f (%zu of %zu visible surface voxels mapped)\n", r.recall, r.surface_voxels_found,
              r.surface_voxels);
  if (heard_score) printHeardScore(*heard, *heard_score, heard_stats);
  std::printf("erosion %.4f (%zu of %zu visible surface voxels free)\n", r.erosion, r.surface_voxels_free,
              r.surface_voxels);
  std::printf("free_accuracy %.4f (%zu of %zu free voxels in the water)\n", r.free_accuracy, r.free_in_water,
              r.free_voxels);
  std::printf("wall_error_mean_m %.4f rms_m %.4f (%zu occupied voxels within %.2f m of a surface)\n",
              r.mean_distance_m, r.rms_distance_m, r.matched_voxels, options.match_distance_m);
  std::printf("surface_error_median_m %.4f p90_m %.4f (over %zu occupied voxels)\n", r.surface_error_median_m,
              r.surface_error_p90_m, r.occupied_voxels);
  for (const SurfaceOffset& surface : r.surfaces) {
    std::printf("surface %zu %s median_offset_m %+.4f (%zu voxels)\n", surface.primitive,
                primitiveKind(scene.primitives[surface.primitive]), surface.median_signed_offset_m, surface.voxels);
  }
  std::printf("region z [%.3f, %.3f] m, range %.3f m, tolerance %.3f m\n", r.z_min_m, r.z_max_m, r.max_range_m,
              r.tolerance_m);
  std::printf("scored %zu occupied, %zu surface and %zu free voxels of %s in %.3f s%s%s\n", r.occupied_voxels,
              r.surface_voxels, r.free_voxels, args.map.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
              args.png.empty() ? "" : " -> ", args.png.c_str());
}

}  // namespace sonarmap::cli

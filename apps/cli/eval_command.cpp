#include "eval_command.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/scene_file.hpp"

namespace sonarmap::cli {

Command addEvalCommand(CLI::App& app, EvalArgs& args) {
  CLI::App* cmd = app.add_subcommand("eval", "Score a map (.bt/.ot) against a ground-truth scene");
  cmd->add_option("map", args.map, "Map to score: OctoMap binary (.bt) or full (.ot) tree")->required();
  cmd->add_option("--truth", args.truth, "Scene file, or a built-in scene: tank | harbour")->required();
  cmd->add_option("--z-min", args.z_min_m, "Lowest voxel centre scored, m (default: lowest known voxel)");
  cmd->add_option("--z-max", args.z_max_m, "Highest voxel centre scored, m (default: highest known voxel)");
  cmd->add_option("--tolerance", args.tolerance_m, "Match distance, m (never below one voxel diagonal)")
      ->capture_default_str();
  cmd->add_option("--max-range", args.max_range_m, "Sonar reach, m (default: farthest known voxel)");
  cmd->add_option("--sensor", args.sensor, "Sonar position x,y,z in the map frame, m; repeatable (default: origin)")
      ->delimiter(',')
      ->allow_extra_args(false);
  auto options = std::make_shared<GroundTruthOptions>();
  return {cmd, [cmd, &args, options] { *options = toGroundTruthOptions(*cmd, args); },
          [&args, options] { runEval(args, *options); }};
}

GroundTruthOptions toGroundTruthOptions(const CLI::App& cmd, const EvalArgs& args) {
  GroundTruthOptions options;
  options.tolerance_m = args.tolerance_m;
  if (cmd.count("--z-min") > 0) options.z_min_m = args.z_min_m;
  if (cmd.count("--z-max") > 0) options.z_max_m = args.z_max_m;
  if (cmd.count("--max-range") > 0) options.max_range_m = args.max_range_m;
  if (!args.sensor.empty()) {
    if (args.sensor.size() % 3 != 0) throw ValueError("--sensor takes x,y,z: three numbers per position");
    options.sensor_positions_m.clear();
    for (std::size_t i = 0; i < args.sensor.size(); i += 3) {
      options.sensor_positions_m.emplace_back(args.sensor[i], args.sensor[i + 1], args.sensor[i + 2]);
    }
  }
  options.validate();
  return options;
}

namespace {

/// A scene file when `truth` names an existing file, else a built-in scene of that name.
Scene loadTruth(const std::string& truth) {
  const std::vector<std::string> names = builtinSceneNames();
  if (!std::filesystem::exists(truth) && std::find(names.begin(), names.end(), truth) != names.end()) {
    return builtinScene(truth);
  }
  return readScene(truth);
}

}  // namespace

void runEval(const EvalArgs& args, const GroundTruthOptions& options) {
  const OcTree16 map = readMapFile(args.map);
  const Scene scene = loadTruth(args.truth);
  const GroundTruthReport r = evaluateAgainstScene(map, scene, options);
  std::printf("precision %.4f (%zu of %zu occupied voxels on a surface)\n", r.precision, r.occupied_on_surface,
              r.occupied_voxels);
  std::printf("recall %.4f (%zu of %zu visible surface voxels mapped)\n", r.recall, r.surface_voxels_found,
              r.surface_voxels);
  std::printf("free_accuracy %.4f (%zu of %zu free voxels in the water)\n", r.free_accuracy, r.free_in_water,
              r.free_voxels);
  std::printf("wall_error_mean_m %.4f rms_m %.4f (%zu occupied voxels within %.2f m of a surface)\n",
              r.mean_distance_m, r.rms_distance_m, r.matched_voxels, options.match_distance_m);
  for (const SurfaceOffset& surface : r.surfaces) {
    std::printf("surface %zu %s median_offset_m %+.4f (%zu voxels)\n", surface.primitive,
                primitiveKind(scene.primitives[surface.primitive]), surface.median_signed_offset_m, surface.voxels);
  }
  std::printf("region z [%.3f, %.3f] m, range %.3f m, tolerance %.3f m\n", r.z_min_m, r.z_max_m, r.max_range_m,
              r.tolerance_m);
}

}  // namespace sonarmap::cli

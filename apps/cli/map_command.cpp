#include "map_command.hpp"

#include <chrono>
#include <memory>
#include <cstdio>
#include <numbers>

#include "progress.hpp"
#include "sonarmap/eval/tank_quality.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/sonar/log_reader.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/png_writer.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap::cli {

Command addMapCommand(CLI::App& app, MapArgs& args) {
  CLI::App* cmd = app.add_subcommand("map", "Map a sonar log (.mat) into an occupancy octree (.bt)");
  cmd->add_option("input", args.input, "Sonar log: CRAS Micron .mat")->required();
  cmd->add_option("-o,--output", args.output_bt, "Output map, OctoMap binary tree (.bt)")->required();
  cmd->add_option("--png", args.map_png, "Top view of the map at z = 0 (PNG)");
  cmd->add_option("--polar-png", args.polar_png, "Polar image of the last full sweep (PNG)");
  cmd->add_option("--cartesian-png", args.cartesian_png, "Cartesian image of the last full sweep (PNG)");
  cmd->add_option("--resolution", args.resolution_m, "Voxel edge in metres")->capture_default_str();
  cmd->add_option("--detector", args.detector,
                  "background | threshold | canny | cfar-ca | cfar-so | cfar-go | cfar-os (CFAR along each beam)")
      ->capture_default_str();
  cmd->add_option("--smoothing", args.smoothing, "gaussian | median | mean | none")->capture_default_str();
  cmd->add_option("--ray", args.ray, "dda | bresenham")->capture_default_str();
  cmd->add_option("--aggregation", args.aggregation, "Inner nodes: max | mean")->capture_default_str();
  cmd->add_option("--self-reflection", args.self_reflection_m, "Ignore echoes nearer than this (m)")->capture_default_str();
  cmd->add_option("--beam-width", args.beam_width_deg,
                  "Horizontal beam width in degrees: each beam clears its wedge; 0 = one ray per beam (the paper)")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", args.quiet, "No progress bar");
  cmd->add_flag("--tank-report", args.tank_report,
                "Also print how well the occupied cells at z = 0 trace a rectangular tank's walls");
  auto options = std::make_shared<MapperOptions>();
  return {cmd, [&args, options] { *options = toMapperOptions(args); }, [&args, options] { runMap(args, *options); }};
}

MapperOptions toMapperOptions(const MapArgs& args) {
  MapperOptions options;
  options.resolution_m = args.resolution_m;
  selectDetector(options.detector, args.detector);
  options.smoothing.kind = parseSmoothing(args.smoothing);
  options.ray = parseRayAlgorithm(args.ray);
  if (args.aggregation == "max") {
    options.octree.aggregation = InnerAggregation::kMax;
  } else if (args.aggregation == "mean") {
    options.octree.aggregation = InnerAggregation::kMean;
  } else {
    throw ValueError("unknown aggregation '" + args.aggregation + "', expected max or mean");
  }
  options.self_reflection_range_m = args.self_reflection_m;
  if (!(args.beam_width_deg >= 0.0 && args.beam_width_deg < 180.0)) {
    throw ValueError("beam width must be within [0, 180) degrees");
  }
  options.beam_width_rad = args.beam_width_deg * std::numbers::pi / 180.0;
  options.validate();
  return options;
}

namespace {

/// The polar image of the largest (last, on ties) sweep: the one drawn in the PNGs.
PolarImage lastFullSweep(const SonarLog& log) {
  const std::vector<SweepRange> sweeps = splitSweeps(log.beams);
  if (sweeps.empty()) throw ValueError("the log holds no beams to draw");
  const SweepRange* best = &sweeps.front();
  for (const SweepRange& sweep : sweeps) {
    if (sweep.size() >= best->size()) best = &sweep;
  }
  return makePolarImage(log.beams, best->first, best->last_exclusive);
}

/// Stages every output; nothing appears unless all of them could be written.
void writeOutputs(const MapArgs& args, const SonarLog& log, const OcTree16& map, double pixel_m) {
  FileTransaction outputs;
  outputs.stage(args.output_bt, [&](std::ostream& out) { writeBinary(map, out); });
  if (!args.map_png.empty()) outputs.stageBytes(args.map_png, encodePng(renderSlice(map, 0.0)));
  if (!args.polar_png.empty() || !args.cartesian_png.empty()) {
    const PolarImage polar = lastFullSweep(log);
    if (!args.polar_png.empty()) outputs.stageBytes(args.polar_png, encodePng(polar.intensities));
    if (!args.cartesian_png.empty()) {
      // With single rays (width 0) the image still spreads each beam over the Micron's 3°.
      const double width_deg = args.beam_width_deg > 0.0 ? args.beam_width_deg : 3.0;
      const cv::Mat cartesian = makeCartesianImage(polar, pixel_m, width_deg * std::numbers::pi / 180.0);
      outputs.stageBytes(args.cartesian_png, encodePng(cartesian));
    }
  }
  outputs.commit();
}

void printTankReport(const OcTree16& map) {
  const std::size_t occupied = cellsInSlice(map, 0.0, Occupancy::kOccupied).size();
  if (occupied < 8) {
    std::printf("tank: %zu occupied cells at z = 0, too few to fit walls\n", occupied);
    return;
  }
  const TankMapQuality quality = evaluateTankMap(map, 0.0);
  const WallFitReport& walls = quality.walls;
  std::printf("tank: %.2f x %.2f m at %.1f deg, %zu occupied cells, %.3f on walls, %.3f of walls covered, "
              "rms %.3f m, inside %.3f free %.4f occupied\n",
              walls.rect.width_m, walls.rect.height_m, walls.rect.angle_rad * 180.0 / std::numbers::pi,
              quality.occupied_cells, walls.share_on_walls, walls.wall_coverage, walls.rms_wall_distance_m,
              quality.interior_free_share, quality.interior_occupied_share);
}

}  // namespace

void runMap(const MapArgs& args, const MapperOptions& options) {
  using Clock = std::chrono::steady_clock;
  const SonarLog log = readSonarLog(args.input);
  const auto start = Clock::now();
  SonarMapper mapper = [&] {
    ProgressBar bar("mapping");
    return mapSonarLog(log, options, [&](std::size_t done, std::size_t total) {
      if (!args.quiet) bar.update(done, total);
    });
  }();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  writeOutputs(args, log, mapper.map(), options.resolution_m);
  const MappingStats& stats = mapper.stats();
  const NodeCounts counts = mapper.map().counts();
  std::printf("%zu beams used, %zu skipped, %zu sweeps, %zu obstacles, %zu map nodes (%zu leaves), %.1f KiB, %.3f s -> %s\n",
              stats.beams_used, stats.beams_skipped + stats.out_of_map, stats.sweeps, stats.obstacles, counts.nodes,
              counts.leaves, static_cast<double>(mapper.map().memoryBytes()) / 1024.0, seconds, args.output_bt.c_str());
  if (args.tank_report) printTankReport(mapper.map());
}

}  // namespace sonarmap::cli

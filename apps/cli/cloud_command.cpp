#include "cloud_command.hpp"

#include "help_groups.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "progress.hpp"
#include "sonarmap/algorithms/point_cloud_insertion.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/io/point_text.hpp"
#include "sonarmap/io/scan_graph.hpp"

namespace sonarmap::cli {
namespace {

bool isScanGraph(const std::string& path) { return std::filesystem::path(path).extension() == ".graph"; }

/// "X,Y,Z" in metres. @throws ValueError when it is not three finite numbers.
Eigen::Vector3d parseOrigin(const std::string& text) {
  std::istringstream in(text);
  Eigen::Vector3d origin;
  char comma1 = 0, comma2 = 0;
  if (!(in >> origin.x() >> comma1 >> origin.y() >> comma2 >> origin.z()) || comma1 != ',' || comma2 != ',' ||
      !(in >> std::ws).eof() || !origin.allFinite()) {
    throw ValueError("--origin must be X,Y,Z in metres (three finite numbers), got '" + text + "'");
  }
  return origin;
}

void check(const CloudArgs& args) {
  if (!std::isfinite(args.resolution_m) || args.resolution_m <= 0.0) {
    throw ValueError("--resolution must be a finite number of metres > 0");
  }
  if (!std::isfinite(args.max_range_m)) throw ValueError("--max-range must be finite");
  if (!args.origin.empty()) {
    if (isScanGraph(args.input)) throw ValueError("--origin is for x y z text clouds; a .graph has its poses");
    parseOrigin(args.origin);
  }
  const std::string extension = std::filesystem::path(args.output).extension().string();
  if (extension != ".bt" && extension != ".ot") throw ValueError("-o must name a .bt or .ot file, got '" + args.output + "'");
}

/// Calls `visit` with each scan to insert: every node of a scan graph (sensor-frame points and
/// poses) as it is read, or one text cloud of world-frame points seen from the given origin (the
/// pose then only places the sensor).
void readScans(const CloudArgs& args, const ScanVisitor& visit) {
  if (isScanGraph(args.input)) return readScanGraph(args.input, visit);
  const Eigen::Vector3d origin = args.origin.empty() ? Eigen::Vector3d::Zero() : parseOrigin(args.origin);
  Scan scan;
  scan.points_m = readPointText(args.input);
  for (Eigen::Vector3d& point : scan.points_m) point -= origin;  // into the sensor frame of a pure translation
  scan.sensor_to_world.translation() = origin;
  visit(std::move(scan), 0, 1);
}

void run(const CloudArgs& args) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  OcTree16 map(args.resolution_m);
  InsertOptions options;
  options.max_range_m = args.max_range_m;
  options.discretize = args.discretize;
  InsertStats total;
  std::size_t scans = 0;
  {
    ProgressBar bar("inserting");
    // Each scan is inserted as soon as it is read, into the world frame in place, and handed
    // over: freed once its rays are traced, before the tree grows. One scan's points are in
    // memory at a time, never the whole file's.
    readScans(args, [&](Scan&& scan, std::size_t index, std::size_t count) {
      PointCloud world = std::move(scan.points_m);
      for (Eigen::Vector3d& p : world) p = scan.sensor_to_world * p;
      total += insertPointCloudParallel(map, std::move(world), scan.sensor_to_world.translation(), options,
                                        args.threads);
      scans = count;
      if (!args.quiet) bar.update(index + 1, count);
    });
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  writeMapFile(map, args.output);
  const NodeCounts counts = map.counts();
  std::printf("%zu points in %zu scans, %zu skipped (non-finite), %zu out of map, %zu map nodes (%zu leaves), %.1f KiB, %.3f s -> %s\n",
              total.points, scans, total.skipped_nonfinite, total.out_of_map, counts.nodes, counts.leaves,
              static_cast<double>(map.memoryBytes()) / 1024.0, seconds, args.output.c_str());
}

}  // namespace

Command addCloudCommand(CLI::App& app, CloudArgs& args) {
  CLI::App* cmd = app.add_subcommand("cloud", "Insert point clouds (.graph, or x y z text) into an occupancy octree");
  cmd->add_option("input", args.input, "OctoMap scan graph (.graph) or x y z text cloud (m)")->required();
  cmd->add_option("-o,--output", args.output, "Output map: .bt (max likelihood) or .ot (log-odds)")
      ->required()
      ->group(help_group::kOutput);
  cmd->add_option("--resolution", args.resolution_m, "Voxel edge in METRES")
      ->capture_default_str()
      ->group(help_group::kMapping);
  cmd->add_option("--max-range", args.max_range_m, "Points beyond this only clear free space (m); < 0: none")
      ->group(help_group::kMapping)
      ->capture_default_str();
  cmd->add_option("--origin", args.origin, "Sensor origin X,Y,Z (m) of a text cloud (default 0,0,0)")
      ->group(help_group::kInput);
  cmd->add_flag("--discretize", args.discretize, "One ray per endpoint voxel (OctoMap's discretize)")
      ->group(help_group::kMapping);
  cmd->add_option("--threads", args.threads, "Threads tracing each scan's rays; the same map for any count")
      ->check(CLI::Range(1U, 64U))
      ->capture_default_str()
      ->group(help_group::kMapping);
  cmd->add_flag("-q,--quiet", args.quiet, "No progress bar")->group(help_group::kOutput);
  return {cmd, [&args] { check(args); }, [&args] { run(args); }};
}

}  // namespace sonarmap::cli

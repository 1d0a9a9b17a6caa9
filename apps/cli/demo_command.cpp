#include "demo_command.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "eval_scoring_file.hpp"
#include "help_groups.hpp"
#include "map_command.hpp"
#include "map_outputs.hpp"
#include "output_dir.hpp"
#include "simulate_command.hpp"
#include "view_command.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"

namespace sonarmap::cli {
namespace {

/// The 3D run's folder inside the demo's output folder.
constexpr const char* k3dFolder = "3d-mission";
/// The 3D run's scoring file (eval_scoring_file.hpp), in its folder.
constexpr const char* kScoringFile = "scoring.json";

void check(const DemoArgs& args) {
  if (std::filesystem::exists(args.output_dir) && !std::filesystem::is_directory(args.output_dir)) {
    throw ValueError("-o must name a folder, '" + args.output_dir + "' is a file");
  }
}

/// `map` with its defaults and every image, writing into `dir` under the name "tank".
MapArgs demoMapArgs(const OutputDir& dir, bool quiet) {
  MapArgs args;
  args.input = dir.file("beams.csv");  // the simulated log written beside the map (the figures' titles)
  args.output_bt = dir.file("tank.bt");
  args.map_png = dir.file("tank.png");
  args.polar_png = dir.file("tank_polar.png");
  args.cartesian_png = dir.file("tank_cartesian.png");
  args.quiet = quiet;
  args.tank_report = true;
  return args;
}

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// The 3D run: the simulator's tilted loop (sim/missions.hpp) with its default mounting, the sonar
/// tilted 25° down, as `sonarmap simulate quay3d --sonar micron --mission tilted-loop` flies it.
const SimulatedMission k3dMission{"micron", "quay3d", "tilted-loop"};
constexpr const char* k3dResolution_m = "0.05";

/// `map --3d` with its defaults at 5 cm, the head's beam widths, and the top view, writing into
/// `dir` (the 3D run's folder) under the name "map"; input and nav_file name the simulated files
/// written beside it (for the command printed to remake the map).
MapArgs demo3dMapArgs(const OutputDir& dir, const MsisHeadOptions& head, bool quiet) {
  MapArgs args;
  args.input = dir.file("beams.csv");
  args.nav_file = dir.file("nav.csv");
  args.output_bt = dir.file("map.bt");
  args.map_png = dir.file("map_top.png");
  args.volume = true;
  args.resolution = k3dResolution_m;
  args.beam_width_deg = head.horizontal_beam_width_rad * kDegPerRad;
  args.vertical_aperture_deg = head.vertical_beam_width_rad * kDegPerRad;
  args.quiet = quiet;
  return args;
}

/// `value` to six significant digits, as the demo's printed eval command gave the poses and the
/// aperture, so the scoring file scores as that command did (a rounding's -7e-15 is 0).
double sixDigits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", std::abs(value) < 1e-9 ? 0.0 : value);
  return std::stod(text);
}

/// The scoring file of the 3D run (eval_scoring_file.hpp), its files named as the 3D run's folder
/// holds them: eval scores the map as docs/accuracy.md does (missionTruthOptions), against what
/// the sonar could see (its poses along the mission as navigation fixes, NED, its vertical aperture
/// and its range) and against the surface its beams heard (the log, the TRUE navigation, the mounting
/// the mission was flown with, the head).
ScoringFile scoringFile(const MissionRun& mission) {
  const GroundTruthOptions truth = missionTruthOptions(mission);
  ScoringFile file;
  file.truth = "scene.txt";
  file.max_range_m = sixDigits(truth.max_range_m.value_or(0.0));
  file.vertical_aperture_deg = sixDigits(truth.vertical_aperture_rad.value_or(0.0) * kDegPerRad);
  const Eigen::Matrix3d map_to_ned = nedToMap().linear().transpose();
  for (std::size_t i = 0; i < truth.sensor_positions_m.size(); ++i) {
    std::array<double, 6> pose =
        mountingOfPose(map_to_ned * truth.sensor_orientations[i], map_to_ned * truth.sensor_positions_m[i]);
    for (double& value : pose) value = sixDigits(value);
    file.sensor_poses.push_back(pose);
  }
  file.heard_by = "beams.csv";
  file.nav = "truth_nav.csv";
  file.mounting = mission.mounting;
  file.sonar = k3dMission.preset;
  return file;
}

/// The line that introduces the 3D run: what was simulated and where it went.
void print3dHeader(const MissionRun& mission, const std::string& folder) {
  // The sonar's bearing 0 in the body frame (z down): its angle below the vehicle's horizontal plane.
  const double tilt_deg = std::asin(std::clamp(mission.options.sonar_to_body.linear()(2, 0), -1.0, 1.0)) * kDegPerRad;
  std::printf("3d: %s flying the %s mission over %s, sonar tilted %.0f deg down, mapped with --3d at %s m -> %s\n",
              k3dMission.preset.c_str(), k3dMission.mission.c_str(), k3dMission.scene.c_str(), tilt_deg,
              k3dResolution_m, folder.c_str());
}


void printRun(const MappedLog& mapped, const MapArgs& args, bool with_nav) {
  const std::vector<std::string> warnings =
      mappingWarnings(mapped.mapper.stats(), mapped.mapper.options(), mapped.mapper.map().resolution_m());
  printWarnings(warnings);
  printMapSummary(mapped, args, with_nav, warnings.size());
}

void run(const DemoArgs& args) {
  MsisSimulationOptions simulation_options;  // static head, 28 turns, seed 1
  simulation_options.nav_rate_hz = 0.0;      // static: the map needs no navigation
  const MsisSimulation simulation = simulateMsis(builtinScene("tank"), simulation_options);
  OutputDir dir(args.output_dir);
  const MapArgs map_args = demoMapArgs(dir, args.quiet);
  const MapperOptions mapper_options = toMapperOptions(map_args);
  const MappedLog mapped = mapWithProgress(
      [&](const ProgressCallback& progress) { return mapSonarLog(simulation.log, mapper_options, progress); },
      args.quiet);

  // The 3D run in its own folder: the moving mission, mapped in 3D as `map --3d --nav` maps it.
  const MissionRun mission = simulateMission(k3dMission);
  const std::string folder_3d = dir.file(k3dFolder);
  OutputDir dir_3d(folder_3d);
  const MapArgs map_args_3d = demo3dMapArgs(dir_3d, mission.options.head, args.quiet);
  const std::string side_png = dir_3d.file("map_side.png");
  const MapperOptions mapper_options_3d = toMapperOptions(map_args_3d);
  const MsisSimulation& simulation_3d = mission.simulation;
  // Mapped as its beams.csv holds it: a bearing written in degrees may read back an ulp away
  // (beam_csv.hpp), and the map command the demo prints must remake the same map.
  std::stringstream beams_csv;
  writeBeamCsv(beams_csv, simulation_3d.log);
  const SonarLog written_3d = readBeamCsv(beams_csv, dir_3d.file("beams.csv"));
  const MappedLog mapped_3d = mapWithProgress(
      [&](const ProgressCallback& progress) {
        return mapSonarLog(written_3d, simulation_3d.nav, mission.options.sonar_to_body, mapper_options_3d, progress);
      },
      args.quiet);

  FileTransaction outputs;
  stageMapOutputs(outputs, map_args, simulation.log, mapped.mapper.map(), mapped.mapper.map().resolution_m(), {},
                  {Eigen::Vector3d::Zero()});  // the static sonar at the map origin
  stageSimulation(outputs, args.output_dir, simulation, map_args.map_frame);
  stageMapOutputs(outputs, map_args_3d, simulation_3d.log, mapped_3d.mapper.map(),
                  mapped_3d.mapper.map().resolution_m(), side_png,
                  sonarTrack(simulation_3d.nav, mission.options.sonar_to_body, simulation_3d.log));
  stageSimulation(outputs, folder_3d, simulation_3d, map_args_3d.map_frame);
  const std::string scoring_json = dir_3d.file(kScoringFile);
  outputs.stage(scoring_json, [&](std::ostream& out) { writeScoringFile(out, scoringFile(mission)); });
  // The 3D viewer's pages (sonarmap view) beside each map, the 3D run's with the vehicle's path;
  // left out, with a warning, by a tool built without three.js.
  if (viewerAvailable()) {
    HtmlViewOptions tank_view;
    tank_view.title = "tank.bt";
    stageView(outputs, dir.file("tank.html"), mapInFrame(mapped.mapper.map(), MapFrame::kEnu), tank_view);
    HtmlViewOptions mission_view;
    mission_view.title = std::string(k3dFolder) + "/map.bt";
    mission_view.trajectory_m = trajectoryInMap(simulation_3d.nav);
    mission_view.trajectory_source = "nav.csv";
    stageView(outputs, dir_3d.file("map.html"), mapInFrame(mapped_3d.mapper.map(), MapFrame::kEnu), mission_view);
  } else {
    printWarnings({"this sonarmap was built without three.js: no tank.html, no 3d-mission/map.html"});
  }
  outputs.commit();
  dir.keep();
  dir_3d.keep();
  printRun(mapped, map_args, false);
  printTankReport(mapped.mapper.map());
  std::printf("tank: score it:  sonarmap eval %s --truth %s\n", map_args.output_bt.c_str(),
              dir.file("scene.txt").c_str());
  print3dHeader(mission, folder_3d);
  printRun(mapped_3d, map_args_3d, true);
  std::printf("3d: score it (docs/accuracy.md):  sonarmap eval %s --scoring %s\n", map_args_3d.output_bt.c_str(),
              scoring_json.c_str());
}

}  // namespace

Command addDemoCommand(CLI::App& app, DemoArgs& args) {
  CLI::App* cmd = app.add_subcommand("demo", "Simulate a tank and a 3D mission, map and score them (needs no data)");
  cmd->add_option("-o,--output", args.output_dir, "Output folder (created when missing)")
      ->required()
      ->group(help_group::kOutput);
  cmd->add_flag("-q,--quiet", args.quiet, "No progress bar")->group(help_group::kOutput);
  return {cmd, [&args] { check(args); }, [&args] { run(args); }};
}

}  // namespace sonarmap::cli

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

/// x,y,z,roll,pitch,yaw of a pose (rotation `r`, translation `t`): metres, then the Z-Y-X Euler
/// angles of r = Rz(yaw)·Ry(pitch)·Rx(roll) in degrees: the form of map --mounting and eval
/// --sensor-pose.
std::string poseText(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  std::array<double, 6> pose = mountingOfPose(r, t);
  for (double& value : pose) value = std::abs(value) < 1e-9 ? 0.0 : value;  // rounding, not a pose: -7e-15°
  char text[160];
  std::snprintf(text, sizeof text, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g", pose[0], pose[1], pose[2], pose[3], pose[4], pose[5]);
  return text;
}

/// The eval options that score the map as docs/accuracy.md does (missionTruthOptions): the
/// sonar's poses along the mission and its vertical aperture, for the field-of-view check, and its
/// range, which also bounds where the truth is sought.
std::string fieldOfViewOptions(const MissionRun& mission) {
  const GroundTruthOptions truth = missionTruthOptions(mission);
  char aperture[64];
  std::snprintf(aperture, sizeof aperture, "--vertical-aperture %.6g --max-range %.6g",
                truth.vertical_aperture_rad.value_or(0.0) * kDegPerRad, truth.max_range_m.value_or(0.0));
  std::string options = aperture;
  for (std::size_t i = 0; i < truth.sensor_positions_m.size(); ++i) {
    // --sensor-pose is a navigation fix (NED) of the sonar, as eval reads it.
    const Eigen::Matrix3d map_to_ned = nedToMap().linear().transpose();
    options += " --sensor-pose " + poseText(map_to_ned * truth.sensor_orientations[i], map_to_ned * truth.sensor_positions_m[i]);
  }
  return options;
}

/// The line that introduces the 3D run: what was simulated and where it went.
void print3dHeader(const MissionRun& mission, const std::string& folder) {
  // The sonar's bearing 0 in the body frame (z down): its angle below the vehicle's horizontal plane.
  const double tilt_deg = std::asin(std::clamp(mission.options.sonar_to_body.linear()(2, 0), -1.0, 1.0)) * kDegPerRad;
  std::printf("3d: %s flying the %s mission over %s, sonar tilted %.0f deg down, mapped with --3d at %s m -> %s\n",
              k3dMission.preset.c_str(), k3dMission.mission.c_str(), k3dMission.scene.c_str(), tilt_deg,
              k3dResolution_m, folder.c_str());
}

/// The lines that tell the user how to score the 3D run's map (against the scene, what the sonar
/// could see, and the surface its beams heard, from the log and the true navigation `truth_nav`) and
/// how to make it again.
void print3dCommands(const MapArgs& map_args, const std::string& side_png, const std::string& scene,
                     const std::string& truth_nav, const MissionRun& mission) {
  // The numbers the mission's mounting was built from, exactly: the map command rebuilds the same pose.
  const std::string mounting_text = mountingText(mission.mounting);
  const char* mounting = mounting_text.c_str();
  std::printf("3d: score it:  sonarmap eval %s --truth %s\n", map_args.output_bt.c_str(), scene.c_str());
  std::printf("3d: score what the sonar could see (docs/accuracy.md):  sonarmap eval %s --truth %s %s\n",
              map_args.output_bt.c_str(), scene.c_str(), fieldOfViewOptions(mission).c_str());
  std::printf("3d: score it against the surface its beams heard (docs/accuracy.md):  sonarmap eval %s --truth %s "
              "--heard-by %s --nav %s --mounting %s --sonar %s\n",
              map_args.output_bt.c_str(), scene.c_str(), map_args.input.c_str(), truth_nav.c_str(), mounting,
              k3dMission.preset.c_str());
  std::printf("3d: simulate it again:  sonarmap simulate %s --sonar %s --mission %s --seed %llu -o DIR\n",
              k3dMission.scene.c_str(), k3dMission.preset.c_str(), k3dMission.mission.c_str(),
              static_cast<unsigned long long>(k3dMission.seed));
  std::printf("3d: map it again:  sonarmap map %s --nav %s --mounting %s --3d --resolution %s "
              "--beam-width %g --vertical-aperture %g -o %s --png %s --side-png %s\n",
              map_args.input.c_str(), map_args.nav_file.c_str(), mounting,
              map_args.resolution.c_str(), map_args.beam_width_deg, map_args.vertical_aperture_deg,
              map_args.output_bt.c_str(), map_args.map_png.c_str(), side_png.c_str());
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
  stageSimulation(outputs, args.output_dir, simulation);
  stageMapOutputs(outputs, map_args_3d, simulation_3d.log, mapped_3d.mapper.map(),
                  mapped_3d.mapper.map().resolution_m(), side_png,
                  sonarTrack(simulation_3d.nav, mission.options.sonar_to_body, simulation_3d.log));
  stageSimulation(outputs, folder_3d, simulation_3d);
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
  print3dHeader(mission, folder_3d);
  printRun(mapped_3d, map_args_3d, true);
  print3dCommands(map_args_3d, side_png, dir_3d.file("scene.txt"), dir_3d.file("truth_nav.csv"), mission);
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

#include "simulate_command.hpp"

#include "help_groups.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "map_options.hpp"
#include "output_dir.hpp"
#include "sonarmap/formats/mcap_writer.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "progress.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/geodetic.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/missions.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"
#include "sonarmap/formats/beam_csv.hpp"

namespace sonarmap::cli {
namespace {

namespace fs = std::filesystem;

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// A built-in name wins over a file of the same name (write ./tank for the file).
/// @throws ValueError (usage) when `scene` is neither a built-in name nor an existing file.
void checkScene(const std::string& scene) {
  if (isBuiltinSceneName(scene) || fs::exists(scene)) return;
  throw ValueError("unknown scene '" + scene + "': neither a built-in scene (" + joined(allBuiltinSceneNames(), ", ") +
                   ") nor a scene file");
}

/// `sonarmap map` of the run written in args.output_dir: its beams with nav.csv, the mounting it was
/// simulated with (simulationMounting's numbers, printed exactly, so that the map rebuilds the same
/// pose), the head's beam widths (a beam CSV does not name its sonar), and --3d in a 3D scene.
std::string mapCommand(const SimulateArgs& args, const MsisHeadOptions& head) {
  const std::array<double, 6> mounting = simulationMounting(args);
  const fs::path dir(args.output_dir);
  const std::vector<std::string> scenes_3d = builtinScene3dNames();
  const bool volume = std::find(scenes_3d.begin(), scenes_3d.end(), args.scene) != scenes_3d.end();
  std::string frame_flag;  // the map in the frame of scene.txt
  if (args.map_frame != kDefaultMapFrame) {
    frame_flag = " --map-frame " + std::string(mapFrameName(args.map_frame));
    std::transform(frame_flag.begin(), frame_flag.end(), frame_flag.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  }
  char text[1024];
  std::snprintf(text, sizeof text,
                "sonarmap map %s --nav %s --mounting %s --beam-width %g --vertical-aperture %g%s%s -o %s",
                (dir / "beams.csv").string().c_str(), (dir / "nav.csv").string().c_str(), mountingText(mounting).c_str(),
                head.horizontal_beam_width_rad * kDegPerRad, head.vertical_beam_width_rad * kDegPerRad,
                volume ? " --3d" : "", frame_flag.c_str(),
                (dir / "map.bt").string().c_str());
  return text;
}

void check(const SimulateArgs& args, MsisSimulationOptions& options) {
  checkScene(args.scene);
  if (!args.geo_origin.empty()) {
    parseGeodeticPoint(args.geo_origin);
    if (args.bag.empty()) throw ValueError("--geo-origin writes NavSatFix messages into the bag: give --bag too");
  }
  checkMissionScene(args, args.scene);
  if (fs::exists(args.output_dir) && !fs::is_directory(args.output_dir)) {
    throw ValueError("-o must name a folder, '" + args.output_dir + "' is a file");
  }
  options = toSimulationOptions(args, args.scene);
}

/// A vehicle without a DVL as ArduSub reports it (LOCAL_POSITION_NED absent, the bridges' pose at
/// north and east 0): the believed track keeps its heading, attitude and depth, its north and east
/// are 0. The truth stays in truth_nav.csv.
void withoutPosition(MsisSimulation& simulation) {
  if (simulation.dead_reckoning.empty()) simulation.dead_reckoning = simulation.nav;
  for (NavSample& fix : simulation.dead_reckoning) fix.position_ned_m.head<2>().setZero();
}

void run(const SimulateArgs& args, const MsisSimulationOptions& options) {
  const MsisHeadOptions& head = options.head;
  const Scene scene = sceneOf(args.scene, head);
  MsisSimulation simulation = [&] {
    ProgressBar bar("simulating");
    return simulateMsis(scene, options, [&](std::size_t done, std::size_t total) {
      if (!args.quiet) bar.update(done, total);
    });
  }();
  if (args.no_position) {
    if (simulation.nav.empty()) throw ValueError("--no-position shapes the navigation, and --nav-rate 0 writes none");
    withoutPosition(simulation);
  }
  OutputDir dir(args.output_dir);
  FileTransaction outputs;
  stageSimulation(outputs, args.output_dir, simulation, args.map_frame);
  const NavTrack& believed = simulation.dead_reckoning.empty() ? simulation.nav : simulation.dead_reckoning;
  if (!args.mcap.empty()) outputs.stageBytes(args.mcap, mcapBytes(simulation.log, believed));
  if (!args.bag.empty()) {
    // the sonar's mounting on /tf_static, so that `map FILE.bag` needs no --mounting
    RosBagWriteOptions bag;
    bag.raw_sensors = true;
    if (!believed.empty()) bag.sonar_to_body = options.sonar_to_body;
    if (!args.geo_origin.empty()) {
      // the written track's positions on the Earth, as a positioning system would give them
      if (simulation.nav.empty()) throw ValueError("--geo-origin needs a moving vehicle (--speed or --mission): a static run has no fixes");
      bag.geodetic_origin = parseGeodeticPoint(args.geo_origin);
    }
    outputs.stageBytes(args.bag, rosBagBytes(simulation.log, believed, bag));
  }
  outputs.commit();
  dir.keep();
  char turns[64] = "turns";
  if (head.isSector()) std::snprintf(turns, sizeof turns, "passes across a %g deg sector", args.sector_deg);
  std::printf("%s: %zu beams in %zu %s, %zu nav fixes, %zu scene primitives -> %s\n", args.sonar.c_str(),
              simulation.log.beams.size(), options.turns, turns, simulation.nav.size(),
              simulation.scene.primitives.size(), args.output_dir.c_str());
  if (!args.mission.empty() && !simulation.nav.empty()) {
    const double speed_mps = args.speed_mps > 0.0 ? args.speed_mps : defaultMissionSpeed_mps(args.mission, head.range_m);
    const MissionPlan plan = missionPlan(args.mission, head.range_m, speed_mps, args.laps);
    std::printf("mission %s: %zu lap(s), %.1f m in %.1f s\n", plan.name.c_str(), args.laps, plan.length_m,
                plan.duration_s);
  }
  if (!simulation.dead_reckoning.empty()) {
    const Eigen::Vector3d drift_m =
        simulation.dead_reckoning.back().position_ned_m - simulation.nav.back().position_ned_m;
    std::printf("nav.csv: dead reckoning, %.3f m from the truth at the end; truth_nav.csv: the true track\n",
                drift_m.norm());
  } else if (!simulation.nav.empty()) {
    std::printf("nav.csv, truth_nav.csv: the true track\n");
  }
  // A mission or a mounting: the map needs the navigation and the mounting, named in full.
  if (!simulation.nav.empty() && (!args.mission.empty() || !args.mounting.empty())) {
    std::printf("map it:  %s\n", mapCommand(args, head).c_str());
  }
}

}  // namespace

std::string joined(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

void addVehiclePathOptions(CLI::App& cmd, SimulationArguments& args) {
  cmd.add_option("--speed", args.speed_mps, "Vehicle speed in M/S (0: static, or the mission's)")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd.add_option("--heading", args.heading_deg, "Vehicle heading in degrees cw from north (not with --mission)")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd.add_option("--depth", args.depth_m, "Vehicle depth in METRES, NED (not with --mission)")
      ->group(help_group::kNavigation);
  cmd.add_option("--mission", args.mission, "Fly a named mission: " + joined(missionNames(), " | "))
      ->group(help_group::kNavigation);
  cmd.add_option("--laps", args.laps, "Times the mission is flown")->capture_default_str()->group(help_group::kNavigation);
  addMountingOption(cmd, args.mounting, "");
}

std::string sonarPresetHelp(const std::string& lead) {
  std::string help = lead;
  for (const std::string& name : sonarPresetNames()) help += (help == lead ? " " : " | ") + name;
  return help;
}

void stageSimulation(FileTransaction& outputs, const std::string& dir, const MsisSimulation& run,
                     MapFrame scene_frame) {
  const fs::path folder(dir);
  outputs.stage((folder / "scene.txt").string(), [&](std::ostream& out) { writeScene(out, run.scene, scene_frame); });
  outputs.stage((folder / "beams.csv").string(), [&](std::ostream& out) { writeBeamCsv(out, run.log); });
  if (!run.nav.empty()) {
    const NavTrack& believed = run.dead_reckoning.empty() ? run.nav : run.dead_reckoning;
    outputs.stage((folder / "nav.csv").string(), [&](std::ostream& out) { writeNavCsv(out, believed); });
    outputs.stage((folder / "truth_nav.csv").string(), [&](std::ostream& out) { writeNavCsv(out, run.nav); });
  }
}

Command addSimulateCommand(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Simulate a scanning sonar in a scene: beams.csv, nav.csv, truth_nav.csv, scene.txt");
  cmd->add_option("scene", args.scene, "Built-in scene (" + joined(allBuiltinSceneNames(), " | ") + ") or scene file")
      ->required();
  cmd->add_option("-o,--output", args.output_dir, "Output folder (created when missing)")
      ->required()
      ->group(help_group::kOutput);
  cmd->add_option("--sonar", args.sonar, sonarPresetHelp("Head preset:"))
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--sector", args.sector_deg, "Scanned sector's width in degrees, (0, 360]")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--sector-center", args.sector_center_deg, "Sector's centre bearing in degrees from ahead, cw")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--seed", args.seed, "Seed of the speckle and noise (same seed, same files)")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--turns", args.turns, "Full turns of the head, or passes across a sector")
      ->capture_default_str()
      ->group(help_group::kInput);
  addVehiclePathOptions(*cmd, args);
  cmd->add_option("--dvl-noise", args.dvl_noise_mps, "Dead reckoning: DVL velocity noise sigma per fix (m/s)")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd->add_option("--dvl-scale-error", args.dvl_scale_error, "Dead reckoning: DVL scale error, a fraction (0.02 = 2 %)")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd->add_option("--heading-bias", args.heading_bias_deg, "Dead reckoning: compass heading bias (degrees)")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd->add_option("--gyro-walk", args.gyro_walk_deg_per_sqrt_s, "Dead reckoning: heading random walk (deg/sqrt(s))")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd->add_option("--nav-rate", args.nav_rate_hz, "Navigation fixes per second in nav.csv (Hz; 0: none)")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd->add_flag("--no-position", args.no_position,
                "Dead reckoning without a DVL: nav.csv and --bag/--mcap hold heading, attitude and depth, north and east 0")
      ->group(help_group::kNavigation);
  cmd->add_option("--bag", args.bag, "Also write the log as a ROS 1 bag (.bag)")->group(help_group::kOutput);
  cmd->add_option("--geo-origin", args.geo_origin,
                 "With --bag: the NED zero on the Earth, DEGREES; each fix also written as a NavSatFix on /gps/fix")
      ->type_name("LAT,LON[,H]")
      ->group(help_group::kOutput);
  cmd->add_option("--mcap", args.mcap, "Also write the log as a ROS 2 log in MCAP (.mcap)")->group(help_group::kOutput);
  addMapFrameOption(*cmd, args.map_frame, "Frame scene.txt is written in (map it in the same)");
  cmd->add_flag("-q,--quiet", args.quiet, "No progress bar")->group(help_group::kOutput);
  auto options = std::make_shared<MsisSimulationOptions>();
  return {cmd, [&args, options] { check(args, *options); }, [&args, options] { run(args, *options); }};
}

}  // namespace sonarmap::cli

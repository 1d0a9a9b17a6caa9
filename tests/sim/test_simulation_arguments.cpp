// SimulationArguments (sim/simulation_arguments.hpp): `sonarmap simulate`'s arguments, shared with
// the Python module's simulate.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {
namespace {

TEST(simSimulationArguments, PresetSectorAndTrajectory) {
  SimulationArguments args;
  args.sonar = "micron";
  args.sector_deg = 90.0;
  args.sector_center_deg = 45.0;
  args.turns = 3;
  args.seed = 9;
  args.speed_mps = 0.5;
  args.heading_deg = 90.0;
  const MsisSimulationOptions options = toSimulationOptions(args);
  EXPECT_DOUBLE_EQ(options.head.range_m, sonarPreset("micron").head.range_m);
  EXPECT_NEAR(options.head.sector_width_rad, std::numbers::pi / 2.0, 1e-12);
  EXPECT_NEAR(options.head.sector_center_rad, std::numbers::pi / 4.0, 1e-12);
  EXPECT_EQ(options.turns, 3U);
  EXPECT_EQ(options.seed, 9U);
  const NavSample later = options.trajectory(2.0);  // heading east at 0.5 m/s
  EXPECT_NEAR(later.position_ned_m.y(), 1.0, 1e-9);
  EXPECT_NEAR(later.position_ned_m.x(), 0.0, 1e-9);
  args.sector_deg = 360.0;
  EXPECT_NEAR(toSimulationOptions(args).head.sector_width_rad, 2.0 * std::numbers::pi, 1e-15);
  // The depth: the built-in scene's unless given (quay3d: 3 m at 5 m range, its surface at depth 0).
  EXPECT_EQ(later.position_ned_m.z(), 0.0);
  EXPECT_EQ(toSimulationOptions(args, "tank").trajectory(2.0).position_ned_m.z(), 0.0);
  EXPECT_EQ(toSimulationOptions(args, "quay3d").trajectory(2.0).position_ned_m.z(), 3.0);
  EXPECT_EQ(toSimulationOptions(args, "my_scene.txt").trajectory(2.0).position_ned_m.z(), 0.0);
  args.sonar = "seaking-30";
  EXPECT_NEAR(toSimulationOptions(args, "quay3d").trajectory(2.0).position_ned_m.z(), 18.0, 1e-9);
  args.depth_m = 1.5;
  EXPECT_EQ(toSimulationOptions(args, "quay3d").trajectory(2.0).position_ned_m.z(), 1.5);
}

TEST(simSimulationArguments, BadValuesNameTheOption) {
  SimulationArguments args;
  args.turns = 0;
  EXPECT_THROW(toSimulationOptions(args), ValueError);
  args = {};
  args.sector_deg = 400.0;
  EXPECT_THROW(toSimulationOptions(args), ValueError);
  args = {};
  args.speed_mps = NAN;
  EXPECT_THROW(toSimulationOptions(args), ValueError);
  args = {};
  args.sonar = "sonar-9000";
  EXPECT_THROW(toSimulationOptions(args), ValueError);
  args = {};
  args.depth_m = INFINITY;
  EXPECT_THROW(toSimulationOptions(args), ValueError);
}

TEST(simSimulationArguments, SceneByNameOrFile) {
  const MsisHeadOptions head = sonarPreset("micron").head;
  EXPECT_TRUE(isBuiltinSceneName("tank"));
  EXPECT_TRUE(isBuiltinSceneName("quay3d"));
  EXPECT_FALSE(isBuiltinSceneName("lake"));
  EXPECT_EQ(sceneOf("tank", head).primitives.size(),
            builtinScene("tank", head.range_m, head.vertical_beam_width_rad).primitives.size());
  EXPECT_THROW(sceneOf("lake", head), ValueError);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "sonarmap_test_scene_of.txt";
  {
    std::ofstream out(file);
    out << "plane 0 0 -1 0 0 1 1\n";
  }
  EXPECT_EQ(sceneOf(file.string(), head).primitives.size(), 1U);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace sonarmap

// End-to-end tests of `sonarmap cloud`: OctoMap's scan graph and x y z text clouds into .bt/.ot
// maps that OctoMap 1.9 reads (test-only dependency), with the CLI's error contract.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

const fs::path kScanGraph = fs::path(SONARMAP_SHARED_DATA) / "octomap_spherical_scan.graph";

#define SKIP_WITHOUT_SCAN_GRAPH() \
  if (!fs::exists(kScanGraph)) GTEST_SKIP() << "shared data absent: " << kScanGraph

using cliCloud = CliTest;

TEST_F(cliCloud, ScanGraphToBtThatOctoMapReadsWithTheSameNodes) {
  SKIP_WITHOUT_SCAN_GRAPH();
  const fs::path bt = out_ / "scan.bt";
  const ProgramRun result = run({"cloud", kScanGraph.string(), "-o", bt.string(), "--resolution", "0.05", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const Names lines = linesOf(result.out);
  ASSERT_EQ(lines.size(), 1U) << result.out;
  std::size_t points = 0, scans = 0, skipped = 0, outside = 0, nodes = 0;
  ASSERT_EQ(std::sscanf(lines[0].c_str(), "%zu points in %zu scans, %zu skipped (non-finite), %zu out of map, %zu map nodes",
                        &points, &scans, &skipped, &outside, &nodes),
            5)
      << lines[0];
  EXPECT_EQ(points, 10201U);
  EXPECT_EQ(scans, 1U);
  EXPECT_EQ(skipped, 0U);

  // The reference: OctoMap inserting the same scan builds a tree of the same size.
  octomap::OcTree reference(0.05);
  octomap::ScanGraph graph;
  ASSERT_TRUE(graph.readBinary(kScanGraph.string()));
  for (octomap::ScanNode* node : graph) reference.insertPointCloud(*node);
  octomap::OcTree ours(0.1);
  ASSERT_TRUE(ours.readBinary(bt.string()));
  EXPECT_DOUBLE_EQ(ours.getResolution(), 0.05);
  EXPECT_EQ(nodes, reference.size());
  reference.toMaxLikelihood();
  reference.prune();
  EXPECT_EQ(ours.size(), reference.size());
  EXPECT_EQ(ours.getNumLeafNodes(), reference.getNumLeafNodes());
}

TEST_F(cliCloud, OtKeepsTheLogOdds) {
  SKIP_WITHOUT_SCAN_GRAPH();
  const fs::path ot = out_ / "scan.ot";
  const ProgramRun result = run({"cloud", kScanGraph.string(), "-o", ot.string(), "--max-range", "3", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::unique_ptr<octomap::AbstractOcTree> tree(octomap::AbstractOcTree::read(ot.string()));
  auto* octree = dynamic_cast<octomap::OcTree*>(tree.get());
  ASSERT_NE(octree, nullptr);
  std::size_t fractional = 0;  // log-odds other than the clamping values: only an .ot keeps them
  for (auto it = octree->begin_leafs(); it != octree->end_leafs(); ++it) {
    const float l = it->getLogOdds();
    fractional += (std::abs(l - octree->getClampingThresMaxLog()) > 1e-4 && std::abs(l - octree->getClampingThresMinLog()) > 1e-4) ? 1 : 0;
  }
  EXPECT_GT(fractional, 100U);
}

TEST_F(cliCloud, TextCloudWithOriginSkipsNonFinitePoints) {
  writeFile(root_ / "cloud.txt", "# x y z\n1 0 0\nnan 0 0\n0 1 0\n0 0 1\n");
  const fs::path ot = out_ / "cloud.ot";
  const ProgramRun result =
      run({"cloud", (root_ / "cloud.txt").string(), "-o", ot.string(), "--origin", "0,0,0.5", "--discretize", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("4 points in 1 scans, 1 skipped (non-finite)"), std::string::npos) << result.out;
  std::unique_ptr<octomap::AbstractOcTree> tree(octomap::AbstractOcTree::read(ot.string()));
  auto* octree = dynamic_cast<octomap::OcTree*>(tree.get());
  ASSERT_NE(octree, nullptr);
  // Points are world frame; the origin only starts the rays: (0, 0, 1) is the last point.
  octomap::OcTreeNode* hit = octree->search(0.0, 0.0, 1.0);
  ASSERT_NE(hit, nullptr);
  EXPECT_TRUE(octree->isNodeOccupied(hit));
  octomap::OcTreeNode* free = octree->search(0.0, 0.0, 0.75);
  ASSERT_NE(free, nullptr);
  EXPECT_FALSE(octree->isNodeOccupied(free));
}

TEST_F(cliCloud, ThreadsGiveTheSameMapByteForByte) {
  // 4,000 points on a tilted 3 m sphere with a bump, half of them past the 2.5 m range limit, so
  // that both hit and clipped rays are split between the threads (256 rays a thread at least).
  std::string text;
  for (int i = 0; i < 4000; ++i) {
    const double azimuth = 0.0157 * i, elevation = std::asin(-0.95 + 1.9 * ((i * 37) % 4000) / 4000.0);
    const double range = 2.0 + (i % 2) * 1.0 + 0.1 * std::sin(5.0 * azimuth);
    char line[96];
    std::snprintf(line, sizeof line, "%.6f %.6f %.6f\n", range * std::cos(elevation) * std::cos(azimuth),
                  range * std::cos(elevation) * std::sin(azimuth), 0.3 + range * std::sin(elevation));
    text += line;
  }
  writeFile(root_ / "cloud.txt", text);
  std::string first;
  for (const char* threads : {"1", "2", "4"}) {
    const fs::path ot = out_ / (std::string("map") + threads + ".ot");
    const ProgramRun result = run({"cloud", (root_ / "cloud.txt").string(), "-o", ot.string(), "--max-range", "2.5",
                                   "--resolution", "0.04", "--threads", threads, "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const std::string bytes = readFile(ot);
    ASSERT_GT(bytes.size(), 10000U);
    if (first.empty()) {
      first = bytes;
    } else {
      EXPECT_TRUE(bytes == first) << threads << " threads gave another map";
    }
  }
}

TEST_F(cliCloud, UsageErrorsExitTwoAndWriteNothing) {
  writeFile(root_ / "cloud.txt", "1 0 0\n");
  const std::string input = (root_ / "cloud.txt").string();
  const std::string out = (out_ / "map.bt").string();
  for (const Names& args : {Names{"cloud", input, "-o", (out_ / "map.png").string()},
                            Names{"cloud", input, "-o", out, "--resolution", "0"},
                            Names{"cloud", input, "-o", out, "--origin", "1,2"},
                            Names{"cloud", input, "-o", out, "--origin", "a,b,c"},
                            Names{"cloud", input, "-o", out, "--threads", "0"},
                            Names{"cloud", input}}) {
    expectError(run(args), 2);
  }
  if (fs::exists(kScanGraph)) expectError(run({"cloud", kScanGraph.string(), "-o", out, "--origin", "0,0,0"}), 2);
  EXPECT_TRUE(listDir(out_).empty());
}

TEST_F(cliCloud, DataErrorsExitOneAndWriteNothing) {
  writeFile(root_ / "bad.txt", "1 0 0\n1 2\n");
  writeFile(root_ / "bad.graph", "not a graph");
  for (const char* input : {"bad.txt", "bad.graph", "missing.txt"}) {
    expectError(run({"cloud", (root_ / input).string(), "-o", (out_ / "map.ot").string()}), 1);
  }
  EXPECT_TRUE(listDir(out_).empty());
}

}  // namespace
}  // namespace sonarmap::test

namespace sonarmap::test {
namespace {

// `sonarmap` runs `cloud` and a bare `--version` with what it links itself and hands every other
// command to the full tool next to it (build tree) or in ../libexec/sonarmap (installed): a copy of
// it alone in a folder maps a cloud to the same bytes as the full tool, and names the full tool it
// lacks for anything else.
TEST_F(cliCloud, LeanToolMapsCloudsAloneAndHandsOtherCommandsToTheFullTool) {
  writeFile(root_ / "cloud.txt", "1 0 0\n0 1.5 0\n0 0 2\n-1 -1 -1\n");
  const fs::path alone = root_ / "alone";
  fs::create_directory(alone);
  fs::copy_file(SONARMAP_CLI, alone / "sonarmap");
  const ProgramRun lean = runProgram((alone / "sonarmap").string(),
                                     {"cloud", (root_ / "cloud.txt").string(), "-o", (out_ / "lean.bt").string(), "-q"}, root_);
  ASSERT_EQ(lean.exit_code, 0) << lean.err;
  const fs::path full_tool = fs::path(SONARMAP_CLI).parent_path() / "sonarmap-full";
  const ProgramRun full = runProgram(full_tool.string(),
                                     {"cloud", (root_ / "cloud.txt").string(), "-o", (out_ / "full.bt").string(), "-q"}, root_);
  ASSERT_EQ(full.exit_code, 0) << full.err;
  EXPECT_EQ(readFile(out_ / "lean.bt"), readFile(out_ / "full.bt"));
  EXPECT_EQ(runProgram((alone / "sonarmap").string(), {"--version"}, root_).out,
            runProgram(full_tool.string(), {"--version"}, root_).out);

  const ProgramRun other = runProgram((alone / "sonarmap").string(), {"info", (out_ / "lean.bt").string()}, root_);
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_EQ(other.err.rfind("sonarmap: error: the full sonarmap tool is missing: tried " + (alone / "sonarmap-full").string(), 0), 0U)
      << other.err;
  EXPECT_EQ(std::count(other.err.begin(), other.err.end(), '\n'), 1) << other.err;
}

}  // namespace
}  // namespace sonarmap::test

// OctoMap's own test scan (../shared/data/octomap_spherical_scan.graph) through both libraries:
// our reader and insertPointCloud against OctoMap's ScanGraph and insertPointCloud, at 5 cm and
// 2 cm. The maps must agree on ≥ 99.9 % of the known volume and write files the other
// library reads with identical leaves.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "octomap_reference.hpp"
#include "sonarmap/algorithms/point_cloud_insertion.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/io/scan_graph.hpp"

namespace sonarmap {
namespace {

using namespace sonarmap::testing;

const std::string kScanGraph = std::string(SONARMAP_SHARED_DATA) + "/octomap_spherical_scan.graph";

class algorithmsScanGraphParity : public ::testing::TestWithParam<double> {};

TEST_P(algorithmsScanGraphParity, SameMapAsOctomapFromTheSameFile) {
  if (!std::filesystem::exists(kScanGraph)) GTEST_SKIP() << kScanGraph << " not found";
  const double resolution_m = GetParam();
  OcTree16 ours(resolution_m);
  for (const Scan& scan : readScanGraph(kScanGraph)) insertScan(ours, scan);
  octomap::ScanGraph graph;
  ASSERT_TRUE(graph.readBinary(kScanGraph));
  octomap::OcTree theirs(resolution_m);
  for (octomap::ScanNode* node : graph) theirs.insertPointCloud(*node);

  const VoxelAgreement agreement = compareWithOctomap(ours, theirs);
  std::printf("[parity] spherical scan graph, res %.2f: %s\n", resolution_m, agreement.summary().c_str());
  EXPECT_GE(agreement.agreement(), 0.999) << agreement.summary();
  EXPECT_EQ(agreement.differ, 0U) << "no voxel free in one map and occupied in the other";
  // Float rounding in OctoMap's DDA moves a handful of voxels at 2 cm: node counts agree to 0.01 %.
  EXPECT_NEAR(static_cast<double>(ours.counts().nodes), static_cast<double>(theirs.size()), 1e-4 * theirs.size());

  // Their reader finds our map in our .bt, leaf for leaf.
  std::stringstream bt;
  writeBinary(ours, bt);
  octomap::OcTree read_back(0.1);
  ASSERT_TRUE(read_back.readBinary(bt));
  EXPECT_EQ(read_back.size(), ours.counts().nodes);
  EXPECT_EQ(read_back.getNumLeafNodes(), ours.counts().leaves);
}

INSTANTIATE_TEST_SUITE_P(algorithms, algorithmsScanGraphParity, ::testing::Values(0.05, 0.02),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return info.param > 0.03 ? std::string("res5cm") : std::string("res2cm");
                         });

}  // namespace
}  // namespace sonarmap

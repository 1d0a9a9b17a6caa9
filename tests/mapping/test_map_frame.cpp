// The frame maps are written in (mapping/map_frame.hpp): an echo known in NED lands at (e, n, −d)
// in an ENU map and at (n, e, d) in a NED map, exactly, pruned leaves included; map files name
// their frame in the header and read back into the internal frame.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {
namespace {

constexpr double kRes = 0.1;

/// An internal (NWU) map with an occupied voxel at each NED position, placed as the mapper places
/// echoes (nedToMap), and a pruned free cube of 8³ voxels.
OcTree16 mapOfNedEchoes(const std::vector<Eigen::Vector3d>& echoes_ned) {
  OcTree16 map(kRes);
  for (const Eigen::Vector3d& ned : echoes_ned) map.updateNode(map.coder().keyOfChecked(nedToMap() * ned), 2.0F);
  map.updateCube(map.coder().keyOfChecked(Eigen::Vector3d(-3.0, 2.0, 1.0)), 13, -1.0F);  // 8 voxels per edge
  map.updateInnerOccupancy();
  return map;
}


std::map<std::tuple<unsigned, unsigned, unsigned, int>, float> leavesOf(const OcTree16& map) {
  std::map<std::tuple<unsigned, unsigned, unsigned, int>, float> leaves;
  map.forEachLeaf([&](const LeafView<16>& leaf) { leaves[{leaf.key[0], leaf.key[1], leaf.key[2], leaf.depth}] = leaf.log_odds; });
  return leaves;
}

TEST(MapFrame, NedEchoIsAtEastNorthUpInEnuAndAsItIsInNed) {
  const std::vector<Eigen::Vector3d> echoes = {{4.23, -1.37, 2.96}, {-0.55, 7.81, 0.04}, {12.04, 3.33, -1.27}};
  const OcTree16 nwu = mapOfNedEchoes(echoes);
  const OcTree16 enu = mapInFrame(nwu, MapFrame::kEnu);
  const OcTree16 ned = mapInFrame(nwu, MapFrame::kNed);
  for (const Eigen::Vector3d& p : echoes) {
    SCOPED_TRACE(p.transpose());
    const Eigen::Vector3d at_enu(p.y(), p.x(), -p.z());
    EXPECT_EQ(enu.occupancyAt(at_enu), Occupancy::kOccupied);
    EXPECT_EQ(ned.occupancyAt(p), Occupancy::kOccupied);
    // The voxel holding the echo, not a neighbour: its centre is within half a voxel per axis.
    const Eigen::Vector3d centre = enu.coder().centerOf(enu.coder().keyOfChecked(at_enu));
    EXPECT_LE((centre - at_enu).cwiseAbs().maxCoeff(), kRes / 2 + 1e-12);
    // Nothing where an NWU frame would put it, nor at the unconverted position.
    EXPECT_NE(enu.occupancyAt(nedToMap() * p), Occupancy::kOccupied);
    EXPECT_NE(ned.occupancyAt(nedToMap() * p), Occupancy::kOccupied);
  }
  // The free cube stays one pruned leaf of the same size, its voxels negated or swapped exactly.
  EXPECT_EQ(enu.counts().leaves, nwu.counts().leaves);
  EXPECT_EQ(ned.counts().leaves, nwu.counts().leaves);
  EXPECT_EQ(enu.occupancyAt(nwuToMapFrame(MapFrame::kEnu) * Eigen::Vector3d(-3.0 + 0.35, 2.0 + 0.35, 1.0 + 0.35)),
            Occupancy::kFree);
}

TEST(MapFrame, ConversionIsExactAndInvertible) {
  const OcTree16 nwu = mapOfNedEchoes({{1.02, 2.07, 3.01}, {-4.05, 0.03, 0.95}});
  for (MapFrame frame : {MapFrame::kEnu, MapFrame::kNed}) {
    SCOPED_TRACE(std::string(mapFrameName(frame)));
    EXPECT_EQ(leavesOf(mapFromFrame(mapInFrame(nwu, frame), frame)), leavesOf(nwu));
    // Every leaf's centre is the rotated centre of a leaf of the internal map, with its log-odds.
    const OcTree16 out = mapInFrame(nwu, frame);
    std::size_t matched = 0;
    nwu.forEachLeaf([&](const LeafView<16>& leaf) {
      const double half = leaf.edgeVoxels() * kRes / 2;
      const Eigen::Vector3d centre = nwu.coder().centerOf(leaf.key) - Eigen::Vector3d::Constant(kRes / 2 - half);
      const Eigen::Vector3d moved = nwuToMapFrame(frame) * centre;
      const std::optional<float> found = out.search(out.coder().keyOfChecked(moved), leaf.depth);
      ASSERT_TRUE(found.has_value());
      EXPECT_EQ(*found, leaf.log_odds);
      ++matched;
    });
    EXPECT_EQ(matched, nwu.counts().leaves);
  }
}

TEST(MapFrame, NamesParseAndRefuse) {
  EXPECT_EQ(parseMapFrame("enu"), MapFrame::kEnu);
  EXPECT_EQ(parseMapFrame("NED"), MapFrame::kNed);
  EXPECT_THROW(parseMapFrame("nwu"), ValueError);
  EXPECT_THROW(parseMapFrame("xyz"), ValueError);
  EXPECT_EQ(kDefaultMapFrame, MapFrame::kEnu);
  EXPECT_EQ(mapFrameDescription(MapFrame::kEnu), "ENU (x east, y north, z up)");
}

TEST(MapFrame, FileHeaderNamesTheFrameAndReadsBackIntoTheInternalFrame) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sonarmap_test_map_frame";
  std::filesystem::create_directories(dir);
  const OcTree16 nwu = mapOfNedEchoes({{2.03, -1.07, 0.52}});
  for (const char* name : {"m.bt", "m.ot"}) {
    for (MapFrame frame : {MapFrame::kEnu, MapFrame::kNed}) {
      SCOPED_TRACE(std::string(name) + " " + std::string(mapFrameName(frame)));
      const std::string path = (dir / name).string();
      writeMapFileInFrame(nwu, path, frame);
      std::ifstream in(path, std::ios::binary);
      std::string first, second, third;
      std::getline(in, first);
      std::getline(in, second);
      std::getline(in, third);
      EXPECT_EQ(third, "# sonarmap map frame: " + mapFrameDescription(frame));
      EXPECT_EQ(mapFrameOfComments(readMapFileHeader(path).comments), frame);
      const FramedMap back = readMapFileToNwu(path);
      EXPECT_EQ(back.frame, frame);
      EXPECT_EQ(back.map.occupancyAt(nedToMap() * Eigen::Vector3d(2.03, -1.07, 0.52)), Occupancy::kOccupied);
      EXPECT_EQ(readMapFile(path).occupancyAt(nwuToMapFrame(frame) * nedToMap() * Eigen::Vector3d(2.03, -1.07, 0.52)),
                Occupancy::kOccupied);
    }
    // A file whose header names no frame is taken as the internal frame.
    const std::string plain = (dir / name).string();
    writeMapFile(nwu, plain);
    EXPECT_EQ(mapFrameOfComments(readMapFileHeader(plain).comments), std::nullopt);
    EXPECT_EQ(readMapFileToNwu(plain).frame, MapFrame::kNwu);
  }
  std::filesystem::remove_all(dir);
}

// A map mapped about a local origin (UTM) names it in its header, so it can be placed back; the
// voxels are the same.
TEST(MapFrame, FileHeaderNamesTheLocalOriginAndReadsItBack) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sonarmap_test_map_origin";
  std::filesystem::create_directories(dir);
  const OcTree16 nwu = mapOfNedEchoes({{2.03, -1.07, 0.52}});
  const Eigen::Vector3d origin_ned_m(4'600'123.25, 500'456.5, -0.75);
  const std::string path = (dir / "utm.bt").string();
  writeMapFileInFrame(nwu, path, MapFrame::kEnu, origin_ned_m);
  const FramedMap back = readMapFileToNwu(path);
  EXPECT_EQ(back.origin_ned_m, origin_ned_m);  // exactly: 17 significant digits
  EXPECT_EQ(back.map.occupancyAt(nedToMap() * Eigen::Vector3d(2.03, -1.07, 0.52)), Occupancy::kOccupied);
  // Near zero no line is written and the origin reads as zero.
  writeMapFileInFrame(nwu, path, MapFrame::kEnu);
  EXPECT_EQ(mapHeaderComments(MapFrame::kEnu, Eigen::Vector3d::Zero()),
            std::vector<std::string>{mapFrameComment(MapFrame::kEnu)});
  for (const std::string& comment : readMapFileHeader(path).comments) EXPECT_FALSE(comment.starts_with("sonarmap map origin"));
  EXPECT_EQ(readMapFileToNwu(path).origin_ned_m, Eigen::Vector3d::Zero());
  EXPECT_THROW(mapOriginOfComments({"sonarmap map origin: 4600000 east 0 m"}), ValueError);
  EXPECT_THROW(mapOriginOfComments({"sonarmap map origin: nan 0 0 m"}), ValueError);
  std::filesystem::remove_all(dir);
}

// The line gives the origin to 0.1 mm on the Earth, without an estimate's rounding noise, and
// reads back within that.
TEST(MapFrame, GeodeticOriginLineIsRoundedToATenthOfAMillimetre) {
  GeodeticPoint zero;
  zero.latitude_deg = 43.29460000000012;
  zero.longitude_deg = -5.3655;
  zero.height_m = -0.00002;
  const std::string line = mapGeodeticComment(zero);
  EXPECT_TRUE(line.starts_with("sonarmap geodetic origin: 43.2946 -5.3655 0 (latitude")) << line;
  const std::optional<GeodeticPoint> back = geodeticOriginOfComments({"other", line});
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->latitude_deg, zero.latitude_deg, 1e-9);
  EXPECT_NEAR(back->longitude_deg, zero.longitude_deg, 1e-9);
  EXPECT_NEAR(back->height_m, zero.height_m, 1e-4);
  zero.latitude_deg = -89.123456789;
  zero.height_m = 12.34567;
  EXPECT_TRUE(mapGeodeticComment(zero).starts_with("sonarmap geodetic origin: -89.123456789 -5.3655 12.3457 ("));
}

}  // namespace
}  // namespace sonarmap

// .graph scan graphs: OctoMap's own sample file, our writer read by OctoMap 1.9 (liboctomap-dev,
// test-only), OctoMap's writer read by us, round trips and malformed files.
#include <gtest/gtest.h>

#include <octomap/ScanGraph.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <thread>

#include <sys/stat.h>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/scan_graph.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

const fs::path kSphericalScan = fs::path(SONARMAP_SHARED_DATA) / "octomap_spherical_scan.graph";

/// A few scans with random poses; one has no points.
std::vector<Scan> sampleScans() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-5.0, 5.0);
  std::vector<Scan> scans(3);
  for (std::size_t n = 0; n < scans.size(); ++n) {
    for (std::size_t p = 0; p < (n == 1 ? 0 : 50 + 20 * n); ++p) scans[n].points_m.emplace_back(coord(rng), coord(rng), coord(rng));
    const Eigen::Quaterniond q = Eigen::Quaterniond(coord(rng), coord(rng), coord(rng), coord(rng)).normalized();
    scans[n].sensor_to_world.linear() = q.toRotationMatrix();
    scans[n].sensor_to_world.translation() = Eigen::Vector3d(coord(rng), coord(rng), coord(rng));
  }
  return scans;
}

std::string graphBytes(const std::vector<Scan>& scans) {
  std::ostringstream out;
  writeScanGraph(out, scans);
  return out.str();
}

std::vector<Scan> parse(const std::string& bytes) {
  std::istringstream in(bytes);
  return readScanGraph(in, "test.graph");
}

void putU32(std::string& bytes, std::size_t at, std::uint32_t value) { std::memcpy(&bytes[at], &value, 4); }
void putF64(std::string& bytes, std::size_t at, double value) { std::memcpy(&bytes[at], &value, 8); }
void appendU32(std::string& bytes, std::uint32_t value) { bytes.append(reinterpret_cast<const char*>(&value), 4); }
void appendF64(std::string& bytes, double value) { bytes.append(reinterpret_cast<const char*>(&value), 8); }

/// An edge record: ids, identity pose, weight.
std::string edgeBytes(std::uint32_t first, std::uint32_t second) {
  std::string edge;
  appendU32(edge, first);
  appendU32(edge, second);
  appendU32(edge, 3);
  for (int i = 0; i < 3; ++i) appendF64(edge, 0.5);
  appendU32(edge, 4);
  for (double v : {1.0, 0.0, 0.0, 0.0}) appendF64(edge, v);
  appendF64(edge, 1.0);
  return edge;
}

/// Graph with one node of two points and `edges` appended: the layout's offsets are fixed.
/// node count 0, point count 4, point markers 8 and 36 (x at 12, 40), translation marker 64,
/// tx 68, quaternion marker 92, qw 96 … qz 120, id 128, edge count 132, edges from 136.
std::string smallGraph(const std::vector<std::string>& edges = {}) {
  Scan scan;
  scan.points_m = {{1.0, 2.0, 3.0}, {-1.0, 0.5, 0.25}};
  scan.sensor_to_world.translation() = Eigen::Vector3d(0.1, 0.2, 0.3);
  std::string bytes = graphBytes({scan});
  putU32(bytes, 132, static_cast<std::uint32_t>(edges.size()));
  for (const std::string& edge : edges) bytes += edge;
  return bytes;
}

/// `bytes` fail with `message_part` both from a stream and from a file read by its path (a
/// regular file is parsed through a mapping, readScanGraph(const std::string&)).
void expectFileError(const std::string& bytes, const std::string& message_part) {
  const TempDir dir;
  const std::string path = dir.file("test.graph");
  std::ofstream(path, std::ios::binary) << bytes;
  for (const bool by_path : {false, true}) {
    try {
      by_path ? readScanGraph(path) : parse(bytes);
      ADD_FAILURE() << "no FileError; expected one mentioning '" << message_part << "'" << (by_path ? " (by path)" : "");
    } catch (const FileError& error) {
      EXPECT_NE(std::string(error.what()).find(message_part), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("test.graph: byte "), std::string::npos) << error.what();
    }
  }
}

Eigen::Vector3d fromOctomap(const octomap::point3d& p) { return {p.x(), p.y(), p.z()}; }

TEST(ioScanGraph, ReadsOctoMapsSphericalScan) {
  if (!fs::exists(kSphericalScan)) GTEST_SKIP() << "no shared data at " << kSphericalScan;
  EXPECT_EQ(fs::file_size(kSphericalScan), 285708U);
  const std::vector<Scan> scans = readScanGraph(kSphericalScan.string());
  ASSERT_EQ(scans.size(), 1U);
  EXPECT_EQ(scans[0].points_m.size(), 10201U);
  EXPECT_TRUE(scans[0].sensor_to_world.translation().isApprox(Eigen::Vector3d(1.0, 0.0, -0.5)));
  EXPECT_TRUE(scans[0].sensor_to_world.linear().isIdentity(1e-12));

  // OctoMap reads the same points (it keeps float32; the file holds those floats as float64).
  octomap::ScanGraph theirs;
  ASSERT_TRUE(theirs.readBinary(kSphericalScan.string()));
  ASSERT_EQ(theirs.size(), 1U);
  const octomap::Pointcloud& cloud = *(*theirs.begin())->scan;
  ASSERT_EQ(cloud.size(), scans[0].points_m.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) ASSERT_EQ(static_cast<float>(scans[0].points_m[i][axis]), cloud[i](axis));
  }
}

TEST(ioScanGraph, RoundTripKeepsPointsAndPoses) {
  const TempDir dir;
  const std::vector<Scan> scans = sampleScans();
  writeScanGraph(dir.file("round.graph"), scans);
  EXPECT_EQ(fs::file_size(dir.file("round.graph")), 4 + 3 * (4 + 64 + 4) + (50 + 90) * 28U + 4);
  const std::vector<Scan> back = readScanGraph(dir.file("round.graph"));
  ASSERT_EQ(back.size(), scans.size());
  for (std::size_t n = 0; n < scans.size(); ++n) {
    EXPECT_EQ(back[n].points_m, scans[n].points_m);  // float64 both ways: exact
    EXPECT_TRUE(back[n].sensor_to_world.isApprox(scans[n].sensor_to_world, 1e-12));
  }
}

TEST(ioScanGraph, APipeReadsAsTheFileDoes) {
  const TempDir dir;
  const std::string bytes = graphBytes(sampleScans());
  const std::string fifo = dir.file("scans.graph");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << bytes; });
  const std::vector<Scan> piped = readScanGraph(fifo);  // not a regular file: read as a stream
  writer.join();
  std::ofstream(dir.file("file.graph"), std::ios::binary) << bytes;
  const std::vector<Scan> mapped = readScanGraph(dir.file("file.graph"));
  ASSERT_EQ(piped.size(), mapped.size());
  for (std::size_t n = 0; n < mapped.size(); ++n) {
    EXPECT_EQ(piped[n].points_m, mapped[n].points_m);
    EXPECT_TRUE(piped[n].sensor_to_world.isApprox(mapped[n].sensor_to_world, 0.0));
  }
  EXPECT_EQ(mapped.size(), 3U);
}

TEST(ioScanGraph, ScanByScanVisitsEachScanInOrderBeforeTheNext) {
  const TempDir dir;
  const std::vector<Scan> scans = sampleScans();
  writeScanGraph(dir.file("scans.graph"), scans);
  for (const bool by_path : {true, false}) {
    std::vector<std::size_t> visited;
    std::vector<Scan> got;
    const ScanVisitor visit = [&](Scan&& scan, std::size_t index, std::size_t count) {
      EXPECT_EQ(count, scans.size());
      visited.push_back(index);
      got.push_back(std::move(scan));
    };
    if (by_path) {
      readScanGraph(dir.file("scans.graph"), visit);
    } else {
      std::istringstream in(graphBytes(scans));
      readScanGraph(in, visit, "test.graph");
    }
    EXPECT_EQ(visited, (std::vector<std::size_t>{0, 1, 2})) << (by_path ? "by path" : "stream");
    ASSERT_EQ(got.size(), scans.size());
    for (std::size_t n = 0; n < scans.size(); ++n) EXPECT_EQ(got[n].points_m, scans[n].points_m);
  }
}

TEST(ioScanGraph, ScanByScanThrowsForABadEdgeAfterTheScans) {
  const TempDir dir;
  const std::string path = dir.file("test.graph");
  std::ofstream(path, std::ios::binary) << smallGraph({edgeBytes(0, 7)});
  std::size_t visited = 0;
  EXPECT_THROW(readScanGraph(path, [&](Scan&&, std::size_t, std::size_t) { ++visited; }), FileError);
  EXPECT_EQ(visited, 1U);  // the scan came first; the caller has written nothing yet
  // What the visitor throws reaches the caller, and no later scan is read.
  writeScanGraph(dir.file("three.graph"), sampleScans());
  visited = 0;
  EXPECT_THROW(readScanGraph(dir.file("three.graph"),
                             [&](Scan&&, std::size_t, std::size_t) {
                               ++visited;
                               throw ValueError("stop");
                             }),
               ValueError);
  EXPECT_EQ(visited, 1U);
}

TEST(ioScanGraph, OctoMapReadsOurGraph) {
  const TempDir dir;
  const std::vector<Scan> scans = sampleScans();
  writeScanGraph(dir.file("ours.graph"), scans);
  octomap::ScanGraph theirs;
  ASSERT_TRUE(theirs.readBinary(dir.file("ours.graph")));
  ASSERT_EQ(theirs.size(), scans.size());
  std::size_t n = 0;
  for (const octomap::ScanNode* node : theirs) {
    EXPECT_EQ(node->id, n);
    ASSERT_EQ(node->scan->size(), scans[n].points_m.size());
    for (std::size_t i = 0; i < node->scan->size(); ++i) {
      const Eigen::Vector3d point = scans[n].points_m[i];
      EXPECT_TRUE(fromOctomap((*node->scan)[i]).isApprox(point, 1e-6));
      // Same pose: OctoMap's transform of the point equals ours.
      const Eigen::Vector3d world = fromOctomap(node->pose.transform((*node->scan)[i]));
      EXPECT_LT((world - scans[n].sensor_to_world * point).norm(), 1e-4);
    }
    ++n;
  }
}

TEST(ioScanGraph, WeReadOctoMapsGraphWithEdges) {
  const TempDir dir;
  octomap::ScanGraph theirs;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coord(-3.0F, 3.0F);
  for (int n = 0; n < 3; ++n) {
    auto* cloud = new octomap::Pointcloud();  // the graph owns it
    for (int i = 0; i < 100 + n; ++i) cloud->push_back(coord(rng), coord(rng), coord(rng));
    theirs.addNode(cloud, octomap::pose6d(1.0F * n, 2.0F, -0.5F, 0.1 * n, -0.2, 0.3 * n));
    if (n > 0) theirs.connectPrevious();
  }
  ASSERT_TRUE(theirs.writeBinary(dir.file("theirs.graph")));

  const std::vector<Scan> ours = readScanGraph(dir.file("theirs.graph"));
  ASSERT_EQ(ours.size(), theirs.size());
  std::size_t n = 0;
  for (const octomap::ScanNode* node : theirs) {
    ASSERT_EQ(ours[n].points_m.size(), node->scan->size());
    for (std::size_t i = 0; i < node->scan->size(); ++i) {
      ASSERT_EQ(ours[n].points_m[i], fromOctomap((*node->scan)[i]));  // floats widened: exact
      const Eigen::Vector3d world = fromOctomap(node->pose.transform((*node->scan)[i]));
      EXPECT_LT((world - ours[n].sensor_to_world * ours[n].points_m[i]).norm(), 1e-5);
    }
    ++n;
  }
}

TEST(ioScanGraph, TruncatedAtEveryOffsetThrowsFileError) {
  const std::string bytes = smallGraph({edgeBytes(0, 0)});
  ASSERT_EQ(bytes.size(), 136U + 80U);
  EXPECT_EQ(parse(bytes).size(), 1U);
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    EXPECT_THROW(parse(bytes.substr(0, size)), FileError) << "truncated to " << size << " bytes";
  }
  expectFileError(bytes + "x", "unexpected bytes after the last edge");
  expectFileError(smallGraph().substr(0, 20), "byte 4: node count declares 1 (72 bytes each) but only 16 bytes are left");
  expectFileError(smallGraph().substr(0, 2), "byte 0: file ends, expected node count (4 bytes, 2 left)");
  expectFileError(smallGraph().substr(0, 134), "byte 132: file ends, expected edge count");
}

TEST(ioScanGraph, HugeDeclaredCountsThrowBeforeAllocating) {
  std::string bytes = smallGraph();
  putU32(bytes, 0, 1000000000U);
  expectFileError(bytes, "node count declares 1000000000");
  bytes = smallGraph();
  putU32(bytes, 4, 0xFFFFFFFFU);  // ~120 GB of points claimed
  expectFileError(bytes, "point count of node 0 declares 4294967295");
  bytes = smallGraph();
  putU32(bytes, 132, 50000000U);
  expectFileError(bytes, "edge count declares 50000000");
  bytes = smallGraph();
  putU32(bytes, 4, 3);  // one point more than there is: the pose no longer fits
  expectFileError(bytes, "point count of node 0 declares 3");
}

TEST(ioScanGraph, WrongMarkersAndValuesThrowFileError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::string bytes = smallGraph();
  putU32(bytes, 36, 2);
  expectFileError(bytes, "byte 36: size marker of point 1 of node 0 is 2, expected 3");
  bytes = smallGraph();
  putU32(bytes, 64, 4);
  expectFileError(bytes, "byte 64: size marker of translation of pose of node 0 is 4");
  bytes = smallGraph();
  putU32(bytes, 92, 3);
  expectFileError(bytes, "byte 92: size marker of rotation of pose of node 0 is 3, expected 4");
  bytes = smallGraph();
  putF64(bytes, 40, nan);
  expectFileError(bytes, "byte 40: x of point 1 of node 0 is nan");
  bytes = smallGraph();
  putF64(bytes, 68, std::numeric_limits<double>::infinity());
  expectFileError(bytes, "byte 68: x of translation of pose of node 0 is inf");
  bytes = smallGraph();
  putF64(bytes, 96, 0.0);  // zero quaternion
  expectFileError(bytes, "byte 92: rotation of pose of node 0 has norm 0.000000");
  bytes = smallGraph();
  putF64(bytes, 96, 2.0);
  expectFileError(bytes, "expected a unit quaternion");
  bytes = smallGraph();
  putF64(bytes, 96, 1.0 + 1e-5);  // unit-ish: normalised
  EXPECT_TRUE(parse(bytes)[0].sensor_to_world.linear().isIdentity(1e-12));
  expectFileError(smallGraph({edgeBytes(0, 7)}), "byte 140: second node id of edge 0 is 7, not the id of a node");
  std::string edge = edgeBytes(0, 0);
  putF64(edge, 72, nan);
  expectFileError(smallGraph({edge}), "weight of edge 0 is nan");
  expectFileError("", "expected node count");
  EXPECT_THROW(readScanGraph("/nonexistent/x.graph"), FileError);
}

TEST(ioScanGraph, RandomCorruptionThrowsOnlyLibraryErrors) {
  const std::string good = smallGraph({edgeBytes(0, 0)});
  std::mt19937 rng(1);
  for (int trial = 0; trial < 3000; ++trial) {
    std::string bytes = good;
    for (int flips = 1 + trial % 4; flips > 0; --flips) bytes[rng() % bytes.size()] = static_cast<char>(rng());
    try {
      parse(bytes);
    } catch (const Error&) {  // FileError; anything else (or a crash) fails the test
    }
  }
}

TEST(ioScanGraph, WriterRejectsNonFiniteValuesAndWritesNothing) {
  const TempDir dir;
  std::vector<Scan> scans = sampleScans();
  scans[2].points_m[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(writeScanGraph(dir.file("bad.graph"), scans), ValueError);
  EXPECT_FALSE(fs::exists(dir.file("bad.graph")));
  scans = sampleScans();
  scans[0].sensor_to_world.translation().x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(writeScanGraph(dir.file("bad.graph"), scans), ValueError);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 0);
  EXPECT_THROW(writeScanGraph("/nonexistent-dir/x.graph", sampleScans()), FileError);
}

}  // namespace
}  // namespace sonarmap

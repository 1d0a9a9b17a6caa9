#include "bench_cloud_workloads.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <numbers>
#include <optional>

#include <octomap/math/Utils.h>

#include "../tests/algorithms/octomap_reference.hpp"  // compareWithOctomap, leavesOf (header only)
#include "sonarmap/algorithms/point_cloud_insertion.hpp"
#include "sonarmap/io/scan_graph.hpp"

#ifndef SONARMAP_SHARED_DATA
#define SONARMAP_SHARED_DATA "../shared/data"
#endif

namespace sonarmap::bench {
namespace {

octomap::point3d toO(const Eigen::Vector3d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}
Eigen::Vector3d fromO(const octomap::point3d& p) { return {p.x(), p.y(), p.z()}; }

/// Adds one world-frame scan (points already float-representable) to the world/OctoMap lists.
void addWorldScan(CloudWorkload& w, PointCloud points, const Eigen::Vector3d& origin_m) {
  octomap::Pointcloud cloud;
  cloud.reserve(points.size());
  for (const Eigen::Vector3d& p : points) cloud.push_back(toO(p));
  w.points += points.size();
  w.world.push_back(std::move(points));
  w.origins.push_back(origin_m);
  w.world_o.push_back(std::move(cloud));
  w.origins_o.push_back(toO(origin_m));
}

/// Ray ends clipped at the range limit, as both insertions clip them (traversal rows only).
void clipRayEnds(CloudWorkload& w) {
  for (std::size_t s = 0; s < w.world.size(); ++s) {
    PointCloud ends;
    octomap::Pointcloud ends_o;
    for (std::size_t i = 0; i < w.world[s].size(); ++i) {
      Eigen::Vector3d end = w.world[s][i];
      octomap::point3d end_o = w.world_o[s][i];
      if (w.max_range_m >= 0.0) {
        const double range = (end - w.origins[s]).norm();
        if (range > w.max_range_m) end = w.origins[s] + (end - w.origins[s]) * (w.max_range_m / range);
        const double range_o = (end_o - w.origins_o[s]).norm();
        if (range_o > w.max_range_m) {
          end_o = w.origins_o[s] + (end_o - w.origins_o[s]).normalized() * static_cast<float>(w.max_range_m);
        }
      }
      ends.push_back(end);
      ends_o.push_back(end_o);
    }
    w.ray_ends.push_back(std::move(ends));
    w.ray_ends_o.push_back(std::move(ends_o));
  }
}

std::unique_ptr<CloudWorkload> loadGraph(double resolution_m, std::string& error) {
  const char* folder = std::getenv("SONARMAP_DATA");
  const std::filesystem::path base = (folder != nullptr && *folder != '\0') ? folder : SONARMAP_SHARED_DATA;
  const std::string path = (base / "octomap_spherical_scan.graph").string();
  if (!std::filesystem::exists(path)) {
    error = "data file absent: " + path + " (set SONARMAP_DATA to its folder)";
    return nullptr;
  }
  auto w = std::make_unique<CloudWorkload>();
  w->resolution_m = resolution_m;
  w->posed = true;
  try {
    w->scans = readScanGraph(path);
  } catch (const std::exception& e) {
    error = e.what();
    return nullptr;
  }
  w->graph = std::make_unique<octomap::ScanGraph>();
  if (!w->graph->readBinary(path) || w->graph->size() != w->scans.size()) {
    error = "OctoMap could not read " + path;
    return nullptr;
  }
  for (const Scan& scan : w->scans) {
    PointCloud world;
    for (const Eigen::Vector3d& p : scan.points_m) world.push_back(scan.sensor_to_world * p);
    w->points += world.size();
    w->world.push_back(std::move(world));
    w->origins.push_back(scan.sensor_to_world.translation());
  }
  for (const octomap::ScanNode* node : *w->graph) {
    octomap::Pointcloud cloud(*node->scan);
    cloud.transform(node->pose);
    w->world_o.push_back(std::move(cloud));
    w->origins_o.push_back(node->pose.trans());
  }
  clipRayEnds(*w);
  return w;
}

/// OctoMap's InsertScan test (octomap/src/testing/unit_tests.cpp), its points generated with
/// OctoMap's own rotations so that they are the very same floats.
std::unique_ptr<CloudWorkload> makeSphere() {
  auto w = std::make_unique<CloudWorkload>();
  const octomap::point3d origin(0.01F, 0.01F, 0.02F);
  octomap::point3d point_on_surface(2.01F, 0.01F, 0.01F);
  PointCloud points;
  for (int i = 0; i < 360; ++i) {
    for (int j = 0; j < 360; ++j) {
      points.push_back(fromO(origin + point_on_surface));
      point_on_surface.rotate_IP(0, 0, DEG2RAD(1.));
    }
    point_on_surface.rotate_IP(0, DEG2RAD(1.), 0);
  }
  addWorldScan(*w, std::move(points), fromO(origin));
  clipRayEnds(*w);
  return w;
}

/// A corridor [-10.007, 9.993] × [-2.011, 1.989] × [-1.509, 1.491] m (walls off the voxel
/// boundaries) seen from 10 positions 2 m apart along its axis: 512 azimuths × 200 elevations
/// (±85°) per scan, range to the nearest wall plus uniform noise of ±1 cm (an LCG, so the cloud is
/// the same on every platform), max range 10 m: the far ends of the corridor are out of range.
std::unique_ptr<CloudWorkload> makeRoom() {
  auto w = std::make_unique<CloudWorkload>();
  w->max_range_m = 10.0;
  const Eigen::Vector3d lo(-10.007, -2.011, -1.509), hi(9.993, 1.989, 1.491);
  std::uint32_t seed = 271828;
  const auto noise = [&seed] {
    seed = seed * 1664525U + 1013904223U;
    return ((seed >> 8) / 16777216.0 - 0.5) * 0.02;
  };
  constexpr int kScans = 10, kAzimuths = 512, kElevations = 200;
  for (int s = 0; s < kScans; ++s) {
    const Eigen::Vector3d origin = fromO(toO({-9.0 + 2.0 * s + 0.013, 0.017, 0.023}));
    PointCloud points;
    points.reserve(kAzimuths * kElevations);
    for (int a = 0; a < kAzimuths; ++a) {
      const double azimuth = 2.0 * std::numbers::pi * (a + 0.5) / kAzimuths;
      for (int e = 0; e < kElevations; ++e) {
        const double elevation = (-85.0 + 170.0 * (e + 0.5) / kElevations) * std::numbers::pi / 180.0;
        const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                std::sin(elevation));
        double range = 1e9;
        for (int axis = 0; axis < 3; ++axis) {
          if (d[axis] > 1e-12) range = std::min(range, (hi[axis] - origin[axis]) / d[axis]);
          if (d[axis] < -1e-12) range = std::min(range, (lo[axis] - origin[axis]) / d[axis]);
        }
        points.push_back(fromO(toO(origin + d * (range + noise()))));
      }
    }
    addWorldScan(*w, std::move(points), origin);
  }
  clipRayEnds(*w);
  return w;
}

struct Loaded {
  std::unique_ptr<CloudWorkload> workload;
  std::string error;
};

Loaded load(CloudId id) {
  Loaded loaded;
  switch (id) {
    case CloudId::kGraph5cm: loaded.workload = loadGraph(0.05, loaded.error); break;
    case CloudId::kGraph2cm: loaded.workload = loadGraph(0.02, loaded.error); break;
    case CloudId::kSphere5cm: loaded.workload = makeSphere(); break;
    case CloudId::kRoom5cm: loaded.workload = makeRoom(); break;
  }
  return loaded;
}

}  // namespace

const CloudWorkload* cloudOrSkip(benchmark::State& state, CloudId id) {
  static std::array<std::optional<Loaded>, kCloudWorkloads> cache;
  std::optional<Loaded>& slot = cache[static_cast<std::size_t>(id)];
  if (!slot) slot = load(id);
  if (!slot->workload) state.SkipWithError(slot->error.c_str());
  return slot->workload.get();
}

void insertSonarmap(OcTree16& map, const CloudWorkload& w) {
  InsertOptions options;
  options.max_range_m = w.max_range_m;
  if (w.posed) {
    for (const Scan& scan : w.scans) insertScan(map, scan, options);
  } else {
    for (std::size_t s = 0; s < w.world.size(); ++s) insertPointCloud(map, w.world[s], w.origins[s], options);
  }
}

void insertOctomap(octomap::OcTree& tree, const CloudWorkload& w) {
  if (w.posed) {
    for (const octomap::ScanNode* node : *w.graph) tree.insertPointCloud(*node, w.max_range_m);
  } else {
    for (std::size_t s = 0; s < w.world_o.size(); ++s) {
      tree.insertPointCloud(w.world_o[s], w.origins_o[s], w.max_range_m);
    }
  }
}

void insertSonarmapParallel(OcTree16& map, const CloudWorkload& w, unsigned threads, PointCloud& buffer) {
  InsertOptions options;
  options.max_range_m = w.max_range_m;
  if (w.posed) {
    for (const Scan& scan : w.scans) {
      buffer.clear();
      for (const Eigen::Vector3d& p : scan.points_m) buffer.push_back(scan.sensor_to_world * p);
      insertPointCloudParallel(map, buffer, scan.sensor_to_world.translation(), options, threads);
    }
  } else {
    for (std::size_t s = 0; s < w.world.size(); ++s) {
      insertPointCloudParallel(map, w.world[s], w.origins[s], options, threads);
    }
  }
}

const CloudComparison& cloudComparison(CloudId id, const CloudWorkload& w) {
  static std::array<std::optional<CloudComparison>, kCloudWorkloads> cache;
  std::optional<CloudComparison>& slot = cache[static_cast<std::size_t>(id)];
  if (slot) return *slot;
  CloudComparison c;
  OcTree16 ours(w.resolution_m);
  insertSonarmap(ours, w);
  octomap::OcTree theirs(w.resolution_m);
  insertOctomap(theirs, w);
  c.sonarmap_bytes = ours.memoryBytes();
  c.octomap_nodes = theirs.size();
  c.octomap_leaves = theirs.getNumLeafNodes();
  c.octomap_bytes = theirs.memoryUsage();
  const testing::VoxelAgreement agreement = testing::compareWithOctomap(ours, theirs);
  c.known_sonarmap = agreement.ours_known;
  c.known_octomap = agreement.theirs_known;
  c.known_both = agreement.agree + agreement.differ;
  c.agree = agreement.agree;
  slot = c;
  return *slot;
}

bool parallelMapIsSerial(const CloudWorkload& w, const OcTree16& map) {
  OcTree16 serial(w.resolution_m);
  insertSonarmap(serial, w);
  return testing::leavesOf(map) == testing::leavesOf(serial);
}

}  // namespace sonarmap::bench

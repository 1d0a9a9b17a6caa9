#pragma once
/// @file bench_cloud_workloads.hpp
/// Point-cloud workloads, built once per process for both libraries, and what is
/// compared between the maps they produce (see bench_cloud.cpp).

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <octomap/octomap.h>

#include "sonarmap/core/point_cloud.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap::bench {

/// The cloud workloads.
enum class CloudId {
  kGraph5cm,   ///< ../shared/data/octomap_spherical_scan.graph at 5 cm, scan by scan with its pose
  kGraph2cm,   ///< the same at 2 cm
  kSphere5cm,  ///< OctoMap's InsertScan test: 360 × 360 points on a 2 m sphere, at 5 cm
  kRoom5cm,    ///< 10 scans of 102,400 points in a 20 m × 4 m × 3 m corridor, 10 m range, 5 cm
};
inline constexpr int kCloudWorkloads = 4;

/// One workload, in the form each library takes it. Points are float-representable, so OctoMap
/// (float) and sonarmap (double) start from the same numbers.
struct CloudWorkload {
  std::string name;
  double resolution_m = 0.05;
  double max_range_m = -1.0;  ///< passed to both insertPointCloud calls; < 0: none
  std::size_t points = 0;     ///< over all scans

  /// Graph workloads: each library reads the file with its own reader and inserts scan by scan
  /// with the pose (sonarmap's insertScan, OctoMap's insertPointCloud(const ScanNode&)).
  bool posed = false;
  std::vector<Scan> scans;                      ///< sonarmap: sensor frame + pose (posed only)
  std::unique_ptr<octomap::ScanGraph> graph;    ///< OctoMap: the same file (posed only)

  /// Every workload, world frame: what insertPointCloud gets (generated workloads), what the
  /// parallel insertion gets after the transform (graph), and the rays of the traversal rows.
  std::vector<PointCloud> world;                ///< points in the map frame (posed: pose * point)
  std::vector<Eigen::Vector3d> origins;         ///< sensor origin per scan
  std::vector<octomap::Pointcloud> world_o;     ///< the same in OctoMap's floats
  std::vector<octomap::point3d> origins_o;
  /// Ray ends for the traversal rows: the world points, clipped at max_range_m as the insertions
  /// clip them (only the room workload has points beyond its range).
  std::vector<PointCloud> ray_ends;
  std::vector<octomap::Pointcloud> ray_ends_o;
};

/// The workload, built on first use, or nullptr (and state.SkipWithError) when the graph file is
/// missing or unreadable. The graph is looked up like the CRAS log: $SONARMAP_DATA, else the
/// SONARMAP_SHARED_DATA folder.
const CloudWorkload* cloudOrSkip(benchmark::State& state, CloudId id);

/// Timed bodies: the whole workload into a fresh map, each library's way, serially.
void insertSonarmap(OcTree16& map, const CloudWorkload& workload);
void insertOctomap(octomap::OcTree& tree, const CloudWorkload& workload);
/// insertPointCloudParallel scan by scan (graph scans transformed into `buffer` first, as
/// insertScan does).
void insertSonarmapParallel(OcTree16& map, const CloudWorkload& workload, unsigned threads, PointCloud& buffer);

/// The maps compared, computed once per workload outside any timed loop.
struct CloudComparison {
  std::size_t octomap_nodes = 0, octomap_leaves = 0, octomap_bytes = 0;  ///< memoryUsage()
  std::size_t sonarmap_bytes = 0;
  /// Finest voxels, pruned leaves expanded (tests/algorithms/octomap_reference.hpp).
  std::size_t known_sonarmap = 0, known_octomap = 0, known_both = 0, agree = 0;
};
const CloudComparison& cloudComparison(CloudId id, const CloudWorkload& workload);
/// Whether `map` (from insertSonarmapParallel) equals the serial insertion's map leaf by leaf.
bool parallelMapIsSerial(const CloudWorkload& workload, const OcTree16& map);

}  // namespace sonarmap::bench

#pragma once
// What the peers' drivers share (bench/peers): the scan graph read once by OctoMap's own reader
// (liboctomap's ScanGraph::readBinary, so that every driver reads the same floats the same way),
// the report line run.sh parses, and the usage and failure exits.
#include <chrono>
#include <cstdio>
#include <vector>

#include <octomap/octomap.h>

namespace peers {

/// One scan in the world frame, metres, as the graph's pose places it.
struct WorldScan {
  double origin[3];
  std::vector<double> xyz;  ///< x, y, z of each point
};

inline std::vector<WorldScan> readWorldScans(const char* path) {
  octomap::ScanGraph graph;
  std::vector<WorldScan> scans;
  if (!graph.readBinary(path)) return scans;
  for (const octomap::ScanNode* node : graph) {
    WorldScan scan;
    const octomath::Vector3 origin = node->pose.trans();
    for (int i = 0; i < 3; ++i) scan.origin[i] = origin(i);
    scan.xyz.reserve(3 * node->scan->size());
    for (const octomath::Vector3& point : *node->scan) {
      const octomath::Vector3 world = node->pose.transform(point);
      for (int i = 0; i < 3; ++i) scan.xyz.push_back(world(i));
    }
    scans.push_back(std::move(scan));
  }
  return scans;
}

inline double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The line run.sh reads: "<name> insert_s <s> free <voxels> occupied <voxels>" (finest voxels).
inline void report(const char* name, double insert_s, std::size_t free, std::size_t occupied) {
  std::printf("%s insert_s %.4f free %zu occupied %zu\n", name, insert_s, free, occupied);
}

inline int usage(const char* name) {
  std::fprintf(stderr, "usage: %s IN.graph OUT RESOLUTION_M\n", name);
  return 2;
}

inline int fail(const char* what) {
  std::fprintf(stderr, "%s\n", what);
  return 1;
}

}  // namespace peers

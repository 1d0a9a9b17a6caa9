// ufomap_cloud IN.graph OUT.um RESOLUTION_M: UFOMap's side of the peers' table (run.sh), the job of
// `sonarmap cloud`: every scan inserted with ufo::map::OccupancyMap::insertPointCloudDiscrete at its
// defaults (depth 0, exact rays, no early stopping: one ray per distinct end voxel, as OctoMap's
// discretize; v1.0.0's non-discrete insertPointCloud does not compile: its freeSpace call matches
// no overload) at OctoMap's probabilities (0.7, 0.4, clamping 0.1192/0.971, UFOMap's defaults), no
// range limit, the map written with write(). Built by
// build.sh against a UFOMap v1.0.0 checkout (lz4, TBB), outside the project's CMake.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <ufo/map/occupancy_map.h>

#include "peer_common.hpp"

int main(int argc, char** argv) {
  if (argc != 4) return peers::usage("ufomap_cloud");
  const std::vector<peers::WorldScan> scans = peers::readWorldScans(argv[1]);
  if (scans.empty()) return peers::fail("cannot read the scan graph");
  const auto start = std::chrono::steady_clock::now();
  ufo::map::OccupancyMap map(std::atof(argv[3]));
  for (const peers::WorldScan& scan : scans) {
    ufo::map::PointCloud cloud;
    cloud.reserve(scan.xyz.size() / 3);
    for (std::size_t i = 0; i < scan.xyz.size(); i += 3) cloud.push_back(ufo::map::Point3(scan.xyz[i], scan.xyz[i + 1], scan.xyz[i + 2]));
    map.insertPointCloudDiscrete(ufo::map::Point3(scan.origin[0], scan.origin[1], scan.origin[2]), cloud);
  }
  const double insert_s = peers::since(start);
  if (!map.write(argv[2])) return peers::fail("cannot write the map");
  std::size_t free = 0, occupied = 0;
  for (auto it = map.beginLeaves(false, true, false), end = map.endLeaves(); it != end; ++it) {
    free += std::size_t{1} << (3 * it.getDepth());
  }
  for (auto it = map.beginLeaves(true, false, false), end = map.endLeaves(); it != end; ++it) {
    occupied += std::size_t{1} << (3 * it.getDepth());
  }
  peers::report("ufomap", insert_s, free, occupied);
  return 0;
}

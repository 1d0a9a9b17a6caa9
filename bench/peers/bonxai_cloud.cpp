// bonxai_cloud IN.graph OUT.bx RESOLUTION_M: Bonxai's side of the peers' table (run.sh), the job of
// `sonarmap cloud`: every scan inserted with Bonxai::ProbabilisticMap::insertPointCloud at its
// defaults (OctoMap's probabilities and clamping, bonxai_map/probabilistic_map.hpp), no range limit,
// the grid written with Bonxai::Serialize. Bonxai's rays step in integer voxel coordinates and may
// move diagonally (RayIterator), so they cross fewer voxels than OctoMap's exact traversal: the
// free and occupied voxels printed show what that costs. Built by build.sh against a Bonxai
// checkout, outside the project's CMake; Bonxai's code is not in this repository.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "bonxai/serialization.hpp"
#include "bonxai_map/probabilistic_map.hpp"
#include "peer_common.hpp"

int main(int argc, char** argv) {
  if (argc != 4) return peers::usage("bonxai_cloud");
  const std::vector<peers::WorldScan> scans = peers::readWorldScans(argv[1]);
  if (scans.empty()) return peers::fail("cannot read the scan graph");
  const auto start = std::chrono::steady_clock::now();
  Bonxai::ProbabilisticMap map(std::atof(argv[3]));
  std::vector<Bonxai::Point3D> points;
  for (const peers::WorldScan& scan : scans) {
    points.clear();
    for (std::size_t i = 0; i < scan.xyz.size(); i += 3) points.push_back({scan.xyz[i], scan.xyz[i + 1], scan.xyz[i + 2]});
    map.insertPointCloud(points, Bonxai::Point3D{scan.origin[0], scan.origin[1], scan.origin[2]}, 1e9);
  }
  const double insert_s = peers::since(start);
  std::ofstream out(argv[2], std::ios::binary);
  Bonxai::Serialize(out, map.grid());
  if (!out) return peers::fail("cannot write the map");
  std::vector<Bonxai::CoordT> free, occupied;
  map.getFreeVoxels(free);
  map.getOccupiedVoxels(occupied);
  peers::report("bonxai", insert_s, free.size(), occupied.size());
  return 0;
}

// octomap_cloud IN.graph OUT.bt RESOLUTION_M: OctoMap's side of the peers' table (run.sh), the
// job of `sonarmap cloud IN.graph -o OUT.bt --resolution R`: every scan of the graph inserted
// with OcTree::insertPointCloud(ScanNode) at OctoMap's defaults (hit 0.7, miss 0.4, clamping
// 0.1192/0.971, no range limit), the tree written as .bt. Prints the insertion time by its own
// clock and the finest voxels known, free and occupied. Built by build.sh against Debian's
// liboctomap-dev, outside the project's CMake.
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include <octomap/octomap.h>

#include "peer_common.hpp"

int main(int argc, char** argv) {
  if (argc != 4) return peers::usage("octomap_cloud");
  octomap::ScanGraph graph;
  if (!graph.readBinary(argv[1])) return peers::fail("cannot read the scan graph");
  const auto start = std::chrono::steady_clock::now();
  octomap::OcTree tree(std::atof(argv[3]));
  for (const octomap::ScanNode* node : graph) tree.insertPointCloud(*node, -1.0);
  const double insert_s = peers::since(start);
  if (!tree.writeBinary(argv[2])) return peers::fail("cannot write the map");
  std::size_t free = 0, occupied = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const std::size_t voxels = std::size_t{1} << (3 * (tree.getTreeDepth() - it.getDepth()));
    (tree.isNodeOccupied(*it) ? occupied : free) += voxels;
  }
  peers::report("octomap", insert_s, free, occupied);
  return 0;
}

// Uses the installed library: a voxel updated, written as OctoMap binary, read back.
#include <cstdio>
#include <filesystem>

#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  sonarmap::OcTree16 map(0.05);
  map.updateNode(map.coder().keyOfChecked({1.0, 2.0, 0.5}), 2.0F);
  sonarmap::writeBinaryFile(map, argv[1]);
  const sonarmap::OcTree16 back = sonarmap::readBinaryFile(argv[1]);
  const bool ok = back.occupancyAt({1.0, 2.0, 0.5}) == sonarmap::Occupancy::kOccupied;
  std::printf("consumer: %s\n", ok ? "read back the occupied voxel" : "FAILED");
  return ok ? 0 : 1;
}

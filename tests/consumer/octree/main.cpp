// Uses the octree alone: the voxels a ray crosses (DDA) marked free, its end voxel occupied, then
// read back. Links sonarmap::octree only (the standard library and Eigen).
#include <cstdio>
#include <vector>

#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/raycast/dda.hpp"

int main() {
  sonarmap::OcTree16 map(0.05);
  const Eigen::Vector3d origin_m(0.0, 0.0, 0.0), end_m(2.0, 1.0, 0.5);
  std::vector<sonarmap::OcTree16::KeyType> keys;
  if (!sonarmap::rayKeysDDA(map.coder(), origin_m, end_m, keys)) return 1;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) map.integrate(keys[i], /*occupied=*/false);
  map.integrate(keys.back(), /*occupied=*/true);
  const bool ok = map.occupancyAt(end_m) == sonarmap::Occupancy::kOccupied &&
                  map.occupancyAt(0.5 * end_m) == sonarmap::Occupancy::kFree;
  std::printf("octree consumer: %s (%zu voxels on the ray)\n", ok ? "free ray, occupied end" : "FAILED", keys.size());
  return ok ? 0 : 1;
}

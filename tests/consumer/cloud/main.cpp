// `sonarmap cloud`'s job from a user's program: the scans of an OctoMap scan graph (or, without
// one, a synthetic sphere of points around the origin) inserted at 5 cm and written as a .bt map.
// Links sonarmap::octree, algorithms and io only.
// Usage: cloud_consumer OUT.bt [IN.graph]
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>
#include <vector>

#include "sonarmap/algorithms/point_cloud_insertion.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/io/scan_graph.hpp"

namespace {

/// 36 × 18 points on a sphere of radius 2 m around the sensor at the origin (sensor frame).
sonarmap::Scan sphere() {
  sonarmap::Scan scan;
  for (int i = 0; i < 36; ++i) {
    for (int j = 1; j < 18; ++j) {
      const double azimuth_rad = i * std::numbers::pi / 18.0, polar_rad = j * std::numbers::pi / 18.0;
      scan.points_m.emplace_back(2.0 * std::sin(polar_rad) * std::cos(azimuth_rad),
                                 2.0 * std::sin(polar_rad) * std::sin(azimuth_rad), 2.0 * std::cos(polar_rad));
    }
  }
  return scan;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: cloud_consumer OUT.bt [IN.graph]\n");
    return 2;
  }
  try {
    const std::vector<sonarmap::Scan> scans = argc == 3 ? sonarmap::readScanGraph(argv[2]) : std::vector{sphere()};
    sonarmap::OcTree16 map(0.05);
    for (const sonarmap::Scan& scan : scans) sonarmap::insertScan(map, scan);
    sonarmap::writeMapFile(map, argv[1]);
    std::printf("cloud consumer: %zu scans, %zu map nodes -> %s\n", scans.size(), map.counts().nodes, argv[1]);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "cloud_consumer: %s\n", error.what());
    return 1;
  }
  return 0;
}

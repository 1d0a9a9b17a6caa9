// sonarmap_cloud_inputs OUT_DIR: writes the generated point-cloud workloads of the peers' table
// (bench/peers/run.sh, docs/performance.md "Peers") as OctoMap scan graphs, so that OctoMap's
// tools, the peers' drivers and `sonarmap cloud` read the very same points:
//   sphere_5m.graph    OctoMap's InsertScan test pattern (octomap/src/testing/unit_tests.cpp)
//                      on a 5 m sphere: 360 × 360 rays from (0.01, 0.01, 0.02) m, in 1° steps
//                      about z, then about y, from (5.01, 0.01, 0.01) m;
//   corridor.graph     one laser scan in a corridor [-10.007, 9.993] × [-2.011, 1.989] ×
//                      [-1.509, 1.491] m from (-5.987, 0.017, 0.023) m: 441 azimuths × 200
//                      elevations (±85°) = 88,200 rays to the nearest wall, ±1 cm uniform noise
//                      (an LCG), ranges 1.5–16 m, the size of one FR-079 corridor scan (88,206
//                      points; that dataset is not reachable from this machine).
// Points are float-representable: a scan graph stores floats.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <numbers>
#include <vector>

#include "sonarmap/io/scan_graph.hpp"

namespace {

using sonarmap::Scan;

Eigen::Vector3d asFloats(const Eigen::Vector3d& p) { return p.cast<float>().cast<double>(); }

Scan sphere() {
  Scan scan;
  scan.sensor_to_world.translation() = asFloats({0.01, 0.01, 0.02});
  Eigen::Vector3d on_surface(5.01, 0.01, 0.01);
  const Eigen::AngleAxisd about_z(std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ());
  const Eigen::AngleAxisd about_y(std::numbers::pi / 180.0, Eigen::Vector3d::UnitY());
  for (int i = 0; i < 360; ++i) {
    for (int j = 0; j < 360; ++j) {
      scan.points_m.push_back(asFloats(on_surface));  // sensor frame: the origin is a translation
      on_surface = about_z * on_surface;
    }
    on_surface = about_y * on_surface;
  }
  return scan;
}

Scan corridor() {
  const Eigen::Vector3d lo(-10.007, -2.011, -1.509), hi(9.993, 1.989, 1.491);
  const Eigen::Vector3d origin = asFloats({-5.987, 0.017, 0.023});
  std::uint32_t seed = 271828;
  const auto noise = [&seed] {
    seed = seed * 1664525U + 1013904223U;
    return ((seed >> 8) / 16777216.0 - 0.5) * 0.02;
  };
  Scan scan;
  scan.sensor_to_world.translation() = origin;
  constexpr int kAzimuths = 441, kElevations = 200;
  for (int a = 0; a < kAzimuths; ++a) {
    const double azimuth = 2.0 * std::numbers::pi * (a + 0.5) / kAzimuths;
    for (int e = 0; e < kElevations; ++e) {
      const double elevation = (-85.0 + 170.0 * (e + 0.5) / kElevations) * std::numbers::pi / 180.0;
      const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                              std::sin(elevation));
      double range_m = 1e9;
      for (int axis = 0; axis < 3; ++axis) {
        if (d[axis] > 1e-12) range_m = std::min(range_m, (hi[axis] - origin[axis]) / d[axis]);
        if (d[axis] < -1e-12) range_m = std::min(range_m, (lo[axis] - origin[axis]) / d[axis]);
      }
      scan.points_m.push_back(asFloats(d * (range_m + noise())));
    }
  }
  return scan;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sonarmap_cloud_inputs OUT_DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    sonarmap::writeScanGraph((dir / "sphere_5m.graph").string(), {sphere()});
    sonarmap::writeScanGraph((dir / "corridor.graph").string(), {corridor()});
    std::printf("%s: sphere_5m.graph (129,600 points), corridor.graph (88,200 points)\n", dir.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sonarmap_cloud_inputs: %s\n", e.what());
    return 1;
  }
  return 0;
}

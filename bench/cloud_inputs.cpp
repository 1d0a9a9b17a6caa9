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
//   building.graph     the FR-079 dataset's size and extent (Hornung et al. 2013, Table I: 66
//                      scans, 43.8 × 18.2 × 3.3 m): a 3 m wide corridor along x with 8 rooms of
//                      5 × 7.6 m on each side, each open to it by a 1 m door, scanned from 66
//                      poses 0.6 m apart along the corridor, each 441 × 200 rays (±85°) to the
//                      first wall, ±1 cm noise: 5,821,200 points. Walls are the free space's
//                      boundary (a union of boxes), so rays leave the corridor through doors.
// Points are float-representable: a scan graph stores floats.
#include <algorithm>
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

/// Free space of the building: boxes whose union is the air (corridor, rooms, doors).
struct Box {
  Eigen::Vector3d lo, hi;
  bool inside(const Eigen::Vector3d& p) const { return (p.array() > lo.array()).all() && (p.array() < hi.array()).all(); }
  /// Ray parameter at which a ray from `p` (inside) along `d` leaves the box.
  double exit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const {
    double t = 1e9;
    for (int axis = 0; axis < 3; ++axis) {
      if (d[axis] > 1e-12) t = std::min(t, (hi[axis] - p[axis]) / d[axis]);
      if (d[axis] < -1e-12) t = std::min(t, (lo[axis] - p[axis]) / d[axis]);
    }
    return t;
  }
};

std::vector<Scan> building() {
  constexpr double kLength = 43.8, kHeight = 3.3, kCorridor = 3.0, kRoomDepth = 7.6;
  constexpr int kRoomsPerSide = 8;
  std::vector<Box> air{{{0.0, -kCorridor / 2, 0.0}, {kLength, kCorridor / 2, kHeight}}};
  const double room_width = kLength / kRoomsPerSide;
  for (int side : {-1, 1}) {
    for (int r = 0; r < kRoomsPerSide; ++r) {
      const double x0 = r * room_width + 0.15, x1 = (r + 1) * room_width - 0.15;  // 0.3 m walls
      const double near = kCorridor / 2 + 0.2, far = near + kRoomDepth;
      const double y0 = side > 0 ? near : -far, y1 = side > 0 ? far : -near;
      air.push_back({{x0, y0, 0.0}, {x1, y1, kHeight}});
      const double door = x0 + 0.4 + 0.37 * (r % 3);  // doors not aligned across the corridor
      const double dy0 = side > 0 ? kCorridor / 2 - 0.01 : -near - 0.01, dy1 = side > 0 ? near + 0.01 : -kCorridor / 2 + 0.01;
      air.push_back({{door, dy0, 0.0}, {door + 1.0, dy1, 2.1}});
    }
  }
  std::uint32_t seed = 314159;
  const auto noise = [&seed] {
    seed = seed * 1664525U + 1013904223U;
    return ((seed >> 8) / 16777216.0 - 0.5) * 0.02;
  };
  std::vector<Scan> scans;
  constexpr int kScans = 66, kAzimuths = 441, kElevations = 200;
  for (int s = 0; s < kScans; ++s) {
    Scan scan;
    const Eigen::Vector3d origin = asFloats({1.003 + 0.6 * s, 0.013 * (s % 5) - 0.02, 1.207});
    scan.sensor_to_world.translation() = origin;
    for (int a = 0; a < kAzimuths; ++a) {
      const double azimuth = 2.0 * std::numbers::pi * (a + 0.5) / kAzimuths + 0.01 * s;
      for (int e = 0; e < kElevations; ++e) {
        const double elevation = (-85.0 + 170.0 * (e + 0.5) / kElevations) * std::numbers::pi / 180.0;
        const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                std::sin(elevation));
        double t = 0.0;  // walk from box to box until the point is in none: the first wall
        for (bool moved = true; moved;) {
          moved = false;
          const Eigen::Vector3d p = origin + (t + 1e-6) * d;
          double next = t;
          for (const Box& box : air)
            if (box.inside(p)) next = std::max(next, t + 1e-6 + box.exit(p, d));
          if (next > t) t = next, moved = true;
        }
        scan.points_m.push_back(asFloats(d * (t + noise())));
      }
    }
    scans.push_back(std::move(scan));
  }
  return scans;
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
    sonarmap::writeScanGraph((dir / "building.graph").string(), building());
    std::printf("%s: sphere_5m.graph (129,600 points), corridor.graph (88,200 points), building.graph (66 scans, 5,821,200 points)\n",
                dir.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sonarmap_cloud_inputs: %s\n", e.what());
    return 1;
  }
  return 0;
}

#include "sonarmap/mapping/sweep_fan.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// The longest free range at one grid angle and the beam it comes from.
struct Cover {
  double range_m = 0.0;
  int beam = -1;
};

Eigen::Vector3d inSonarPlane(double angle_rad, double range_m) {
  return {range_m * std::cos(angle_rad), range_m * std::sin(angle_rad), 0.0};
}

/// Calls f(j) for every grid index j within the beam's width (at least the nearest one).
template <class F>
void forEachGridAngle(double bearing_rad, double width_rad, int levels, F&& f) {
  const long n = 1L << levels;
  const double step = kTwoPi / static_cast<double>(n);
  long first = static_cast<long>(std::ceil((bearing_rad - 0.5 * width_rad) / step));
  long last = static_cast<long>(std::floor((bearing_rad + 0.5 * width_rad) / step));
  if (last < first) first = last = std::lround(bearing_rad / step);
  for (long j = first; j <= last; ++j) f(static_cast<std::size_t>(((j % n) + n) % n));
}

void planSingleRays(const std::vector<PlannedBeam>& beams, std::vector<FreeRay>& rays) {
  for (const PlannedBeam& beam : beams) {
    const Eigen::Vector3d end_m = beam.sonar_to_map * inSonarPlane(beam.bearing_rad, beam.free_range_m);
    rays.push_back({beam.sonar_to_map.translation(), end_m});
  }
}

}  // namespace

void planFreeRays(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m,
                  std::vector<FreeRay>& rays) {
  planFreeRays(beams, BeamShape{beam_width_rad, 0.0}, voxel_m, rays);
}

void planFreeRays(const std::vector<PlannedBeam>& beams, const BeamShape& shape, double voxel_m,
                  std::vector<FreeRay>& rays) {
  rays.clear();
  if (shape.width_rad <= 0.0) return planSingleRays(beams, rays);
  double longest_m = voxel_m;
  for (const PlannedBeam& beam : beams) longest_m = std::max(longest_m, beam.free_range_m);
  int levels = 3;  // 2^levels grid angles per turn, at most one voxel apart at the longest range
  while (levels < 24 && kTwoPi * longest_m / std::ldexp(1.0, levels) > voxel_m) ++levels;
  const double step = kTwoPi / std::ldexp(1.0, levels);
  // Elevation rows i · step, |i| ≤ rows_each_side: the same angular grid as the bearings, so the
  // rays are at most a voxel apart at the longest range on both axes (0: the sonar's plane only).
  const long rows_each_side = static_cast<long>(std::floor(0.5 * shape.vertical_aperture_rad / step));

  std::vector<Cover> cover(std::size_t{1} << levels);
  for (std::size_t b = 0; b < beams.size(); ++b) {
    const PlannedBeam& beam = beams[b];
    forEachGridAngle(beam.bearing_rad, shape.width_rad, levels, [&](std::size_t j) {
      if (beam.free_range_m > cover[j].range_m) cover[j] = {beam.free_range_m, static_cast<int>(b)};
    });
  }
  const std::size_t n = cover.size();
  // A grid index's level: its coarser neighbours lie 2^(levels − level) steps either side.
  auto levelOf = [&](unsigned long index) { return index == 0 ? 0 : levels - std::countr_zero(index); };
  // Where a ray of `level` starts: its coarser neighbours are less than a voxel apart before.
  auto spreadOf = [&](int level) {
    const double coarse_gap_rad = 2.0 * std::ldexp(step, levels - level);
    return voxel_m / coarse_gap_rad - voxel_m;
  };
  std::vector<double> cos_elevation, sin_elevation;  // of rows −rows_each_side … rows_each_side
  for (long i = -rows_each_side; i <= rows_each_side; ++i) {
    cos_elevation.push_back(std::cos(static_cast<double>(i) * step));
    sin_elevation.push_back(std::sin(static_cast<double>(i) * step));
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (cover[j].beam < 0) continue;
    const int azimuth_level = levelOf(j);
    const PlannedBeam& beam = beams[static_cast<std::size_t>(cover[j].beam)];
    const double angle = static_cast<double>(j) * step;
    const double cos_angle = std::cos(angle), sin_angle = std::sin(angle);
    const double end_m = cover[j].range_m;
    // The azimuth neighbours' reach limits a ray of this grid angle's level (either of them may end
    // sooner: beyond it the ray covers its cells alone).
    double neighbours_m = end_m;
    if (azimuth_level > 1) {
      const std::size_t offset = std::size_t{1} << (levels - azimuth_level);
      neighbours_m = std::min(cover[(j + n - offset) % n].range_m, cover[(j + offset) % n].range_m);
    }
    for (long i = -rows_each_side; i <= rows_each_side; ++i) {
      const int elevation_level = levelOf(static_cast<unsigned long>(std::abs(i)));
      const int level = std::max(azimuth_level, elevation_level);
      double start_m = 0.0;
      if (level > 1) {
        // On the elevation axis the neighbours belong to the same beam: only the azimuth axis'
        // neighbours can end sooner.
        start_m = std::max(0.0, std::min(spreadOf(level), azimuth_level == level ? neighbours_m : end_m));
      }
      const auto row = static_cast<std::size_t>(i + rows_each_side);
      const Eigen::Vector3d direction(cos_elevation[row] * cos_angle, cos_elevation[row] * sin_angle, sin_elevation[row]);
      rays.push_back({beam.sonar_to_map * (std::min(start_m, end_m) * direction), beam.sonar_to_map * (end_m * direction),
                      std::abs(static_cast<double>(i) * step) > 0.25 * shape.vertical_aperture_rad});
    }
  }
}

void planSweep(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m, double tolerance_m,
               std::vector<FreeRay>& rays, std::vector<HitPoint>& hits) {
  planFreeRays(beams, beam_width_rad, voxel_m, rays);
  planArcs(beams, beam_width_rad, voxel_m, tolerance_m, hits);
}

}  // namespace sonarmap

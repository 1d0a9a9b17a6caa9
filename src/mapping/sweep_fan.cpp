#include "sonarmap/mapping/sweep_fan.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

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
  rays.clear();
  if (beam_width_rad <= 0.0) return planSingleRays(beams, rays);
  double longest_m = voxel_m;
  for (const PlannedBeam& beam : beams) longest_m = std::max(longest_m, beam.free_range_m);
  int levels = 3;  // 2^levels grid angles per turn, at most one voxel apart at the longest range
  while (levels < 24 && kTwoPi * longest_m / std::ldexp(1.0, levels) > voxel_m) ++levels;
  const double step = kTwoPi / std::ldexp(1.0, levels);

  std::vector<Cover> cover(std::size_t{1} << levels);
  for (std::size_t b = 0; b < beams.size(); ++b) {
    const PlannedBeam& beam = beams[b];
    forEachGridAngle(beam.bearing_rad, beam_width_rad, levels, [&](std::size_t j) {
      if (beam.free_range_m > cover[j].range_m) cover[j] = {beam.free_range_m, static_cast<int>(b)};
    });
  }
  const std::size_t n = cover.size();
  for (std::size_t j = 0; j < n; ++j) {
    if (cover[j].beam < 0) continue;
    // Level k ray: its coarser neighbours lie 2^(levels−k) grid steps either side.
    const int level = j == 0 ? 0 : levels - std::countr_zero(j);
    double start_m = 0.0;
    if (level > 1) {
      const std::size_t offset = std::size_t{1} << (levels - level);
      const double coarse_gap_rad = 2.0 * static_cast<double>(offset) * step;
      const double spread_m = voxel_m / coarse_gap_rad - voxel_m;  // coarser rays < 1 voxel apart before
      start_m = std::max(0.0, std::min({spread_m, cover[(j + n - offset) % n].range_m, cover[(j + offset) % n].range_m}));
    }
    const PlannedBeam& beam = beams[static_cast<std::size_t>(cover[j].beam)];
    const double angle = static_cast<double>(j) * step;
    const double end_m = cover[j].range_m;
    rays.push_back({beam.sonar_to_map * inSonarPlane(angle, std::min(start_m, end_m)), beam.sonar_to_map * inSonarPlane(angle, end_m)});
  }
}

void planSweep(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m, double tolerance_m,
               std::vector<FreeRay>& rays, std::vector<HitPoint>& hits) {
  planFreeRays(beams, beam_width_rad, voxel_m, rays);
  planArcs(beams, beam_width_rad, voxel_m, tolerance_m, hits);
}

}  // namespace sonarmap

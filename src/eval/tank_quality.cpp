#include "sonarmap/eval/tank_quality.hpp"

#include <cmath>

#include "sonarmap/mapping/map_slice.hpp"

namespace sonarmap {

TankMapQuality evaluateTankMap(const OcTree16& map, double z_m, const WallFitOptions& options) {
  TankMapQuality quality;
  const std::vector<Eigen::Vector2d> occupied = cellsInSlice(map, z_m, Occupancy::kOccupied);
  quality.occupied_cells = occupied.size();
  quality.walls = evaluateWalls(occupied, options);
  const RectangleFit& rect = quality.walls.rect;
  const Eigen::Vector2d u(std::cos(rect.angle_rad), std::sin(rect.angle_rad));
  const Eigen::Vector2d v(-u.y(), u.x());
  const double half_u = 0.5 * rect.width_m - options.wall_tolerance_m;
  const double half_v = 0.5 * rect.height_m - options.wall_tolerance_m;
  auto inside = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = p - rect.center_m;
    return std::abs(d.dot(u)) < half_u && std::abs(d.dot(v)) < half_v;
  };
  if (half_u <= 0.0 || half_v <= 0.0) return quality;
  // Classify every voxel of the slice whose centre lies inside the shrunk rectangle.
  const auto& coder = map.coder();
  const double reach = std::hypot(half_u, half_v);
  const auto lo = coder.keyOfChecked({rect.center_m.x() - reach, rect.center_m.y() - reach, z_m});
  const auto hi = coder.keyOfChecked({rect.center_m.x() + reach, rect.center_m.y() + reach, z_m});
  std::size_t free_inside = 0, occupied_inside = 0;
  for (auto x = lo[0]; x <= hi[0]; ++x) {
    for (auto y = lo[1]; y <= hi[1]; ++y) {
      if (!inside({coder.centerOf(x), coder.centerOf(y)})) continue;
      ++quality.interior_cells;
      const Occupancy occupancy = map.occupancyOf(Key16{{x, y, lo[2]}});
      free_inside += occupancy == Occupancy::kFree ? 1 : 0;
      occupied_inside += occupancy == Occupancy::kOccupied ? 1 : 0;
    }
  }
  if (quality.interior_cells > 0) {
    quality.interior_free_share = static_cast<double>(free_inside) / static_cast<double>(quality.interior_cells);
    quality.interior_occupied_share = static_cast<double>(occupied_inside) / static_cast<double>(quality.interior_cells);
  }
  return quality;
}

}  // namespace sonarmap

#include "sonarmap/eval/ground_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_set>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

namespace {

using KeySet = std::unordered_set<Key16, KeyHash<16>>;

/// Known finest voxels of the evaluated slab.
struct RegionVoxels {
  std::vector<Key16> occupied;
  std::vector<Key16> free;
  Key16 lo{}, hi{};  ///< bounding box of all of them (inclusive)
};

void requirePositive(double value, const char* field) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw ValueError(std::string("ground-truth options: ") + field + " must be a finite number > 0, got " +
                     std::to_string(value));
  }
}

double share(std::size_t part, std::size_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

/// The slab [z_min, z_max]: the options' bounds, or the extent of the map's known leaves.
std::pair<double, double> slabOf(const OcTree16& map, const GroundTruthOptions& options) {
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  const double res = map.resolution_m();
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    const double z0 = map.coder().centerOf(leaf.key[2]);  // centre of the leaf's lowest voxel layer
    lowest = std::min(lowest, z0);
    highest = std::max(highest, z0 + (leaf.edgeVoxels() - 1.0) * res);
  });
  return {options.z_min_m.value_or(lowest), options.z_max_m.value_or(highest)};
}

/// Expands every known leaf into its finest voxels whose centre lies in [z_min, z_max].
RegionVoxels collectRegion(const OcTree16& map, double z_min_m, double z_max_m) {
  RegionVoxels region;
  const auto& coder = map.coder();
  bool any = false;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    const Occupancy occupancy = map.model().classify(leaf.log_odds);
    if (occupancy == Occupancy::kUnknown) return;
    std::vector<Key16>& target = occupancy == Occupancy::kOccupied ? region.occupied : region.free;
    const auto edge = static_cast<unsigned>(leaf.edgeVoxels());
    for (unsigned dz = 0; dz < edge; ++dz) {
      const auto z = static_cast<std::uint16_t>(leaf.key[2] + dz);
      const double z_m = coder.centerOf(z);
      if (z_m < z_min_m || z_m > z_max_m) continue;
      for (unsigned dy = 0; dy < edge; ++dy) {
        for (unsigned dx = 0; dx < edge; ++dx) {
          const Key16 key{{static_cast<std::uint16_t>(leaf.key[0] + dx), static_cast<std::uint16_t>(leaf.key[1] + dy), z}};
          target.push_back(key);
          if (!any) region.lo = region.hi = key;
          any = true;
          growKeyBox(region.lo, region.hi, key);
        }
      }
    }
  });
  if (!any) {
    throw ValueError("the map has no known voxel in the evaluated slab z = [" + std::to_string(z_min_m) + ", " +
                     std::to_string(z_max_m) + "] m");
  }
  return region;
}

/// Distance from `point_m` to the nearest of `sensors`, and that sensor.
std::pair<double, const Eigen::Vector3d*> nearestSensor(const std::vector<Eigen::Vector3d>& sensors,
                                                         const Eigen::Vector3d& point_m) {
  std::pair<double, const Eigen::Vector3d*> best{std::numeric_limits<double>::infinity(), nullptr};
  for (const Eigen::Vector3d& sensor : sensors) {
    const double d = (point_m - sensor).norm();
    if (d < best.first) best = {d, &sensor};
  }
  return best;
}

/// True when the segment from some sensor to `point_m` crosses no surface.
bool reachableInWater(const SceneRayCaster& caster, const std::vector<Eigen::Vector3d>& sensors,
                      const Eigen::Vector3d& point_m) {
  for (const Eigen::Vector3d& sensor : sensors) {
    const Eigen::Vector3d to = point_m - sensor;
    const double distance_m = to.norm();
    if (distance_m < 1e-9 || !caster.firstHit(sensor, to / distance_m, distance_m)) return true;
  }
  return false;
}

/// True when a sensor within `range_m` sees the surface near `point_m`: the first surface along
/// the way is met no earlier than `slack_m` before the point.
bool visibleSurface(const SceneRayCaster& caster, const std::vector<Eigen::Vector3d>& sensors,
                    const Eigen::Vector3d& point_m, double range_m, double slack_m) {
  for (const Eigen::Vector3d& sensor : sensors) {
    const Eigen::Vector3d to = point_m - sensor;
    const double distance_m = to.norm();
    if (distance_m > range_m || distance_m < 1e-9) continue;
    const auto hit = caster.firstHit(sensor, to / distance_m, distance_m + slack_m);
    if (hit && hit->surface.range_m >= distance_m - slack_m) return true;
  }
  return false;
}

/// True when an occupied voxel's centre lies within `tolerance_m` of the centre of `key`.
bool occupiedNear(const KeySet& occupied, const Key16& key, double tolerance_m, double res_m) {
  const int reach = static_cast<int>(std::floor(tolerance_m / res_m));
  const double reach_sq = (tolerance_m / res_m) * (tolerance_m / res_m);
  for (int dz = -reach; dz <= reach; ++dz) {
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        if (dx * dx + dy * dy + dz * dz > reach_sq) continue;
        const Key16 near{{static_cast<std::uint16_t>(key[0] + dx), static_cast<std::uint16_t>(key[1] + dy),
                          static_cast<std::uint16_t>(key[2] + dz)}};
        if (occupied.contains(near)) return true;
      }
    }
  }
  return false;
}

/// Precision and wall-position error over the occupied voxels.
void scoreOccupied(const OcTree16& map, const Scene& scene, const SceneRayCaster& caster, const RegionVoxels& region,
                   const GroundTruthOptions& options, GroundTruthReport& report) {
  std::vector<std::vector<double>> offsets(scene.primitives.size());
  double sum = 0.0, sum_sq = 0.0;
  for (const Key16& key : region.occupied) {
    const Eigen::Vector3d center = map.coder().centerOf(key);
    std::size_t nearest = 0;
    double distance_m = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
      const double d = distanceToSurface(scene.primitives[i], center);
      if (d < distance_m) std::tie(distance_m, nearest) = std::pair{d, i};
    }
    report.occupied_on_surface += distance_m <= report.tolerance_m ? 1 : 0;
    if (distance_m > options.match_distance_m) continue;
    ++report.matched_voxels;
    sum += distance_m;
    sum_sq += distance_m * distance_m;
    const auto [sensor_distance_m, sensor] = nearestSensor(options.sensor_positions_m, center);
    bool behind = false;
    if (sensor_distance_m > 1e-9) {
      const auto hit = caster.intersect(nearest, *sensor, (center - *sensor) / sensor_distance_m);
      behind = hit && hit->range_m < sensor_distance_m;
    }
    offsets[nearest].push_back(behind ? -distance_m : distance_m);
  }
  report.occupied_voxels = region.occupied.size();
  report.precision = share(report.occupied_on_surface, report.occupied_voxels);
  if (report.matched_voxels > 0) {
    report.mean_distance_m = sum / static_cast<double>(report.matched_voxels);
    report.rms_distance_m = std::sqrt(sum_sq / static_cast<double>(report.matched_voxels));
  }
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    std::vector<double>& values = offsets[i];
    if (values.empty()) continue;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    double median = *middle;
    if (values.size() % 2 == 0) median = 0.5 * (median + *std::max_element(values.begin(), middle));
    report.surfaces.push_back({i, values.size(), median});
  }
}

/// Recall: visible surface voxels of the region's box with an occupied voxel within tolerance.
void scoreSurfaces(const OcTree16& map, const Scene& scene, const SceneRayCaster& caster, const RegionVoxels& region,
                   const GroundTruthOptions& options, GroundTruthReport& report) {
  const KeySet occupied(region.occupied.begin(), region.occupied.end());
  const auto& coder = map.coder();
  const double res = map.resolution_m();
  // The known box grown horizontally by T: a wall just beyond the last known voxel still counts.
  const int grow = static_cast<int>(std::ceil(report.tolerance_m / res));
  auto lower = [&](int axis) { return std::max(0, static_cast<int>(region.lo[axis]) - grow); };
  auto upper = [&](int axis) { return std::min(0xFFFF, static_cast<int>(region.hi[axis]) + grow); };
  for (int z = region.lo[2]; z <= region.hi[2]; ++z) {
    for (int y = lower(1); y <= upper(1); ++y) {
      for (int x = lower(0); x <= upper(0); ++x) {
        const Key16 key{{static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint16_t>(z)}};
        const Eigen::Vector3d center = coder.centerOf(key);
        if (distanceToSurface(scene, center) > 0.5 * res) continue;
        if (!visibleSurface(caster, options.sensor_positions_m, center, report.max_range_m, res)) continue;
        ++report.surface_voxels;
        report.surface_voxels_found += occupiedNear(occupied, key, report.tolerance_m, res) ? 1 : 0;
      }
    }
  }
  report.recall = share(report.surface_voxels_found, report.surface_voxels);
}

/// Free accuracy: free voxels reachable through water from a sensor, or within tolerance of a surface.
void scoreFree(const OcTree16& map, const Scene& scene, const SceneRayCaster& caster, const RegionVoxels& region,
               const GroundTruthOptions& options, GroundTruthReport& report) {
  for (const Key16& key : region.free) {
    const Eigen::Vector3d center = map.coder().centerOf(key);
    const bool in_water = distanceToSurface(scene, center) <= report.tolerance_m ||
                          reachableInWater(caster, options.sensor_positions_m, center);
    report.free_in_water += in_water ? 1 : 0;
  }
  report.free_voxels = region.free.size();
  report.free_accuracy = share(report.free_in_water, report.free_voxels);
}

/// The map's reach: the largest distance from a known voxel of the region to its nearest sensor.
double reachOf(const OcTree16& map, const RegionVoxels& region, const std::vector<Eigen::Vector3d>& sensors) {
  double reach_m = 0.0;
  for (const std::vector<Key16>* keys : {&region.occupied, &region.free}) {
    for (const Key16& key : *keys) reach_m = std::max(reach_m, nearestSensor(sensors, map.coder().centerOf(key)).first);
  }
  return reach_m;
}

}  // namespace

void GroundTruthOptions::validate() const {
  requirePositive(tolerance_m, "tolerance_m");
  requirePositive(match_distance_m, "match_distance_m");
  if (max_range_m) requirePositive(*max_range_m, "max_range_m");
  for (const auto& [bound, field] : {std::pair{z_min_m, "z_min_m"}, std::pair{z_max_m, "z_max_m"}}) {
    if (bound && !std::isfinite(*bound)) throw ValueError(std::string("ground-truth options: ") + field + " is not finite");
  }
  if (z_min_m && z_max_m && *z_min_m > *z_max_m) {
    throw ValueError("ground-truth options: z_min_m " + std::to_string(*z_min_m) + " is above z_max_m " +
                     std::to_string(*z_max_m));
  }
  if (sensor_positions_m.empty()) throw ValueError("ground-truth options: sensor_positions_m is empty");
  for (const Eigen::Vector3d& sensor : sensor_positions_m) {
    if (!sensor.allFinite()) throw ValueError("ground-truth options: a sensor position is not finite");
  }
}

GroundTruthReport evaluateAgainstScene(const OcTree16& map, const Scene& scene, const GroundTruthOptions& options) {
  options.validate();
  if (scene.primitives.empty()) throw ValueError("the ground-truth scene holds no primitive");
  validateScene(scene);
  GroundTruthReport report;
  report.tolerance_m = std::max(options.tolerance_m, std::sqrt(3.0) * map.resolution_m());
  std::tie(report.z_min_m, report.z_max_m) = slabOf(map, options);
  const RegionVoxels region = collectRegion(map, report.z_min_m, report.z_max_m);
  report.max_range_m =
      options.max_range_m.value_or(reachOf(map, region, options.sensor_positions_m) + report.tolerance_m);
  const SceneRayCaster caster(scene);
  scoreOccupied(map, scene, caster, region, options, report);
  scoreSurfaces(map, scene, caster, region, options, report);
  scoreFree(map, scene, caster, region, options, report);
  return report;
}

}  // namespace sonarmap

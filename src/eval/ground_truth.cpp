#include "sonarmap/eval/ground_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <Eigen/LU>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/core/statistics.hpp"
#include "occupied_near.hpp"
#include "surface_voxels.hpp"

namespace sonarmap {

namespace {

/// Reports the scoring as three equal stages (occupied voxels, surface voxels, free voxels) of
/// kStageUnits units each, calling the callback only when the count of units changes.
class StageProgress {
 public:
  static constexpr std::size_t kStages = 3, kStageUnits = 1000;
  explicit StageProgress(const ProgressCallback& callback) : callback_(callback) {}
  /// `done` of `total` items of stage `stage` (0, 1, 2) are scored.
  void operator()(std::size_t stage, std::size_t done, std::size_t total) {
    if (!callback_) return;
    const std::size_t units = stage * kStageUnits + (total == 0 ? kStageUnits : done * kStageUnits / total);
    if (units == last_) return;
    last_ = units;
    callback_(units, kStages * kStageUnits);
  }

 private:
  const ProgressCallback& callback_;
  std::size_t last_ = static_cast<std::size_t>(-1);
};

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
    leaf.forEachVoxel([&](const Key16& key) {
      const double z_m = coder.centerOf(key[2]);
      if (z_m < z_min_m || z_m > z_max_m) return;
      target.push_back(key);
      if (!any) region.lo = region.hi = key;
      any = true;
      growKeyBox(region.lo, region.hi, key);
    });
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

/// The sensors' field of view: their orientations (sonar → map) and half the vertical aperture,
/// or no check when `orientations` is empty.
struct FieldOfView {
  const std::vector<Eigen::Matrix3d>& orientations;
  double half_aperture_rad = 0.0;

  /// True when the unit direction `to_unit` (map frame) from sensor `index` lies within the
  /// aperture: its elevation in the sonar frame, asin of the sonar-frame z component, within
  /// ±half_aperture_rad.
  bool sees(std::size_t index, const Eigen::Vector3d& to_unit) const {
    if (orientations.empty()) return true;
    const double up = std::clamp(orientations[index].col(2).dot(to_unit), -1.0, 1.0);  // (Rᵀ · u).z
    return std::abs(std::asin(up)) <= half_aperture_rad;
  }
};

/// True when a sensor within `range_m` sees the surface near `point_m`: the point is within its
/// field of view, and the first surface along the way is met no earlier than `slack_m` before it.
bool visibleSurface(const SceneRayCaster& caster, const std::vector<Eigen::Vector3d>& sensors, const FieldOfView& view,
                    const Eigen::Vector3d& point_m, double range_m, double slack_m) {
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const Eigen::Vector3d to = point_m - sensors[i];
    const double distance_m = to.norm();
    if (distance_m > range_m || distance_m < 1e-9) continue;
    const Eigen::Vector3d unit = to / distance_m;
    if (!view.sees(i, unit)) continue;
    const auto hit = caster.firstHit(sensors[i], unit, distance_m + slack_m);
    if (hit && hit->surface.range_m >= distance_m - slack_m) return true;
  }
  return false;
}

/// The distance from `point_m` to the nearest surface of the scene (metres) and that primitive's
/// index (the first of equals).
std::pair<double, std::size_t> nearestPrimitive(const Scene& scene, const Eigen::Vector3d& point_m) {
  std::pair<double, std::size_t> nearest{std::numeric_limits<double>::infinity(), 0};
  for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
    const double d = distanceToSurface(scene.primitives[i], point_m);
    if (d < nearest.first) nearest = {d, i};
  }
  return nearest;
}

/// Precision and wall-position error over the occupied voxels.
void scoreOccupied(const OcTree16& map, const Scene& scene, const SceneRayCaster& caster, const RegionVoxels& region,
                   const GroundTruthOptions& options, GroundTruthReport& report, StageProgress& progress) {
  std::vector<std::vector<double>> offsets(scene.primitives.size());
  std::vector<double> distances;  // of every occupied voxel, for the surface error
  distances.reserve(region.occupied.size());
  report.occupied_errors.reserve(region.occupied.size());
  double sum = 0.0, sum_sq = 0.0;
  for (const Key16& key : region.occupied) {
    progress(0, report.occupied_errors.size(), region.occupied.size());
    const Eigen::Vector3d center = map.coder().centerOf(key);
    const auto [distance_m, nearest] = nearestPrimitive(scene, center);
    report.occupied_on_surface += distance_m <= report.tolerance_m ? 1 : 0;
    if (distance_m > report.tolerance_m && reachableInWater(caster, options.sensor_positions_m, center)) {
      ++report.occupied_in_water;  // a shell in front of a surface, not a voxel behind or inside one
    }
    distances.push_back(distance_m);
    report.occupied_errors.push_back({center, distance_m});
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
  report.surface_error_median_m = percentile(distances, 0.5);
  report.surface_error_p90_m = percentile(distances, 0.9);
  if (report.matched_voxels > 0) {
    report.mean_distance_m = sum / static_cast<double>(report.matched_voxels);
    report.rms_distance_m = std::sqrt(sum_sq / static_cast<double>(report.matched_voxels));
  }
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    std::vector<double>& values = offsets[i];
    if (values.empty()) continue;
    report.surfaces.push_back({i, values.size(), percentile(values, 0.5)});
  }
}

/// Recall and erosion: visible surface voxels of the region's box with an occupied voxel within
/// tolerance, and those the map holds free.
void scoreSurfaces(const OcTree16& map, const Scene& scene, const SceneRayCaster& caster, const RegionVoxels& region,
                   const GroundTruthOptions& options, GroundTruthReport& report, StageProgress& progress) {
  const detail::KeySet occupied(region.occupied.begin(), region.occupied.end());
  const auto& coder = map.coder();
  const double res = map.resolution_m();
  const FieldOfView view{options.sensor_orientations, 0.5 * options.vertical_aperture_rad.value_or(0.0)};
  // The known box grown horizontally by T: a wall just beyond the last known voxel still counts.
  const int grow = static_cast<int>(std::ceil(report.tolerance_m / res));
  Key16 lo = region.lo, hi = region.hi;
  for (int axis = 0; axis < 2; ++axis) {
    lo[axis] = static_cast<std::uint16_t>(std::max(0, static_cast<int>(region.lo[axis]) - grow));
    hi[axis] = static_cast<std::uint16_t>(std::min(0xFFFF, static_cast<int>(region.hi[axis]) + grow));
  }
  if (options.surface_box_m) {  // the caller's box, clipped to the keys the map can hold
    const double first_m = coder.centerOf(std::uint16_t{0}), last_m = coder.centerOf(std::uint16_t{0xFFFF});
    for (int axis = 0; axis < 3; ++axis) {
      const auto indexOf = [&](double v_m) { return *coder.indexOf(std::clamp(v_m, first_m, last_m)); };
      lo[axis] = indexOf(options.surface_box_m->min()[axis]);
      hi[axis] = indexOf(options.surface_box_m->max()[axis]);
    }
  }
  std::vector<SurfaceRecall> by_primitive(scene.primitives.size());
  const auto candidates = detail::surfaceVoxels(coder, scene, lo, hi);
  std::size_t done = 0;
  for (const Key16& key : candidates) {
    progress(1, done++, candidates.size());
    const Eigen::Vector3d center = coder.centerOf(key);
    if (!visibleSurface(caster, options.sensor_positions_m, view, center, report.max_range_m, res)) continue;
    const bool found = detail::occupiedNear(occupied, key, report.tolerance_m, res);
    const bool free = map.occupancyOf(key) == Occupancy::kFree;
    SurfaceRecall& nearest = by_primitive[nearestPrimitive(scene, center).second];
    ++nearest.visible_voxels;
    nearest.found_voxels += found ? 1 : 0;
    nearest.free_voxels += free ? 1 : 0;
  }
  for (std::size_t i = 0; i < by_primitive.size(); ++i) {
    SurfaceRecall& counts = by_primitive[i];
    if (counts.visible_voxels == 0) continue;
    counts.primitive = i;
    report.surface_voxels += counts.visible_voxels;
    report.surface_voxels_found += counts.found_voxels;
    report.surface_voxels_free += counts.free_voxels;
    report.recall_by_surface.push_back(counts);
  }
  report.recall = share(report.surface_voxels_found, report.surface_voxels);
  report.erosion = share(report.surface_voxels_free, report.surface_voxels);
}

/// Free accuracy: free voxels reachable through water from a sensor, or within tolerance of a surface.
void scoreFree(const OcTree16& map, const Scene& scene, const SceneRayCaster& caster, const RegionVoxels& region,
               const GroundTruthOptions& options, GroundTruthReport& report, StageProgress& progress) {
  std::size_t done = 0;
  for (const Key16& key : region.free) {
    progress(2, done++, region.free.size());
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
  if (vertical_aperture_rad) {
    const double aperture_rad = *vertical_aperture_rad;
    if (!(std::isfinite(aperture_rad) && aperture_rad > 0.0 && aperture_rad < std::numbers::pi)) {
      throw ValueError("ground-truth options: vertical_aperture_rad must be in (0, π), got " +
                       std::to_string(aperture_rad));
    }
  }
  if (surface_box_m && (surface_box_m->isEmpty() || !surface_box_m->min().allFinite() || !surface_box_m->max().allFinite())) {
    throw ValueError("ground-truth options: surface_box_m must be a finite, non-empty box");
  }
  if (vertical_aperture_rad.has_value() != !sensor_orientations.empty()) {
    throw ValueError(
        "ground-truth options: the field-of-view check needs both vertical_aperture_rad and sensor_orientations");
  }
  if (!sensor_orientations.empty() && sensor_orientations.size() != sensor_positions_m.size()) {
    throw ValueError("ground-truth options: " + std::to_string(sensor_orientations.size()) +
                     " sensor orientations for " + std::to_string(sensor_positions_m.size()) + " sensor positions");
  }
  for (std::size_t i = 0; i < sensor_orientations.size(); ++i) {
    const Eigen::Matrix3d& rotation = sensor_orientations[i];
    const bool rotation_ok = rotation.allFinite() &&
                             (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-6 &&
                             rotation.determinant() > 0.0;
    if (!rotation_ok) {
      throw ValueError("ground-truth options: sensor orientation " + std::to_string(i) + " is not a finite rotation");
    }
  }
}

GroundTruthReport evaluateAgainstScene(const OcTree16& map, const Scene& scene, const GroundTruthOptions& options,
                                       const ProgressCallback& callback) {
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
  StageProgress progress(callback);
  scoreOccupied(map, scene, caster, region, options, report, progress);
  scoreSurfaces(map, scene, caster, region, options, report, progress);
  scoreFree(map, scene, caster, region, options, report, progress);
  progress(StageProgress::kStages - 1, 1, 1);
  return report;
}

}  // namespace sonarmap

// castRay: an unbounded 3D DDA along a direction, querying the tree at each voxel.
#include "sonarmap/algorithms/cast_ray.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace sonarmap {
namespace {

/// What the walk does at a voxel: stop with a hit, stop without one, or go on.
enum class Step { kHit, kGiveUp, kContinue };

Step classifyVoxel(const OcTree16& map, const Key16& key, bool ignore_unknown) {
  const std::optional<float> value = map.search(key);
  if (!value) return ignore_unknown ? Step::kContinue : Step::kGiveUp;
  return map.model().isOccupied(*value) ? Step::kHit : Step::kContinue;
}

void checkArguments(const Eigen::Vector3d& direction, double max_range_m) {
  if (!direction.allFinite() || direction.squaredNorm() == 0.0) {
    throw ValueError("castRay direction must be finite and non-zero, got (" + std::to_string(direction.x()) + ", " +
                     std::to_string(direction.y()) + ", " + std::to_string(direction.z()) + ")");
  }
  if (std::isnan(max_range_m)) throw ValueError("castRay max range must be a number of metres, got NaN");
}

}  // namespace

std::optional<Eigen::Vector3d> castRay(const OcTree16& map, const Eigen::Vector3d& origin_m,
                                       const Eigen::Vector3d& direction, double max_range_m, bool ignore_unknown) {
  checkArguments(direction, max_range_m);
  const KeyCoder<16>& coder = map.coder();
  Key16 key = coder.keyOfChecked(origin_m);  // throws OutOfMapError
  switch (classifyVoxel(map, key, ignore_unknown)) {
    case Step::kHit: return coder.centerOf(key);
    case Step::kGiveUp: return std::nullopt;
    case Step::kContinue: break;
  }

  // Initialisation (A&W §3): t is in metres along the unit direction.
  const Eigen::Vector3d unit = direction.normalized();
  const double resolution_m = coder.resolution_m();
  constexpr double kNever = std::numeric_limits<double>::infinity();
  std::array<int, 3> step{};
  std::array<double, 3> t_max{}, t_delta{};
  for (int axis = 0; axis < 3; ++axis) {
    step[axis] = unit[axis] > 0.0 ? 1 : (unit[axis] < 0.0 ? -1 : 0);
    if (step[axis] == 0) {
      t_max[axis] = t_delta[axis] = kNever;
      continue;
    }
    // The voxel's face the ray leaves through, in metres.
    const double face_m = (KeyCoder<16>::cellOf(key[axis]) + (step[axis] > 0 ? 1.0 : 0.0)) * resolution_m;
    t_max[axis] = (face_m - origin_m[axis]) / unit[axis];
    t_delta[axis] = resolution_m / std::fabs(unit[axis]);
  }
  const bool limited = max_range_m > 0.0;
  const double max_range_sq = max_range_m * max_range_m;

  // Incremental phase: cross the nearest face until a decision.
  for (;;) {
    const int axis = t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
    const bool at_border = step[axis] > 0 ? key[axis] == 0xFFFF : key[axis] == 0;
    if (at_border) return std::nullopt;  // the next voxel is outside the map
    key[axis] = static_cast<std::uint16_t>(key[axis] + step[axis]);
    t_max[axis] += t_delta[axis];
    const Eigen::Vector3d centre_m = coder.centerOf(key);
    if (limited && (centre_m - origin_m).squaredNorm() > max_range_sq) return std::nullopt;
    switch (classifyVoxel(map, key, ignore_unknown)) {
      case Step::kHit: return centre_m;
      case Step::kGiveUp: return std::nullopt;
      case Step::kContinue: break;
    }
  }
}

}  // namespace sonarmap

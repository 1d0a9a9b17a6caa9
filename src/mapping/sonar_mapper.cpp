#include "sonarmap/mapping/sonar_mapper.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>


#include "sonarmap/raycast/bresenham.hpp"
#include "sonarmap/raycast/dda.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/sweeps.hpp"
#include "sweep_key_set.hpp"

namespace sonarmap {

RayAlgorithm parseRayAlgorithm(std::string_view name) {
  if (name == "dda") return RayAlgorithm::kDDA;
  if (name == "bresenham") return RayAlgorithm::kBresenham;
  throw ValueError("unknown ray algorithm '" + std::string(name) + "', expected dda or bresenham");
}

void MapperOptions::validate() const {
  if (!std::isfinite(resolution_m) || resolution_m <= 0.0) {
    throw ValueError("resolution must be a finite number of metres > 0, got " + std::to_string(resolution_m));
  }
  if (!std::isfinite(self_reflection_range_m) || self_reflection_range_m < 0.0) {
    throw ValueError("self-reflection range must be >= 0 m, got " + std::to_string(self_reflection_range_m));
  }
  if (!(beam_width_rad >= 0.0 && beam_width_rad < 3.14159265358979323846)) {
    throw ValueError("beam width must be within [0, pi) rad, got " + std::to_string(beam_width_rad));
  }
  if (!(full_confidence_intensity >= 1.0 && full_confidence_intensity <= 255.0)) {
    throw ValueError("full-confidence intensity must be within 1…255, got " + std::to_string(full_confidence_intensity));
  }
  octree.occupancy.validate();
}

namespace {
const MapperOptions& validated(const MapperOptions& options) {
  options.validate();
  return options;
}
}  // namespace

struct SonarMapper::SweepCells {
  SweepKeySet seen;  ///< cells already updated in this sweep, and the sweep's hit cells
};

SonarMapper::SonarMapper(const MapperOptions& options)
    : options_(validated(options)), map_(options.resolution_m, options.octree), cells_(std::make_unique<SweepCells>()) {}
SonarMapper::SonarMapper(SonarMapper&&) noexcept = default;
SonarMapper& SonarMapper::operator=(SonarMapper&&) noexcept = default;
SonarMapper::~SonarMapper() = default;

float SonarMapper::hitLogOdds(std::uint8_t intensity) const {
  const double weight = std::min(1.0, static_cast<double>(intensity) / options_.full_confidence_intensity);
  return static_cast<float>(map_.model().hit * weight);
}

std::vector<BeamDetection> SonarMapper::mapSweep(PolarImage& polar, const Eigen::Isometry3d& sonar_to_map) {
  removeSelfReflection(polar, options_.self_reflection_range_m);
  smooth(polar, options_.smoothing);
  std::vector<BeamDetection> detections = detectObstacles(polar, options_.detector);
  integrateSweep(polar, detections, sonar_to_map);
  return detections;
}

namespace {
void growBox(Key16& lo, Key16& hi, const Key16& key) {
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis] = std::min(lo[axis], key[axis]);
    hi[axis] = std::max(hi[axis], key[axis]);
  }
}
bool keyLess(const Key16& a, const Key16& b) { return a.k < b.k; }
}  // namespace

bool SonarMapper::planBeam(const Eigen::Isometry3d& sonar_to_map, double bearing_rad, double range_m, bool hit,
                           std::uint8_t intensity) {
  // The fan has 2^levels + 1 rays, at most one voxel apart at its far end. The two edge rays start
  // at the sonar; a ray of level k (k ≥ 1, spacing width / 2^k) starts where its coarser
  // neighbours, width / 2^(k−1) apart, drift a voxel apart — before that they cover its cells.
  const double width = options_.beam_width_rad;
  const double voxel_m = options_.resolution_m;
  int levels = 0;
  while (width > 0.0 && range_m * width / std::ldexp(1.0, levels) > voxel_m && levels < 16) ++levels;
  const int rays = width > 0.0 ? (1 << levels) + 1 : 1;
  const std::size_t first_ray = rays_.size(), first_hit = hits_.size();
  Key16 lo = box_lo_, hi = box_hi_;
  for (int j = 0; j < rays; ++j) {
    const double angle = bearing_rad + (rays == 1 ? 0.0 : width * (static_cast<double>(j) / (rays - 1) - 0.5));
    const int level = (j == 0 || j == rays - 1) ? 0 : levels - std::countr_zero(static_cast<unsigned>(j));
    const double start_m = level == 0 ? 0.0 : std::max(0.0, voxel_m * std::ldexp(1.0, level - 1) / width - voxel_m);
    const Eigen::Vector3d direction(std::cos(angle), std::sin(angle), 0.0);
    const Eigen::Vector3d end_m = sonar_to_map * Eigen::Vector3d(range_m * direction);
    const auto end_key = map_.coder().keyOf(end_m);
    if (!end_key) {
      rays_.resize(first_ray);
      hits_.resize(first_hit);
      return false;
    }
    growBox(lo, hi, *end_key);
    rays_.push_back({sonar_to_map * Eigen::Vector3d(std::min(start_m, range_m) * direction), end_m, hit});
    if (hit) hits_.emplace_back(*end_key, intensity);
  }
  box_lo_ = lo;
  box_hi_ = hi;
  return true;
}

void SonarMapper::integrateFreeCells() {
  auto visit = [&](const Key16& key) {
    if (!cells_->seen.insert(key)) return;  // updated already, or a hit cell of this sweep
    map_.integrate(key, false);
    ++stats_.free_updates;
  };
  // Rays alternate direction (far end first on every other ray), so consecutive updates are
  // neighbours and the octree's descent starts from a deep common ancestor.
  bool forward = true;
  for (const FanRay& ray : rays_) {
    const Eigen::Vector3d& from = forward ? ray.start_m : ray.end_m;
    const Eigen::Vector3d& to = forward ? ray.end_m : ray.start_m;
    if (options_.ray == RayAlgorithm::kDDA) {
      traverseDDA(map_.coder(), from, to, visit);
    } else {
      traverseBresenham(map_.coder(), from, to, visit);
    }
    forward = !forward;
  }
}

void SonarMapper::integrateHits() {
  // One update per hit cell, with the strongest echo that fell into it.
  std::sort(hits_.begin(), hits_.end(), [](const auto& a, const auto& b) { return keyLess(a.first, b.first); });
  for (std::size_t i = 0; i < hits_.size();) {
    std::uint8_t intensity = hits_[i].second;
    std::size_t j = i + 1;
    for (; j < hits_.size() && hits_[j].first == hits_[i].first; ++j) intensity = std::max(intensity, hits_[j].second);
    map_.updateNode(hits_[i].first, hitLogOdds(intensity));
    ++stats_.occupied_updates;
    i = j;
  }
}

void SonarMapper::integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                 const Eigen::Isometry3d& sonar_to_map) {
  if (detections.size() != static_cast<std::size_t>(polar.rows())) {
    throw ValueError("sweep has " + std::to_string(polar.rows()) + " beams but " + std::to_string(detections.size()) +
                     " detections");
  }
  const auto origin_key = map_.coder().keyOf(sonar_to_map.translation());
  if (!origin_key) {
    stats_.out_of_map += detections.size();
    return;
  }
  rays_.clear();
  hits_.clear();
  box_lo_ = box_hi_ = *origin_key;
  for (std::size_t row = 0; row < detections.size(); ++row) {
    const BeamDetection& detection = detections[row];
    const double range_m = detection.hasObstacle() ? (detection.obstacle_bin + 0.5) * polar.bin_length_m
                                                   : polar.valid_bins[row] * polar.bin_length_m;
    if (!planBeam(sonar_to_map, polar.bearing_rad[row], range_m, detection.hasObstacle(), detection.intensity)) {
      ++stats_.out_of_map;
      continue;
    }
    ++stats_.beams_used;
    if (detection.hasObstacle()) ++stats_.obstacles;
  }
  cells_->seen.reset(box_lo_, box_hi_);
  for (const auto& hit : hits_) cells_->seen.insert(hit.first);  // an obstacle is never also a miss
  integrateFreeCells();
  integrateHits();
  if (options_.octree.lazy) map_.updateInnerOccupancy();
  ++stats_.sweeps;
}

std::vector<SweepRange> mergeShortSweeps(std::vector<SweepRange> sweeps, std::size_t min_beams) {
  std::vector<SweepRange> merged;
  for (const SweepRange& sweep : sweeps) {
    if (!merged.empty() && (sweep.size() < min_beams || merged.back().size() < min_beams)) {
      merged.back().last_exclusive = sweep.last_exclusive;
    } else {
      merged.push_back(sweep);
    }
  }
  return merged;
}

SonarMapper mapSonarLog(const SonarLog& log, const MapperOptions& options, const ProgressCallback& progress) {
  SonarMapper mapper(options);
  mapper.stats().beams_skipped = log.skipped_beams;
  const auto min_beams = static_cast<std::size_t>(std::max(1, options.detector.background.min_beams));
  const std::vector<SweepRange> sweeps = mergeShortSweeps(splitSweeps(log.beams), min_beams);
  for (std::size_t i = 0; i < sweeps.size(); ++i) {
    PolarImage polar = makePolarImage(log.beams, sweeps[i].first, sweeps[i].last_exclusive);
    mapper.mapSweep(polar);
    if (progress) progress(i + 1, sweeps.size());
  }
  return mapper;
}

}  // namespace sonarmap

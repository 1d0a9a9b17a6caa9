#include "sonarmap/mapping/sonar_mapper.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <future>
#include <string>


#include "sonarmap/raycast/bresenham.hpp"
#include "sonarmap/raycast/dda.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/sweeps.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "../algorithms/key_marks.hpp"

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

struct SonarMapper::SweepWork {
  std::vector<PlannedBeam> beams;                     ///< the sweep's beams inside the map
  std::vector<FreeRay> rays;                          ///< free-space rays, in grid-angle order
  std::vector<HitPoint> hit_points;
  std::vector<std::pair<Key16, std::uint8_t>> hits;   ///< hit cell, intensity
  Key16 box_lo{}, box_hi{};                           ///< keys the sweep's rays stay within
  KeyMarks<16> crossed;  ///< cells the sweep's free rays cross, each once
};

SonarMapper::SonarMapper(const MapperOptions& options)
    : options_(validated(options)), map_(options.resolution_m, options.octree), work_(std::make_unique<SweepWork>()) {}
SonarMapper::SonarMapper(SonarMapper&&) noexcept = default;
SonarMapper& SonarMapper::operator=(SonarMapper&&) noexcept = default;
SonarMapper::~SonarMapper() = default;

float SonarMapper::hitLogOdds(std::uint8_t intensity) const {
  const double weight = std::min(1.0, static_cast<double>(intensity) / options_.full_confidence_intensity);
  return static_cast<float>(map_.model().hit * weight);
}

std::vector<BeamDetection> SonarMapper::detect(PolarImage& polar) const {
  removeSelfReflection(polar, options_.self_reflection_range_m);
  smooth(polar, options_.smoothing);
  return detectObstacles(polar, options_.detector);
}

std::vector<BeamDetection> SonarMapper::mapSweep(PolarImage& polar, const Eigen::Isometry3d& sonar_to_map) {
  std::vector<BeamDetection> detections = detect(polar);
  integrateSweep(polar, detections, sonar_to_map);
  return detections;
}

void SonarMapper::integrateFreeCells() {
  // First mark every cell the rays cross, then update each once, in tree order.
  SweepWork& work = *work_;
  work.crossed.marking([&](auto mark) {
    for (const FreeRay& ray : work.rays) {
      if (options_.ray == RayAlgorithm::kDDA) {
        traverseDDA(map_.coder(), ray.start_m, ray.end_m, mark);
      } else {
        traverseBresenham(map_.coder(), ray.start_m, ray.end_m, mark);
      }
    }
  });
  for (const auto& hit : work.hits) work.crossed.erase(hit.first);  // an obstacle is never also a miss
  // Brick by brick, leaves only; an eager tree then syncs its inner nodes once (the same tree).
  work.crossed.forEachBrick([&](const Key16& corner, std::uint64_t voxels) {
    map_.updateBrick(corner, voxels, map_.model().miss);
    stats_.free_updates += static_cast<std::size_t>(std::popcount(voxels));
  });
  if (!map_.options().lazy) map_.updateDirtyInnerOccupancy();
}

void SonarMapper::integrateHits() {
  // One update per hit cell, with the strongest echo that fell into it.
  auto& hits = work_->hits;
  std::sort(hits.begin(), hits.end(), [](const auto& a, const auto& b) { return KeyMarks<16>::visitLess(a.first, b.first); });
  for (std::size_t i = 0; i < hits.size();) {
    std::uint8_t intensity = hits[i].second;
    std::size_t j = i + 1;
    for (; j < hits.size() && hits[j].first == hits[i].first; ++j) intensity = std::max(intensity, hits[j].second);
    map_.updateNode(hits[i].first, hitLogOdds(intensity));
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
  SweepWork& work = *work_;
  work.beams.clear();
  for (std::size_t row = 0; row < detections.size(); ++row) {
    const BeamDetection& detection = detections[row];
    const double range_m = detection.hasObstacle() ? (detection.obstacle_bin + 0.5) * polar.bin_length_m
                                                   : polar.valid_bins[row] * polar.bin_length_m;
    const PlannedBeam beam{sonar_to_map, polar.bearing_rad[row], range_m, detection.hasObstacle(), detection.intensity};
    if (!beamInsideMap(beam)) {
      ++stats_.out_of_map;
      continue;
    }
    work.beams.push_back(beam);
    ++stats_.beams_used;
    if (detection.hasObstacle()) ++stats_.obstacles;
  }
  planSweep(work.beams, options_.beam_width_rad, options_.resolution_m, work.rays, work.hit_points);
  keySweep();
  integrateFreeCells();
  integrateHits();
  if (options_.octree.lazy) map_.updateInnerOccupancy();
  ++stats_.sweeps;
}

bool SonarMapper::beamInsideMap(const PlannedBeam& beam) const {
  // The sonar and the wedge's far corners and middle; the map is a box, so the wedge is inside.
  const double half = 0.5 * options_.beam_width_rad;
  for (const double offset : {-half, 0.0, half}) {
    const double angle = beam.bearing_rad + offset;
    const Eigen::Vector3d end(beam.free_range_m * std::cos(angle), beam.free_range_m * std::sin(angle), 0.0);
    if (!map_.coder().keyOf(beam.sonar_to_map * end)) return false;
  }
  return map_.coder().keyOf(beam.sonar_to_map.translation()).has_value();
}

void SonarMapper::keySweep() {
  SweepWork& work = *work_;
  work.hits.clear();
  if (work.beams.empty()) return;
  work.box_lo = work.box_hi = *map_.coder().keyOf(work.beams.front().sonar_to_map.translation());
  for (const FreeRay& ray : work.rays) {
    for (const Eigen::Vector3d* point : {&ray.start_m, &ray.end_m}) {
      if (const auto key = map_.coder().keyOf(*point)) growKeyBox(work.box_lo, work.box_hi, *key);
    }
  }
  for (const HitPoint& hit : work.hit_points) {
    if (const auto key = map_.coder().keyOf(hit.point_m)) {
      work.hits.emplace_back(*key, hit.intensity);
      growKeyBox(work.box_lo, work.box_hi, *key);
    }
  }
  work.crossed.reset(work.box_lo, work.box_hi);
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

namespace {
/// A sweep cleaned and searched, ready to integrate.
struct DetectedSweep {
  PolarImage polar;
  std::vector<BeamDetection> detections;
};
}  // namespace

SonarMapper mapSonarLog(const SonarLog& log, const MapperOptions& options, const ProgressCallback& progress) {
  SonarMapper mapper(options);
  mapper.stats().beams_skipped = log.skipped_beams;
  const auto min_beams = static_cast<std::size_t>(std::max(1, options.detector.background.min_beams));
  const std::vector<SweepRange> sweeps = mergeShortSweeps(splitSweeps(log.beams), min_beams);
  auto detectSweep = [&](std::size_t i) {
    DetectedSweep sweep{makePolarImage(log.beams, sweeps[i].first, sweeps[i].last_exclusive), {}};
    sweep.detections = mapper.detect(sweep.polar);
    return sweep;
  };
  const auto launch = options.pipeline_detection ? std::launch::async : std::launch::deferred;
  std::future<DetectedSweep> next;
  if (!sweeps.empty()) next = std::async(launch, detectSweep, 0);
  for (std::size_t i = 0; i < sweeps.size(); ++i) {
    DetectedSweep sweep = next.get();  // rethrows what the detection threw
    if (i + 1 < sweeps.size()) next = std::async(launch, detectSweep, i + 1);
    mapper.integrateSweep(sweep.polar, sweep.detections);
    if (progress) progress(i + 1, sweeps.size());
  }
  return mapper;
}

}  // namespace sonarmap

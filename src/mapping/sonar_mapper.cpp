#include "sonarmap/mapping/sonar_mapper.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <future>
#include <optional>
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
  if (!(max_range_m > 0.0)) throw ValueError("max range must be > 0 m, got " + std::to_string(max_range_m));
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
  std::vector<PlannedBeam> group;    ///< planBeams: the beams of one group of nearby poses
  std::vector<FreeRay> group_rays;   ///< planBeams: that group's rays
  std::vector<HitPoint> group_hits;  ///< planBeams: that group's hit points
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
        traverseDDASteps(map_.coder(), ray.start_m, ray.end_m, mark);
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

template <class PoseOfRow>
void SonarMapper::integrateRows(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                PoseOfRow&& pose_of) {
  SweepWork& work = *work_;
  work.beams.clear();
  for (std::size_t row = 0; row < detections.size(); ++row) {
    const Eigen::Isometry3d* sonar_to_map = pose_of(row);
    if (sonar_to_map == nullptr) {
      ++stats_.beams_without_nav;
      continue;
    }
    const BeamDetection& detection = detections[row];
    double range_m = detection.hasObstacle() ? (detection.obstacle_bin + 0.5) * polar.bin_length_m
                                             : polar.valid_bins[row] * polar.bin_length_m;
    bool hit = detection.hasObstacle();
    if (range_m > options_.max_range_m) {  // OctoMap's maxrange: free up to the limit, no obstacle
      range_m = options_.max_range_m;
      hit = false;
      ++stats_.beams_clipped;
    }
    const PlannedBeam beam{*sonar_to_map, polar.bearing_rad[row], range_m, hit, detection.intensity};
    if (!beamInsideMap(beam)) {
      ++stats_.out_of_map;
      continue;
    }
    work.beams.push_back(beam);
    ++stats_.beams_used;
    if (hit) ++stats_.obstacles;
  }
  planBeams();
  keySweep();
  integrateFreeCells();
  integrateHits();
  if (options_.octree.lazy) map_.updateInnerOccupancy();
  ++stats_.sweeps;
}

namespace {
/// @throws ValueError when the sweep's `what` (detections, poses) do not number one per polar row.
void checkRows(const PolarImage& polar, std::size_t count, const char* what) {
  if (count != static_cast<std::size_t>(polar.rows())) {
    throw ValueError("sweep has " + std::to_string(polar.rows()) + " beams but " + std::to_string(count) + " " + what);
  }
}

/// An upper bound of how far any point within `reach_m` of the sonar moves between the poses `a`
/// and `b`: |Δtranslation| + reach · |Δrotation angle|.
double poseDisplacementBound_m(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double reach_m) {
  if (a.matrix() == b.matrix()) return 0.0;
  const double angle_rad = Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
  return (a.translation() - b.translation()).norm() + reach_m * std::abs(angle_rad);
}
}  // namespace

void SonarMapper::integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                 const Eigen::Isometry3d& sonar_to_map) {
  checkRows(polar, detections.size(), "detections");
  integrateRows(polar, detections, [&](std::size_t) { return &sonar_to_map; });
}

void SonarMapper::integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                 const std::vector<Eigen::Isometry3d>& sonar_to_map_per_row) {
  checkRows(polar, detections.size(), "detections");
  checkRows(polar, sonar_to_map_per_row.size(), "poses");
  integrateRows(polar, detections, [&](std::size_t row) { return &sonar_to_map_per_row[row]; });
}

void SonarMapper::integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                 const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map_per_row) {
  checkRows(polar, detections.size(), "detections");
  checkRows(polar, sonar_to_map_per_row.size(), "poses");
  integrateRows(polar, detections, [&](std::size_t row) -> const Eigen::Isometry3d* {
    const auto& pose = sonar_to_map_per_row[row];
    return pose ? &*pose : nullptr;
  });
}

void SonarMapper::planBeams() {
  // The fan (sweep_fan.hpp) assumes its beams share the sonar's pose: a finer ray starts where its
  // coarser neighbours drift a voxel apart. Beams whose poses move no point of their reach by more
  // than a quarter voxel from the group's first pose are planned as one fan (each still placed with
  // its own pose); the others group by group, their rays and hits appended in beam order.
  SweepWork& work = *work_;
  const std::vector<PlannedBeam>& beams = work.beams;
  double reach_m = options_.resolution_m;
  for (const PlannedBeam& beam : beams) reach_m = std::max(reach_m, beam.free_range_m);
  const double tolerance_m = 0.25 * options_.resolution_m;
  auto groupEnd = [&](std::size_t first) {
    std::size_t end = first + 1;
    while (end < beams.size() &&
           poseDisplacementBound_m(beams[first].sonar_to_map, beams[end].sonar_to_map, reach_m) <= tolerance_m) {
      ++end;
    }
    return end;
  };
  if (beams.empty() || groupEnd(0) == beams.size()) {  // one pose (a static sweep): one fan, as always
    planSweep(beams, options_.beam_width_rad, options_.resolution_m, work.rays, work.hit_points);
    return;
  }
  work.rays.clear();
  work.hit_points.clear();
  for (std::size_t first = 0, end = 0; first < beams.size(); first = end) {
    end = groupEnd(first);
    work.group.assign(beams.begin() + static_cast<std::ptrdiff_t>(first), beams.begin() + static_cast<std::ptrdiff_t>(end));
    planSweep(work.group, options_.beam_width_rad, options_.resolution_m, work.group_rays, work.group_hits);
    work.rays.insert(work.rays.end(), work.group_rays.begin(), work.group_rays.end());
    work.hit_points.insert(work.hit_points.end(), work.group_hits.begin(), work.group_hits.end());
  }
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

/// mapSonarLog's body: `integrate(mapper, polar, detections)` places each detected sweep.
template <class Integrate>
SonarMapper mapSweeps(const SonarLog& log, const MapperOptions& options, const ProgressCallback& progress,
                      Integrate&& integrate) {
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
    integrate(mapper, sweep.polar, sweep.detections);
    if (progress) progress(i + 1, sweeps.size());
  }
  return mapper;
}

}  // namespace

SonarMapper mapSonarLog(const SonarLog& log, const MapperOptions& options, const ProgressCallback& progress) {
  return mapSweeps(log, options, progress, [](SonarMapper& mapper, const PolarImage& polar, const auto& detections) {
    mapper.integrateSweep(polar, detections);
  });
}

SonarMapper mapSonarLog(const SonarLog& log, const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body,
                        const MapperOptions& options, const ProgressCallback& progress) {
  const NavInterpolator interpolator(nav);  // checks the track once: throws ValueError when it is invalid
  const Eigen::Isometry3d ned_to_map = nedToMap();
  std::vector<std::optional<Eigen::Isometry3d>> poses;
  return mapSweeps(log, options, progress, [&](SonarMapper& mapper, const PolarImage& polar, const auto& detections) {
    poses.clear();
    for (const double time_s : polar.time_s) {
      const std::optional<Eigen::Isometry3d> body_to_ned = interpolator.bodyToNedAt(time_s);
      poses.push_back(body_to_ned ? std::optional(ned_to_map * *body_to_ned * sonar_to_body) : std::nullopt);
    }
    mapper.integrateSweep(polar, detections, poses);
  });
}

}  // namespace sonarmap

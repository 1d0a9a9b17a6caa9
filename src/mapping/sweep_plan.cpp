/// @file sweep_plan.cpp
/// SonarMapper's planning of a sweep: its beams into free rays and hit points (one fan per group of
/// nearby poses, sweep_fan.hpp), then the hit points into tree-ordered hit cells and the key box
/// the rays stay within (see sonar_mapper.hpp).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "sweep_work.hpp"
#include "../algorithms/radix_sort.hpp"

namespace sonarmap {

namespace {
/// An upper bound of how far any point within `reach_m` of the sonar moves between the poses `a`
/// and `b`: |Δtranslation| + reach · |Δrotation angle|.
double poseDisplacementBound_m(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double reach_m) {
  if (a.matrix() == b.matrix()) return 0.0;
  const double angle_rad = Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
  return (a.translation() - b.translation()).norm() + reach_m * std::abs(angle_rad);
}
}  // namespace

void SonarMapper::planBeams() {
  // The fan (sweep_fan.hpp) assumes its beams share the sonar's pose: a finer ray starts where its
  // coarser neighbours drift a voxel apart. Beams whose poses move no point of their reach by more
  // than a quarter voxel from the group's first pose are planned as one fan (each still placed with
  // its own pose); the others group by group, their rays appended in beam order. The arcs are
  // planned over the whole sweep, each beam with its own pose.
  SweepWork& work = *work_;
  const std::vector<PlannedBeam>& beams = work.beams;
  const double voxel_m = *options_.resolution_m;
  double reach_m = voxel_m;
  for (const PlannedBeam& beam : beams) reach_m = std::max({reach_m, beam.free_range_m, beam.hit ? beam.hit_range_m : 0.0});
  const double drift_m = 0.25 * voxel_m;
  auto groupEnd = [&](std::size_t first) {
    std::size_t end = first + 1;
    while (end < beams.size() &&
           poseDisplacementBound_m(beams[first].sonar_to_map, beams[end].sonar_to_map, reach_m) <= drift_m) {
      ++end;
    }
    return end;
  };
  const BeamShape shape = beamShape();
  // Each beam's own pose; the volume model's obstacles are vertical faces that recede across their
  // beam where the neighbours measure it, the evidence shared by the beam pattern (sweep_fan.hpp).
  planArcs(beams, shape, voxel_m, work.tolerance_m, ArcEvidence::kBeamPattern, work.hit_points, ObstacleSurface::kVertical,
           true);
  // The free space: the cone's loud core only (freeVerticalAperture_rad).
  BeamShape fshape = shape;
  if (options_.beam_model == BeamModel::kVolume) fshape.vertical_aperture_rad = freeVerticalAperture_rad(options_);
  if (beams.empty() || groupEnd(0) == beams.size()) {  // one pose (a static sweep): one fan, as always
    planFreeRays(beams, fshape, voxel_m, work.rays);
    return;
  }
  work.rays.clear();
  for (std::size_t first = 0, end = 0; first < beams.size(); first = end) {
    end = groupEnd(first);
    work.group.assign(beams.begin() + static_cast<std::ptrdiff_t>(first), beams.begin() + static_cast<std::ptrdiff_t>(end));
    planFreeRays(work.group, fshape, voxel_m, work.group_rays);
    work.rays.insert(work.rays.end(), work.group_rays.begin(), work.group_rays.end());
  }
}

void SonarMapper::placeSeabedTraces() {
  // The sweep's weak seabed onsets join those of the sweeps before; the sweep's weak seabed traces
  // then follow the slope they fit around the sweep's onsets, within twice the traces' reach
  // (seabed_slope.hpp). Loud traces neither feed nor follow it (PlannedBeam::loud_trace).
  SweepWork& work = *work_;
  const BeamShape shape = beamShape();
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  double reach_m = 0.0;
  std::vector<PlannedBeam*> traces;  // the sweep's weak seabed traces
  for (PlannedBeam& beam : work.beams) {
    if (beam.loud_trace) continue;
    if (const std::optional<Eigen::Vector3d> onset_m = seabedOnsetPoint(beam, shape)) {
      const Eigen::Vector3d axis = beam.sonar_to_map.linear() * Eigen::Vector3d(std::cos(beam.bearing_rad), std::sin(beam.bearing_rad), 0.0);
      work.seabed.add(*onset_m, axis.head<2>());
      centre_m += *onset_m;
      reach_m = std::max(reach_m, beam.trace_end_m);
      traces.push_back(&beam);
    }
  }
  if (!traces.empty()) {
    const Eigen::Vector3d normal = work.seabed.normalAt(centre_m / static_cast<double>(traces.size()), 2.0 * reach_m);
    for (PlannedBeam* beam : traces) beam->trace_normal = normal;
    work.seabed_onsets_m = {centre_m / static_cast<double>(traces.size()), 2.0 * reach_m};
  }
  checkLoudTraces();
}

void SonarMapper::checkLoudTraces() {
  // A loud trace is drawn on the level through its onset on the aperture's edge. A face whose
  // loud echo outlasts the nominal cone's (a loud face is heard beyond the −3 dB edge) would draw
  // that floor in the water before the face, above the seabed the weak onsets measure; such a
  // beam stays the obstacle it was detected as: where its onset lies above the seabed fitted
  // around the sweep's loud onsets (seabed_slope.hpp) by more than the fit's inlier band plus the
  // sweep's range tolerance.
  SweepWork& work = *work_;
  if (work.loud_obstacles.empty()) return;
  const BeamShape shape = beamShape();
  std::vector<std::optional<Eigen::Vector3d>> onsets;
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  double reach_m = 0.0;
  std::size_t count = 0;
  for (const auto& [index, obstacle] : work.loud_obstacles) {
    const PlannedBeam& beam = work.beams[index];
    onsets.push_back(seabedOnsetPoint(beam, shape));
    if (!onsets.back()) continue;
    centre_m += *onsets.back();
    reach_m = std::max(reach_m, beam.trace_end_m);
    ++count;
  }
  if (count == 0) return;
  const std::optional<SeabedSlope::Fit> seabed = work.seabed.fitAround(centre_m / static_cast<double>(count), 2.0 * reach_m);
  if (!seabed) return;
  const double band_m = SeabedSlope::kInlierDeviations * seabed->deviation_m + work.tolerance_m;
  for (std::size_t i = 0; i < onsets.size(); ++i) {
    if (!onsets[i] || !(seabed->heightAbove(*onsets[i]) > band_m)) continue;
    work.beams[work.loud_obstacles[i].first] = work.loud_obstacles[i].second;
    --stats_.extended_returns;
    ++stats_.obstacles;
  }
}

BeamShape SonarMapper::beamShape() const {
  return {options_.beam_width_rad,
          mapsBeamVolume(options_) ? options_.vertical_aperture_rad : 0.0};
}

bool SonarMapper::beamInsideMap(const PlannedBeam& beam) {
  // The sonar and the wedge's (or cone's) far corners and middles; the map is a box, so the wedge
  // is inside (a cone's far surface bulges by less than a voxel between these points at the
  // resolutions a map this large can have; the traversal checks every key anyway).
  const BeamShape shape = beamShape();
  const double half = 0.5 * shape.width_rad;
  const double half_aperture = 0.5 * shape.vertical_aperture_rad;
  const double reach_m = std::max(beam.free_range_m, beam.hit ? beam.hit_range_m : 0.0);
  bool inside = map_.coder().keyOf(beam.sonar_to_map.translation()).has_value();
  stats_.farthest_m = std::max(stats_.farthest_m, beam.sonar_to_map.translation().cwiseAbs().maxCoeff());
  for (const double elevation : {-half_aperture, 0.0, half_aperture}) {
    for (const double offset : {-half, 0.0, half}) {
      const double angle = beam.bearing_rad + offset;
      const Eigen::Vector3d end =
          beam.sonar_to_map * Eigen::Vector3d(reach_m * std::cos(elevation) * std::cos(angle),
                                              reach_m * std::cos(elevation) * std::sin(angle), reach_m * std::sin(elevation));
      stats_.farthest_m = std::max(stats_.farthest_m, end.cwiseAbs().maxCoeff());
      inside = inside && map_.coder().keyOf(end).has_value();
    }
    if (half_aperture == 0.0) break;
  }
  return inside;
}

namespace {
/// Grows the key box [lo, hi] to hold the key of every end point of `rays` inside the map.
void growKeyBoxByRays(const KeyCoder<16>& coder, const std::vector<FreeRay>& rays, Key16& lo, Key16& hi) {
  // Keys are monotone in each coordinate, axis by axis: when the corners of the rays' bounding box
  // have keys, their keys bound every end point's key. Otherwise (a ray leaving the map, whose
  // traversal is skipped) the end points inside the map, one by one.
  if (rays.empty()) return;
  Eigen::Vector3d min_m = rays.front().start_m, max_m = min_m;
  for (const FreeRay& ray : rays) {
    min_m = min_m.cwiseMin(ray.start_m).cwiseMin(ray.end_m);
    max_m = max_m.cwiseMax(ray.start_m).cwiseMax(ray.end_m);
  }
  const std::optional<Key16> min_key = coder.keyOf(min_m), max_key = coder.keyOf(max_m);
  if (min_key && max_key) {
    growKeyBox(lo, hi, *min_key);
    growKeyBox(lo, hi, *max_key);
    return;
  }
  for (const FreeRay& ray : rays) {
    for (const Eigen::Vector3d* point : {&ray.start_m, &ray.end_m}) {
      if (const auto key = coder.keyOf(*point)) growKeyBox(lo, hi, *key);
    }
  }
}
}  // namespace

void SonarMapper::keySweep() {
  SweepWork& work = *work_;
  work.hits.clear();
  if (work.beams.empty()) return;
  work.box_lo = work.box_hi = *map_.coder().keyOf(work.beams.front().sonar_to_map.translation());
  growKeyBoxByRays(map_.coder(), work.rays, work.box_lo, work.box_hi);
  work.hits.reserve(work.hit_points.size());
  Key16 key, previous_key{};
  std::uint64_t previous_code = 0;
  for (const HitPoint& hit : work.hit_points) {
    if (!map_.coder().keyInto(hit.point_m, key)) continue;
    // std::lround of a value in [0, 65535], without its library call: the integer part, plus one
    // from a fraction of one half (exact: subtracting the integer part rounds nothing).
    const double scaled = std::clamp(hit.weight, 0.0, 1.0) * 0xFFFF;
    const auto whole = static_cast<std::uint64_t>(scaled);
    const std::uint64_t weight = whole + (scaled - static_cast<double>(whole) >= 0.5 ? 1 : 0);
    // Neighbouring points of a shell often share a cell: one entry, the larger weight (what the
    // reduction below keeps), and no second code or box test.
    if (!work.hits.empty() && key == previous_key) {
      work.hits.back() = std::max(work.hits.back(), previous_code | weight);
      continue;
    }
    previous_key = key;
    previous_code = mortonCode(key) << 16;
    work.hits.push_back(previous_code | weight);
    growKeyBox(work.box_lo, work.box_hi, key);
  }
  work.crossed.reset(work.box_lo, work.box_hi);
  // The arc points in tree order (by cell only, stable), then one entry per cell with its largest weight.
  radixSortHighBits(work.hits, 16, work.sort_scratch);
  std::size_t cells = 0;
  for (std::size_t i = 0; i < work.hits.size(); ++cells) {
    std::uint64_t cell = work.hits[i++];
    for (; i < work.hits.size() && work.hits[i] >> 16 == cell >> 16; ++i) cell = std::max(cell, work.hits[i]);
    work.hits[cells] = cell;
  }
  work.hits.resize(cells);
}

}  // namespace sonarmap

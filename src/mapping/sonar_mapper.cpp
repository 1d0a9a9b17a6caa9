#include "sonarmap/mapping/sonar_mapper.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <future>
#include <limits>
#include <optional>
#include <string>

#include "sonarmap/algorithms/resample.hpp"
#include "sonarmap/raycast/bresenham.hpp"
#include "sonarmap/raycast/dda.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/polar_units.hpp"
#include "sonarmap/sonar/sweeps.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "../algorithms/on_threads.hpp"
#include "beam_cells.hpp"
#include "sweep_work.hpp"

namespace sonarmap {

namespace {
/// The map's resolution until the first sweep fixes an automatic one (the map is empty until then).
constexpr double kUnresolvedResolution_m = 0.02;

/// The detector options the mapper detects with: the model's beam width, and for the beam-volume
/// model the evidence detector's loud echoes alone (the background detector). In a cone a return
/// too weak for the obstacle threshold is likeliest a grazing seabed or surface, which the extended
/// returns trace on the level it implies (addExtendedReturns), not a face at its range (measured:
/// kept as faces, the simulated tilted loop's F1 fell from 0.626 to 0.337; docs/accuracy.md).
DetectorOptions detectorOf(const MapperOptions& options) {
  DetectorOptions detector = options.detector;
  detector.beam_width_rad = options.beam_width_rad;
  if (mapsBeamVolume(options) && detector.kind == Detector::kEvidence) {
    detector.kind = Detector::kBackgroundSubtracted;
  }
  return detector;
}

/// An obstacle's loud return, metres along the beam: where it starts, where its loud echo ends (what
/// isLevelReturn judges: a level surface's loud echo lasts longer than a face's, a face's loud echo
/// followed by a weak seabed at its foot does not) and how far its trace reaches.
struct LoudReturn {
  double onset_m, loud_end_m, end_m;
};

/// The lit run that starts with the obstacle's echo (extended_returns.hpp), from the loud echo's
/// leading edge (the obstacle's range: the run may begin earlier, where a loud surface lights bins
/// in the pattern's skirt outside the nominal aperture, and a level drawn from the aperture's edge
/// there lies too high: 1.1 m over a seabed 20 m under a tilted Ping360), its loud echo ending where
/// it falls back (BeamDetection::echo_end_m) or, not measured, with the run. Without a run: the
/// loud echo alone, from the obstacle's range to where it
/// falls back: a seabed loud over most of a tilted head's sweep lifts the background the run
/// detector compares with (on the Ping360's tilted loop at 50 m, 9 in 10 of the obstacle beams where
/// the seabed enters the lower edge had no run), yet its loud echo outlasts any face. Nothing
/// without a measured end.
std::optional<LoudReturn> loudReturn(const BeamDetection& detection) {
  const bool fell_back = detection.echo_end_m >= detection.range_m;
  if (detection.hasExtendedReturn()) {
    const double loud_end_m = fell_back ? std::min(detection.echo_end_m, detection.extended_end_m) : detection.extended_end_m;
    return LoudReturn{std::max(detection.extended_onset_m, detection.range_m), loud_end_m, detection.extended_end_m};
  }
  if (!fell_back) return std::nullopt;
  return LoudReturn{detection.range_m, detection.echo_end_m, detection.echo_end_m};
}

const MapperOptions& validated(const MapperOptions& options) {
  options.validate();
  return options;
}
}  // namespace

SonarMapper::SonarMapper(const MapperOptions& options)
    : options_(validated(options)),
      auto_resolution_(!options.resolution_m),
      map_(options.resolution_m.value_or(kUnresolvedResolution_m), options.octree),
      work_(std::make_unique<SweepWork>()) {}
SonarMapper::SonarMapper(SonarMapper&&) noexcept = default;
SonarMapper& SonarMapper::operator=(SonarMapper&&) noexcept = default;
SonarMapper::~SonarMapper() = default;

double SonarMapper::rangeTolerance_m(const PolarImage& polar) const {
  return options_.range_tolerance_m.value_or(polar.bin_length_m + 0.5 * *options_.resolution_m);
}

void SonarMapper::resolveResolution(const PolarImage& polar) {
  if (!auto_resolution_) return;
  const double reach_m = std::min(polar.cols() * polar.bin_length_m, options_.max_range_m);
  const double wanted_m = autoResolution_m(reach_m > 0.0 ? reach_m : polar.bin_length_m);
  if (!options_.resolution_m) {
    options_.resolution_m = wanted_m;
    map_ = OcTree16(wanted_m, options_.octree);
    return;
  }
  if (wanted_m <= *options_.resolution_m) return;  // never finer: the map so far would be lost
  // A longer range scale than any before (a Ping360 powers on at 2 m): the map so far, coarser.
  if (inversion_) {  // the window so far at its own resolution first
    inversion_->flush(map_);
    inversion_.reset();
  }
  map_ = resampledMap(map_, wanted_m);
  options_.resolution_m = wanted_m;
  ++stats_.resolution_changes;
  work_->occupied_keys.clear();  // the volume model's hit cells, in the new map's keys
  work_->seabed_looks.reset();   // the level surfaces' columns, counted again at the new size
  work_->surface_looks.reset();
  map_.forEachLeaf([&](const LeafView<16>& leaf) {
    if (!(leaf.log_odds > map_.model().occupied_above)) return;
    const auto edge = static_cast<std::uint32_t>(leaf.edgeVoxels());
    for (std::uint32_t x = 0; x < edge; ++x) {
      for (std::uint32_t y = 0; y < edge; ++y) {
        for (std::uint32_t z = 0; z < edge; ++z) {
          Key16 key = leaf.key;
          key[0] = static_cast<std::uint16_t>(key[0] + x);
          key[1] = static_cast<std::uint16_t>(key[1] + y);
          key[2] = static_cast<std::uint16_t>(key[2] + z);
          work_->occupied_keys.push_back(mortonCode(key));
        }
      }
    }
  });
  std::sort(work_->occupied_keys.begin(), work_->occupied_keys.end());
}

namespace {
/// The range the self-reflection band is zeroed to (MapperOptions::self_reflection_range_m): the
/// option, else the band measured on the sweep, never beyond a minimum range the user set (the
/// nearest echo used is then the user's: --min-range).
double selfReflectionRange(const MapperOptions& options, const SweepCalibration& calibration) {
  if (options.self_reflection_range_m) return *options.self_reflection_range_m;
  return std::min(calibration.band_end_m, options.detector.min_range_m.value_or(calibration.band_end_m));
}
}  // namespace

SweepDetection SonarMapper::detectSweep(PolarImage& polar) const {
  // Calibrate on the image as recorded: the band and the near field are measured before the band is
  // zeroed and before any smoothing spreads it.
  DetectorOptions detector = detectorOf(options_);
  const double span_db = detector.intensity_span_db.value_or(intensitySpan_db(polar));
  const SweepCalibration recorded = calibrateSweep(polar, detector.background.calibration, span_db);
  const double self_reflection_m = selfReflectionRange(options_, recorded);
  removeSelfReflection(polar, self_reflection_m);
  // Nothing can be detected, nor water seen, where the bins were zeroed.
  detector.min_range_m = std::max(detector.min_range_m.value_or(recorded.near_field_end_m), self_reflection_m);
  SweepDetection detection;
  if (options_.smoothing.kind == Smoothing::kNone) {
    detection = sonarmap::detectSweep(polar, detector, recorded);
  } else {
    smooth(polar, options_.smoothing);
    SweepCalibration smoothed = calibrateSweep(polar, detector.background.calibration, span_db);
    smoothed.band_end_m = recorded.band_end_m;
    smoothed.near_field_end_m = recorded.near_field_end_m;
    detection = sonarmap::detectSweep(polar, detector, smoothed);
  }
  if (mapsBeamVolume(options_)) {
    addExtendedReturns(polar, detector.background.calibration.background_percentile, detection, options_.extended);
  }
  return detection;
}

SweepDetection SonarMapper::detectRows(PolarImage& rows, const SweepCalibration& calibration) const {
  DetectorOptions detector = detectorOf(options_);
  const double self_reflection_m = selfReflectionRange(options_, calibration);
  removeSelfReflection(rows, self_reflection_m);
  detector.min_range_m = std::max(detector.min_range_m.value_or(calibration.near_field_end_m), self_reflection_m);
  if (options_.smoothing.kind != Smoothing::kNone) smooth(rows, options_.smoothing);
  SweepDetection detection = sonarmap::detectRows(rows, detector, calibration);
  return detection;
}

std::vector<BeamDetection> SonarMapper::detect(PolarImage& polar) const { return detectSweep(polar).detections; }

std::vector<BeamDetection> SonarMapper::mapSweep(PolarImage& polar, const Eigen::Isometry3d& sonar_to_map) {
  SweepDetection detection = detectSweep(polar);
  recordDetection(detection);
  integrateSweep(polar, detection.detections, sonar_to_map);
  return std::move(detection.detections);
}

void SonarMapper::recordDetection(const SweepDetection& detection) {
  stats_.detection += detection.diagnostics;
  MappingStats::Calibration& c = stats_.calibration;
  const double used_m = detection.min_range_m;
  const bool first = c.sweeps_detected == 0;
  c.band_end_m = detection.calibration.band_end_m;
  c.near_field_end_m = detection.calibration.near_field_end_m;
  c.min_range_m = used_m;
  c.threshold_db = detection.calibration.threshold_db;
  c.span_db = detection.calibration.span_db;
  c.min_range_lowest_m = first ? used_m : std::min(c.min_range_lowest_m, used_m);
  c.min_range_highest_m = first ? used_m : std::max(c.min_range_highest_m, used_m);
  ++c.sweeps_detected;
}

void SonarMapper::integrateFreeCells() {
  // First mark every cell the rays cross, then update each once, in tree order.
  SweepWork& work = *work_;
  const bool volume = options_.beam_model == BeamModel::kVolume;
  // Rays [first, last) of one kind (inner or outer) into `marks`.
  auto markRange = [&](KeyMarks<16>& marks, bool outer, std::size_t first, std::size_t last) {
    marks.marking([&](auto mark) {
      for (std::size_t r = first; r < last; ++r) {
        const FreeRay& ray = work.rays[r];
        if (ray.outer != outer) continue;
        if (options_.ray == RayAlgorithm::kDDA) {
          traverseDDASteps(map_.coder(), ray.start_m, ray.end_m, mark);
        } else {
          traverseBresenham(map_.coder(), ray.start_m, ray.end_m, mark);
        }
      }
    });
  };
  // With several threads each traces a share of the rays into its own set; the union is the same
  // whatever the split, so the map is identical.
  auto markRays = [&](KeyMarks<16>& marks, bool outer) {
    const std::size_t n = work.rays.size();
    const auto threads = static_cast<unsigned>(std::clamp<std::size_t>(n / 256, 1, options_.threads));
    if (threads <= 1) return markRange(marks, outer, 0, n);
    work.parts.resize(threads - 1);
    for (KeyMarks<16>& part : work.parts) part.reset(work.box_lo, work.box_hi);
    runOnThreads(threads, [&](unsigned t) {
      markRange(t == 0 ? marks : work.parts[t - 1], outer, n * t / threads, n * (t + 1) / threads);
    });
    for (unsigned t = 1; t < threads; ++t) marks.merge(work.parts[t - 1]);
  };
  markRays(work.crossed, false);
  if (volume) {
    // A cone's quiet outer part may graze a surface without an echo: it does not clear a cell the
    // map holds occupied unless the loud inner part of some cone of the sweep crosses it too.
    work.outer.reset(work.box_lo, work.box_hi);
    markRays(work.outer, true);
    for (const std::uint64_t code : work.occupied_keys) {
      const Key16 key = keyOfMortonCode<16>(code);
      if (!work.outer.contains(key) || work.crossed.contains(key)) continue;
      const std::optional<float> log_odds = map_.search(key);
      if (log_odds && map_.model().isOccupied(*log_odds)) work.outer.erase(key);
    }
    work.crossed.merge(work.outer);
  }
  for (const std::uint64_t hit : work.hits) work.crossed.erase(keyOfMortonCode<16>(hit >> 16));  // never also a miss
  // Brick by brick, leaves only; an eager tree then syncs its inner nodes once (the same tree).
  work.crossed.forEachBrick([&](const Key16& corner, std::uint64_t voxels) {
    map_.updateBrick(corner, voxels, map_.model().miss);
    stats_.free_updates += static_cast<std::size_t>(std::popcount(voxels));
  });
  if (!map_.options().lazy) map_.updateDirtyInnerOccupancy();
}

void SonarMapper::integrateHits() {
  // One update per hit cell (keySweep kept the largest share among its arc points), in tree order:
  // each descent starts where the previous cell's path parts from it.
  SweepWork& work = *work_;
  const double prob_hit = options_.octree.occupancy.prob_hit;
  const bool volume = options_.beam_model == BeamModel::kVolume;
  if (work.hit_log_odds.empty()) work.hit_log_odds.assign(0x10000, std::numeric_limits<float>::quiet_NaN());
  for (const std::uint64_t hit : work.hits) {
    float& delta = work.hit_log_odds[hit & 0xFFFF];
    if (std::isnan(delta)) {
      const double weight = static_cast<double>(hit & 0xFFFF) / 0xFFFF;
      delta = weight >= 1.0 ? map_.model().hit : logOdds(0.5 + (prob_hit - 0.5) * weight);
    }
    map_.updateNode(keyOfMortonCode<16>(hit >> 16), delta);
    ++stats_.occupied_updates;
  }
  if (volume) {  // the sweep's hit cells (sorted and unique, as keySweep left them) joined to earlier sweeps'
    work.merged_keys.clear();
    auto earlier = work.occupied_keys.begin();
    for (const std::uint64_t hit : work.hits) {
      const std::uint64_t cell = hit >> 16;
      for (; earlier != work.occupied_keys.end() && *earlier < cell; ++earlier) work.merged_keys.push_back(*earlier);
      if (earlier != work.occupied_keys.end() && *earlier == cell) ++earlier;
      work.merged_keys.push_back(cell);
    }
    work.merged_keys.insert(work.merged_keys.end(), earlier, work.occupied_keys.end());
    std::swap(work.occupied_keys, work.merged_keys);
  }
}

template <class PoseOfRow>
void SonarMapper::integrateRows(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                PoseOfRow&& pose_of, bool whole_sweep) {
  resolveResolution(polar);
  SweepWork& work = *work_;
  work.beams.clear();
  work.loud_obstacles.clear();
  const double tolerance_m = work.tolerance_m = rangeTolerance_m(polar);
  const bool clears_without_obstacle = clearsWithoutObstacle(options_);
  const BeamShape shape = beamShape();
  const bool volume = mapsBeamVolume(options_);
  for (std::size_t row = 0; row < detections.size(); ++row) {
    const Eigen::Isometry3d* sonar_to_map = pose_of(row);
    if (sonar_to_map == nullptr) {
      ++stats_.beams_without_nav;
      continue;
    }
    const BeamDetection& detection = detections[row];
    if (detection.hasObstacle() && !(std::isfinite(detection.range_m) && detection.range_m > 0.0)) {
      throw ValueError("detection of beam " + std::to_string(row) + " has an obstacle at a range that is not > 0 m");
    }
    const bool traced = volume && !detection.hasObstacle() && detection.hasExtendedReturn();
    if (!detection.hasObstacle() && !clears_without_obstacle && !traced) {  // silence is no proof of water here
      ++stats_.beams_without_evidence;
      continue;
    }
    // Without an obstacle a beam clears only as far as its echo shows water (detection.hpp).
    double range_m = detection.hasObstacle() ? detection.range_m
                                             : std::min(detection.water_range_m, polar.valid_bins[row] * polar.bin_length_m);
    bool hit = detection.hasObstacle();
    if (range_m > options_.max_range_m) {  // OctoMap's maxrange: free up to the limit, no obstacle
      range_m = options_.max_range_m;
      hit = false;
      ++stats_.beams_clipped;
    }
    // Automatic tolerance: the sweep's (a bin plus half a voxel) plus the echo's own rise.
    const double beam_tolerance_m = tolerance_m + (options_.range_tolerance_m ? 0.0 : detection.rise_m);
    double free_range_m = hit ? std::max(0.0, range_m - beam_tolerance_m) : range_m;
    double water_m = -1.0;
    if (volume && detection.echo_onset_m < range_m) {
      // The cone met something before: a weak return it cannot call an obstacle, but no water.
      water_m = detection.echo_onset_m;
      free_range_m = std::min(free_range_m, std::max(0.0, water_m - tolerance_m));
    } else if (!hit && detection.echo_onset_m < range_m) {
      // The planar model's beam without an obstacle: a weak return below the obstacle threshold (a
      // soft or grazing surface) is no proof of water, so the beam clears only up to where its
      // echo starts (Elfes 1987); but an obstacle as strong as another beam's would have crossed
      // the threshold in this one, so it still carves the other beams' arcs up to its water range.
      water_m = range_m;
      free_range_m = std::max(0.0, detection.echo_onset_m);
    }
    PlannedBeam beam{*sonar_to_map, polar.bearing_rad[row], free_range_m, range_m, hit, water_m};
    if (hit) {  // where the loud echo falls back, the lit run's end, the beam's recorded range: no face beyond what it heard
      const double recorded_m = std::min(polar.valid_bins[row] * polar.bin_length_m, options_.max_range_m);
      beam.hit_end_m = detection.hasExtendedReturn() ? std::min(detection.extended_end_m, recorded_m) : recorded_m;
      if (detection.echo_end_m >= detection.range_m) beam.hit_end_m = std::min(beam.hit_end_m, detection.echo_end_m);
    }
    beam.surface_z_m = -options_.water_surface_depth_m;  // nedToMap: the map's z is −depth
    std::optional<PlannedBeam> obstacle;  // a loud trace: the obstacle it was detected as
    const std::optional<LoudReturn> loud =
        hit && volume ? loudReturn(detection) : std::nullopt;
    if (traced) {
      beam.trace_onset_m = detection.extended_onset_m;
      beam.trace_end_m = std::min(detection.extended_end_m, range_m);
    } else if (loud && isLevelReturn(beam, shape, loud->onset_m, loud->loud_end_m, beam_tolerance_m)) {
      // An obstacle whose echo lasts longer than a face's: a level surface entering the cone,
      // unless the seabed measured so far lies well below it (checkLoudTraces).
      obstacle = beam;
      beam.hit = false;
      beam.loud_trace = true;
      beam.trace_onset_m = beam.water_range_m = std::min(loud->onset_m, range_m);
      beam.trace_end_m = beam.hit_range_m = std::min(loud->end_m, options_.max_range_m);
      beam.free_range_m = std::max(0.0, std::min(free_range_m, beam.trace_onset_m - tolerance_m));
    }
    if (!beamInsideMap(beam)) {
      ++stats_.out_of_map;
      continue;
    }
    if (obstacle) work.loud_obstacles.emplace_back(work.beams.size(), *obstacle);
    work.beams.push_back(beam);
    ++stats_.beams_used;
    if (beam.traced()) ++stats_.extended_returns;
    if (beam.hit) ++stats_.obstacles;
  }
  if (volume) placeSeabedTraces();
  if (options_.beam_model != BeamModel::kInversion) {  // the inversion places no faces, traces nor free rays
    planBeams();
    keySweep();
    integrateFreeCells();
    integrateHits();
  }
  if (volume) addLevelSurfaceLooks(polar, detections, pose_of);
  if (options_.octree.lazy) map_.updateInnerOccupancy();
  if (whole_sweep) ++stats_.sweeps;
}

template <class PoseOfRow>
void SonarMapper::addLevelSurfaceLooks(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                       PoseOfRow&& pose_of) {
  SweepWork& work = *work_;
  const double resolution_m = *options_.resolution_m;
  // The seabed where the weak onsets of every sweep so far place it (seabed_slope.hpp), once they
  // were seen from around (their errors cancel): their plane's height at the latest onsets, its
  // slope where the onsets ask for one (normalAt); the water surface where the navigation's depth
  // places it (nedToMap: map z = −depth).
  std::optional<LevelPlane> seabed;
  if (work.seabed_onsets_m) {
    const auto& [onsets_m, radius_m] = *work.seabed_onsets_m;
    if (const std::optional<SeabedSlope::Fit> fit = work.seabed.fitAround(onsets_m, radius_m); fit && fit->seen_around) {
      seabed = LevelPlane{onsets_m - fit->heightAbove(onsets_m) * Eigen::Vector3d::UnitZ(),
                          work.seabed.normalAt(onsets_m, radius_m)};
    }
  }
  std::optional<LevelPlane> surface;
  if (std::isfinite(options_.water_surface_depth_m)) {
    surface = LevelPlane{Eigen::Vector3d(0.0, 0.0, -options_.water_surface_depth_m), -Eigen::Vector3d::UnitZ()};
  }
  const bool inverting = options_.beam_model == BeamModel::kInversion;
  if (!seabed && !surface && !inverting) return;
  if (inverting && !inversion_) {
    const TransducerPattern pattern{{options_.beam_width_rad, 2.0}, {options_.vertical_aperture_rad, 2.0}};
    inversion_ = std::make_unique<VolumeInversion>(pattern, resolution_m, options_.inversion, options_.threads);
  }
  if (!work.seabed_looks) {
    work.seabed_looks.emplace(resolution_m);
    work.surface_looks.emplace(resolution_m);
  }
  const std::vector<CellBeam> cells = cellBeams(polar, detections, resolution_m, work.tolerance_m);
  const double bins_per_cell = std::max(1.0, resolution_m / polar.bin_length_m);
  for (std::size_t row = 0; row < detections.size(); ++row) {
    const Eigen::Isometry3d* pose = pose_of(row);
    if (pose == nullptr) continue;
    const double bearing_rad = polar.bearing_rad[row];
    for (const auto& [plane, looks] : {std::pair{&seabed, &work.seabed_looks}, std::pair{&surface, &work.surface_looks}}) {
      if (*plane) {
        (*looks)->addBeam(*pose, bearing_rad, options_.beam_width_rad, options_.vertical_aperture_rad,
                          cells[row].cell_power, bins_per_cell, **plane);
      }
    }
    if (inverting) {
      const BeamDetection& detection = detections[row];
      const bool echoed = detection.hasObstacle() || detection.hasExtendedReturn();  // else silence: no proof of water
      inversion_->addBeam({*pose, bearing_rad, cells[row].cell_power, cells[row].water_range_m, echoed ? cells[row].water_range_m : 0.0,
                           seabed, surface},
                          map_);
    }
  }
  const auto occupy = [&](const Eigen::Vector3d& point_m) {
    if (const std::optional<Key16> key = map_.coder().keyOf(point_m)) {
      map_.updateNode(*key, map_.model().hit, true);
      ++stats_.occupied_updates;
    }
  };
  work.seabed_looks->drainHeard(occupy);
  work.surface_looks->drainHeard(occupy);
}

void SonarMapper::finish() {
  if (!inversion_) return;
  inversion_->flush(map_);
  map_.updateInnerOccupancy();
}

namespace {
/// @throws ValueError when the sweep's `what` (detections, poses) do not number one per polar row.
void checkRows(const PolarImage& polar, std::size_t count, const char* what) {
  if (count != static_cast<std::size_t>(polar.rows())) {
    throw ValueError("sweep has " + std::to_string(polar.rows()) + " beams but " + std::to_string(count) + " " + what);
  }
}
}  // namespace

void SonarMapper::integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                 const Eigen::Isometry3d& sonar_to_map) {
  checkRows(polar, detections.size(), "detections");
  integrateRows(polar, detections, [&](std::size_t) { return &sonar_to_map; }, true);
}

void SonarMapper::integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                 const std::vector<Eigen::Isometry3d>& sonar_to_map_per_row) {
  checkRows(polar, detections.size(), "detections");
  checkRows(polar, sonar_to_map_per_row.size(), "poses");
  integrateRows(polar, detections, [&](std::size_t row) { return &sonar_to_map_per_row[row]; }, true);
}

void SonarMapper::integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                 const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map_per_row) {
  integratePosedRows(polar, detections, sonar_to_map_per_row, true);
}

void SonarMapper::integrateBeams(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                 const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map_per_row) {
  integratePosedRows(polar, detections, sonar_to_map_per_row, false);
}

void SonarMapper::integratePosedRows(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                     const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map_per_row,
                                     bool whole_sweep) {
  checkRows(polar, detections.size(), "detections");
  checkRows(polar, sonar_to_map_per_row.size(), "poses");
  integrateRows(
      polar, detections,
      [&](std::size_t row) -> const Eigen::Isometry3d* {
        const auto& pose = sonar_to_map_per_row[row];
        return pose ? &*pose : nullptr;
      },
      whole_sweep);
}

}  // namespace sonarmap

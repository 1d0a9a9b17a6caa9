// The analyses of docs/accuracy.md (see accuracy_analysis.hpp).
#include "accuracy_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <vector>

#include "sonarmap/core/statistics.hpp"
#include "sonarmap/eval/simulated_accuracy.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/polar_units.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap::bench {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr int kTurns = 8;  // as the table's runs

/// The `q` quantile (0…1) of a copy of `values`; 0 for no values.
double quantile(std::vector<double> values, double q) { return percentile(values, q); }

struct Simulated {
  SonarPreset preset;
  Scene scene;
  MsisSimulation run;
};

Simulated simulate(const std::string& preset_name, const std::string& scene_name, double scatterers_per_m = 0.0,
                   double scatterer_level_db = 8.0) {
  Simulated s{sonarPreset(preset_name), {}, {}};
  s.preset.echo.water_scatterers_per_m = scatterers_per_m;
  s.preset.echo.water_scatterer_level_db = scatterer_level_db;
  s.scene = builtinScene(scene_name, s.preset.head.range_m, s.preset.head.vertical_beam_width_rad);
  MsisSimulationOptions options;
  options.head = s.preset.head;
  options.echo = s.preset.echo;
  options.turns = kTurns;
  s.run = simulateMsis(s.scene, options);
  return s;
}

MapperOptions headOptions(const SonarPreset& preset) {
  MapperOptions options;
  options.beam_width_rad = preset.head.horizontal_beam_width_rad;  // the head's, as a user states it
  return options;
}

Eigen::Vector3d inPlane(double bearing_rad) { return {std::cos(bearing_rad), std::sin(bearing_rad), 0.0}; }

/// The sweeps of a log as mapSonarLog splits them.
std::vector<SweepRange> sweepsOf(const SonarLog& log) { return groupSweeps(log.beams, 20); }

}  // namespace

void printLeadingEdgeTable() {
  std::printf("\n### Leading edges against the nearest surface in the beam (harbour, %d turns)\n\n", kTurns);
  std::printf("Detected range minus the nearest surface within ±half the nominal beam width, over the beams "
              "with an obstacle (m).\n\n");
  std::printf("| head | bin (m) | beams with an obstacle | p10 | median | p90 |\n|---|---:|---:|---:|---:|---:|\n");
  for (const std::string& name : sonarPresetNames()) {
    const Simulated s = simulate(name, "harbour");
    const SonarMapper mapper(headOptions(s.preset));
    const double half_rad = 0.5 * s.preset.head.horizontal_beam_width_rad;
    std::vector<double> errors;
    double bin_m = 0.0;
    for (const SweepRange& sweep : sweepsOf(s.run.log)) {
      PolarImage polar = makePolarImage(s.run.log.beams, sweep.first, sweep.last_exclusive);
      bin_m = polar.bin_length_m;
      const SweepDetection detection = mapper.detectSweep(polar);
      for (int r = 0; r < polar.rows(); ++r) {
        const BeamDetection& d = detection.detections[static_cast<std::size_t>(r)];
        if (!d.hasObstacle()) continue;
        double nearest_m = INFINITY;
        for (int k = -15; k <= 15; ++k) {
          const double bearing = polar.bearing_rad[static_cast<std::size_t>(r)] + half_rad * k / 15.0;
          const auto hit = firstHit(s.scene, Eigen::Vector3d::Zero(), inPlane(bearing), s.preset.head.range_m);
          if (hit) nearest_m = std::min(nearest_m, hit->surface.range_m);
        }
        if (std::isfinite(nearest_m)) errors.push_back(d.range_m - nearest_m);
      }
    }
    std::printf("| %s | %.3f | %zu | %+.3f | %+.3f | %+.3f |\n", name.c_str(), bin_m, errors.size(), quantile(errors, 0.1),
                quantile(errors, 0.5), quantile(errors, 0.9));
    std::fflush(stdout);
  }
}

void printIncidenceTable() {
  std::printf("\n### Offsets by incidence and at the corners (tank, %d turns, default mapping)\n\n", kTurns);
  std::printf("Median offset along the line of sight of the occupied voxels on the tank's walls (positive: in "
              "front of the wall), by the incidence angle of the line of sight on the wall; then the voxels "
              "within 0.1 × range of a corner: their median distance to the walls and the share within the "
              "precision's tolerance T.\n\n");
  std::printf("| head | voxel (m) | 0–15° | 15–30° | 30–45° | corners: voxels | median distance (m) | within T |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& name : sonarPresetNames()) {
    const Simulated s = simulate(name, "tank");
    const SonarMapper mapper = mapSonarLog(s.run.log, headOptions(s.preset));
    const double voxel_m = mapper.map().resolution_m();
    const double tolerance_m = std::max(0.1, std::sqrt(3.0) * voxel_m);
    const double scale = s.preset.head.range_m / kBuiltinSceneReach_m;
    // The tank's box (builtin_scenes.cpp): inner faces x ∈ ±2.1, y ∈ [−1.8, 2.6] at 5 m reach.
    const std::size_t box = 2;
    const double xs[2] = {-2.1 * scale, 2.1 * scale}, ys[2] = {-1.8 * scale, 2.6 * scale};
    std::vector<double> by_incidence[3], corner_distance;
    std::size_t corner_within = 0;
    for (const auto& cell : cellsInSlice(mapper.map(), 0.0, Occupancy::kOccupied)) {
      const Eigen::Vector3d p(cell.x(), cell.y(), 0.0);
      bool near_corner = false;
      for (const double x : xs) {
        for (const double y : ys) near_corner |= std::hypot(p.x() - x, p.y() - y) < 0.1 * s.preset.head.range_m;
      }
      if (near_corner) {
        const double d = distanceToSurface(s.scene.primitives[box], p);
        corner_distance.push_back(d);
        corner_within += d <= tolerance_m;
        continue;
      }
      const Eigen::Vector3d direction = p.normalized();
      const auto hit = firstHit(s.scene, Eigen::Vector3d::Zero(), direction, 2.0 * s.preset.head.range_m);
      if (!hit || hit->primitive != box) continue;
      const double offset_m = hit->surface.range_m - p.norm();
      if (std::abs(offset_m) > 3.0 * tolerance_m) continue;  // not this wall's voxel
      const double incidence_deg = std::acos(std::min(1.0, std::abs(hit->surface.normal.dot(direction)))) / kDegree;
      if (incidence_deg < 45.0) by_incidence[static_cast<int>(incidence_deg / 15.0)].push_back(offset_m);
    }
    std::printf("| %s | %.2f | %+.3f | %+.3f | %+.3f | %zu | %.3f | %.2f |\n", name.c_str(), voxel_m,
                quantile(by_incidence[0], 0.5), quantile(by_incidence[1], 0.5), quantile(by_incidence[2], 0.5),
                corner_distance.size(), quantile(corner_distance, 0.5),
                corner_distance.empty() ? 0.0 : static_cast<double>(corner_within) / static_cast<double>(corner_distance.size()));
    std::fflush(stdout);
  }
}

void printFalseAlarmTable() {
  std::printf("\n### Weak targets against false alarms\n\n");
  std::printf("| head | false-alarm probability | threshold (dB) | soft: precision / recall | harbour: precision / recall "
              "| open water: obstacles / sweep |\n|---|---:|---:|---|---|---:|\n");
  for (const std::string& name : sonarPresetNames()) {
    for (const double pfa : {1e-6, 1e-4, 1e-3}) {
      MapperOptions options;
      options.detector.background.calibration.false_alarm_probability = pfa;
      const SimulatedAccuracy soft = evaluateSimulatedRun(SimulatedRun{name, "soft"}, options);
      const SimulatedAccuracy harbour = evaluateSimulatedRun(SimulatedRun{name, "harbour"}, options);
      const SimulatedAccuracy open = evaluateSimulatedRun(SimulatedRun{name, "open-water"}, options);
      std::printf("| %s | %g | %.1f | %.3f / %.3f | %.3f / %.3f | %.2f |\n", name.c_str(), pfa,
                  thresholdDb(options.detector.background.calibration), soft.truth.precision, soft.truth.recall,
                  harbour.truth.precision, harbour.truth.recall,
                  open.sweeps > 0 ? static_cast<double>(open.obstacles) / static_cast<double>(open.sweeps) : 0.0);
      std::fflush(stdout);
    }
  }
}

namespace {

constexpr double kLevels_db[] = {6.0, 9.0, 12.0, 13.8, 16.9};
constexpr std::size_t kLevels = std::size(kLevels_db);

/// Counts the residuals above the calibrated background (dB) of bins from the minimum range to
/// 0.1 m before each beam's obstacle (or its end) that reach each of kLevels_db.
void countTail(const SonarLog& log, const MapperOptions& options, std::size_t& bins, std::size_t (&above)[kLevels]) {
  const SonarMapper mapper(options);
  for (const SweepRange& sweep : sweepsOf(log)) {
    const PolarImage raw = makePolarImage(log.beams, sweep.first, sweep.last_exclusive);
    PolarImage polar = raw;
    polar.intensities = raw.intensities.clone();  // detection cleans its image in place
    const SweepDetection detection = mapper.detectSweep(polar);
    const SweepCalibration& calibration = detection.calibration;
    const double counts_per_db = countsForDb(1.0, calibration.span_db);
    const int first = binsForLength(detection.min_range_m, raw.bin_length_m, 0, raw.cols()) + 1;
    for (int r = 0; r < raw.rows(); ++r) {
      const BeamDetection& d = detection.detections[static_cast<std::size_t>(r)];
      int end = std::min(raw.valid_bins[static_cast<std::size_t>(r)], raw.cols());
      if (d.hasObstacle()) end = std::min(end, static_cast<int>((d.range_m - 0.1) / raw.bin_length_m));
      const auto* row = raw.intensities.ptr<std::uint8_t>(r);
      for (int c = first; c < end; ++c) {
        const double residual_db = (row[c] - calibration.background[static_cast<std::size_t>(c)]) / counts_per_db;
        ++bins;
        for (std::size_t k = 0; k < kLevels; ++k) above[k] += residual_db >= kLevels_db[k];
      }
    }
  }
}

void printTailRow(const char* what, std::size_t bins, const std::size_t (&above)[kLevels]) {
  std::printf("| %s | %zu |", what, bins);
  for (std::size_t k = 0; k < kLevels; ++k) {
    std::printf(" %.1e |", bins > 0 ? static_cast<double>(above[k]) / static_cast<double>(bins) : 0.0);
  }
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

void printNoiseTailTable(const std::string& data_dir) {
  std::printf("\n### Noise tails: how often water alone rises above the background\n\n");
  std::printf("Share of water bins whose residual above the calibrated background (the 25th percentile) reaches "
              "each level.\n\n| log | bins |");
  for (const double level : kLevels_db) std::printf(" ≥ %.1f dB |", level);
  std::printf("\n|---|---:|");
  for (std::size_t k = 0; k < kLevels; ++k) std::printf("---:|");
  std::printf("\n| one-look speckle (exponential power) | – |");
  const double quartile = -std::log(0.75);
  for (const double level : kLevels_db) std::printf(" %.1e |", std::exp(-quartile * std::pow(10.0, level / 10.0)));
  std::printf("\n");
  for (const std::string& name : sonarPresetNames()) {
    const Simulated s = simulate(name, "open-water");
    std::size_t bins = 0, above[kLevels] = {};
    countTail(s.run.log, headOptions(s.preset), bins, above);
    printTailRow(("simulated " + name + ", open water").c_str(), bins, above);
  }
  // The simulated tank before its walls, as the real logs' rows count, with water scatterers
  // (EchoModelOptions::water_scatterers_per_m) of a few densities and mean levels.
  const double scatterers[][2] = {{0.0, 9.0}, {3.0, 9.0}, {12.0, 9.0}, {12.0, 12.0}};  // per metre, dB
  for (const auto& [per_m, level_db] : scatterers) {
    const Simulated s = simulate("micron", "tank", per_m, level_db);
    std::size_t bins = 0, above[kLevels] = {};
    countTail(s.run.log, headOptions(s.preset), bins, above);
    char what[120];
    std::snprintf(what, sizeof what, "simulated micron, tank, water before each obstacle, %.0f scatterers/m of %.0f dB",
                  per_m, level_db);
    printTailRow(what, bins, above);
  }
  for (const char* file : {"cras_micron_tank_static.mat", "seanet_sector_target.V4LOG"}) {
    const std::filesystem::path path = std::filesystem::path(data_dir) / file;
    if (!std::filesystem::exists(path)) continue;
    std::size_t bins = 0, above[kLevels] = {};
    countTail(readSonarLog(path.string()), MapperOptions{}, bins, above);
    printTailRow((std::string("real ") + file + ", water before each obstacle").c_str(), bins, above);
  }
}

}  // namespace sonarmap::bench

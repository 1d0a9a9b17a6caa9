#include "bench_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <numbers>
#include <optional>

#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/preprocess.hpp"
#include "sonarmap/sonar/sweeps.hpp"

#ifndef SONARMAP_SHARED_DATA
#define SONARMAP_SHARED_DATA "../shared/data"
#endif

namespace sonarmap::bench {

MapperOptions mapperOptions(Variant variant) {
  MapperOptions options;
  options.resolution_m = 0.02;  // the CRAS log's automatic resolution, also for the synthetic sweeps
  switch (variant) {
    case Variant::kDefault: break;
    case Variant::kSingleRay: options.beam_width_rad = 0.0; break;
    case Variant::kBresenham: options.ray = RayAlgorithm::kBresenham; break;
    case Variant::kEager: options.octree.lazy = false; break;
  }
  return options;
}

MapperOptions volumeOptions(double resolution_m, bool pipeline_detection) {
  MapperOptions options;
  options.beam_model = BeamModel::kVolume;
  options.resolution_m = resolution_m;
  options.pipeline_detection = pipeline_detection;
  return options;
}

std::string crasPath() {
  const char* folder = std::getenv("SONARMAP_DATA");
  const std::filesystem::path base = (folder != nullptr && *folder != '\0') ? folder : SONARMAP_SHARED_DATA;
  return (base / "cras_micron_tank_static.mat").string();
}

namespace {

struct LoadedLog {
  std::optional<SonarLog> log;
  std::string error;
};

LoadedLog loadCras() {
  LoadedLog loaded;
  const std::string path = crasPath();
  if (!std::filesystem::exists(path)) {
    loaded.error = "data file absent: " + path + " (set SONARMAP_DATA to its folder)";
    return loaded;
  }
  try {
    loaded.log = readSonarLog(path);
  } catch (const std::exception& e) {
    loaded.error = e.what();
  }
  return loaded;
}

/// Range in metres from the origin along (cos b, sin b) to the inside of the box [x0, x1] × [y0, y1]
/// that contains the origin.
double rangeToBox(double bearing_rad, double x0, double x1, double y0, double y1) {
  const double c = std::cos(bearing_rad), s = std::sin(bearing_rad);
  double range = 1e9;
  if (c > 1e-12) range = std::min(range, x1 / c);
  if (c < -1e-12) range = std::min(range, x0 / c);
  if (s > 1e-12) range = std::min(range, y1 / s);
  if (s < -1e-12) range = std::min(range, y0 / s);
  return range;
}

}  // namespace

const SonarLog* sourceLog(Source source, std::string& error) {
  if (source == Source::kSynthetic) {
    static const SonarLog synthetic = syntheticTankLog();
    return &synthetic;
  }
  static const LoadedLog cras = loadCras();
  error = cras.error;
  return cras.log ? &*cras.log : nullptr;
}

const SonarLog* logOrSkip(benchmark::State& state, Source source) {
  std::string error;
  const SonarLog* log = sourceLog(source, error);
  if (log == nullptr) state.SkipWithError(error.c_str());
  return log;
}

SonarLog syntheticTankLog() {
  constexpr int kSweeps = 28, kBeamsPerSweep = 200, kBins = 399, kEchoBins = 12;
  constexpr double kBinLength_m = 0.0125313, kSelfReflection_m = 0.3;
  constexpr double kX0 = -1.8, kX1 = 2.4, kY0 = -2.3, kY1 = 1.9;  // tank walls around the sonar, metres
  SonarLog log;
  log.beams.reserve(static_cast<std::size_t>(kSweeps) * kBeamsPerSweep);
  std::uint32_t seed = 12345;
  auto speckle = [&seed] {
    seed = seed * 1664525U + 1013904223U;  // LCG (Numerical Recipes): deterministic on every platform
    return static_cast<std::uint8_t>((seed >> 24) % 26);
  };
  for (int i = 0; i < kSweeps * kBeamsPerSweep; ++i) {
    Beam beam;
    beam.time_s = 0.043 * i;
    beam.bearing_rad = (i % kBeamsPerSweep) * (2.0 * std::numbers::pi / kBeamsPerSweep);
    beam.bin_length_m = kBinLength_m;
    beam.intensities.resize(kBins);
    const int wall_bin = static_cast<int>(rangeToBox(beam.bearing_rad, kX0, kX1, kY0, kY1) / kBinLength_m);
    for (int bin = 0; bin < kBins; ++bin) {
      std::uint8_t value = speckle();
      if ((bin + 0.5) * kBinLength_m < kSelfReflection_m) value = 160;
      if (bin >= wall_bin && bin < wall_bin + kEchoBins) value = static_cast<std::uint8_t>(150 - 5 * (bin - wall_bin));
      beam.intensities[static_cast<std::size_t>(bin)] = value;
    }
    log.beams.push_back(std::move(beam));
  }
  return log;
}

std::vector<PolarImage> rawSweeps(const SonarLog& log, const MapperOptions& options) {
  // As mapSonarLog(): split at full turns, short fragments joined to their neighbour.
  const auto min_beams = static_cast<std::size_t>(std::max(1, options.detector.background.min_beams));
  std::vector<PolarImage> images;
  for (const SweepRange& sweep : groupSweeps(log.beams, min_beams)) {
    images.push_back(makePolarImage(log.beams, sweep.first, sweep.last_exclusive));
  }
  return images;
}

PreparedSweeps prepareSweeps(const SonarLog& log, const MapperOptions& options) {
  PreparedSweeps prepared;
  prepared.polar = rawSweeps(log, options);
  const SonarMapper mapper(options);
  for (PolarImage& polar : prepared.polar) {
    prepared.detections.push_back(mapper.detect(polar));  // cleans the image in place, as mapSweep does
    prepared.beams += static_cast<std::size_t>(polar.rows());
  }
  return prepared;
}

void sweepBeams(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                std::vector<PlannedBeam>& beams) {
  beams.clear();
  for (std::size_t row = 0; row < detections.size(); ++row) {
    const BeamDetection& detection = detections[row];
    const double range_m = detection.hasObstacle() ? detection.range_m : detection.water_range_m;
    beams.push_back({Eigen::Isometry3d::Identity(), polar.bearing_rad[row], range_m, range_m, detection.hasObstacle()});
  }
}

void configure(benchmark::internal::Benchmark* benchmark) {
  benchmark->Unit(benchmark::kMillisecond)->ComputeStatistics("min", [](const std::vector<double>& values) {
    return values.empty() ? 0.0 : *std::min_element(values.begin(), values.end());
  });
}

void setMapCounters(benchmark::State& state, std::size_t sweeps, std::size_t beams, std::size_t nodes,
                    std::size_t leaves, std::size_t bytes) {
  using benchmark::Counter;
  state.counters["sweeps"] = Counter(static_cast<double>(sweeps));
  state.counters["beams/s"] = Counter(static_cast<double>(beams), Counter::kIsIterationInvariantRate);
  state.counters["nodes"] = Counter(static_cast<double>(nodes));
  state.counters["leaves"] = Counter(static_cast<double>(leaves));
  state.counters["bytes"] = Counter(static_cast<double>(bytes), Counter::kDefaults, Counter::kIs1024);
}

}  // namespace sonarmap::bench

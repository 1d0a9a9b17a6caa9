/// @file bench_mapping.cpp
/// sonarmap alone: the whole pipeline as the CLI runs it (BM_MapCras, BM_MapSynthetic), the same
/// split into stages (BM_CrasStages, BM_SyntheticStages) and reading the .mat log (BM_ReadCras).
/// The planar model (the 2D map, paper §6–§8) at 2 cm, and the beam-volume model (the 3D
/// map, BeamModel::kVolume, every other option at its default) at 2 cm and 5 cm: BM_MapCras/volume_*
/// (detection included, on a second thread as the CLI does), BM_MapCras/volume_*_one_thread (the
/// same on one thread: pipeline_detection off), BM_CrasStages/integrate_volume_* (the integration
/// alone, on one thread).
/// voxel_updates/s is the mapper's free + occupied cell updates (MappingStats, after the per-sweep
/// deduplication) over the time of the whole case, detection included where it is timed.
///
/// Maps are freed outside the timed region (the CLI does not time that either); every other step
/// runs inside it, from the log in memory to a map consistent after its last sweep.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_data.hpp"
#include "sonarmap/detection/calibration.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/polar_units.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "sonarmap/raycast/bresenham.hpp"
#include "sonarmap/raycast/dda.hpp"
#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/sonar/preprocess.hpp"

namespace sonarmap::bench {
namespace {

void reportMapper(benchmark::State& state, const SonarMapper& mapper) {
  const NodeCounts counts = mapper.map().counts();
  setMapCounters(state, mapper.stats().sweeps, mapper.stats().beams_used, counts.nodes, counts.leaves,
                 mapper.map().memoryBytes());
  state.counters["obstacles"] = benchmark::Counter(static_cast<double>(mapper.stats().obstacles));
  state.counters["free_updates"] = benchmark::Counter(static_cast<double>(mapper.stats().free_updates));
  state.counters["hit_updates"] = benchmark::Counter(static_cast<double>(mapper.stats().occupied_updates));
  const auto updates = static_cast<double>(mapper.stats().free_updates + mapper.stats().occupied_updates);
  state.counters["voxel_updates/s"] = benchmark::Counter(updates, benchmark::Counter::kIsIterationInvariantRate);
}

/// mapSonarLog(log, options) per iteration: sweep splitting, polar images, self-reflection
/// removal, smoothing, detection (of the next sweep on a second thread while one is integrated:
/// MapperOptions::pipeline_detection), ray casting and octree updates. File reading is not included.
void mapWholeLog(benchmark::State& state, Source source, const MapperOptions& options) {
  const SonarLog* log = logOrSkip(state, source);
  if (log == nullptr) return;
  std::optional<SonarMapper> last;
  for (auto _ : state) {
    SonarMapper mapper = mapSonarLog(*log, options);
    benchmark::DoNotOptimize(mapper.stats().sweeps);
    state.PauseTiming();
    last = std::move(mapper);  // frees the previous iteration's map, untimed
    state.ResumeTiming();
  }
  reportMapper(state, *last);
}

void BM_MapCras(benchmark::State& state, Variant variant) { mapWholeLog(state, Source::kCras, mapperOptions(variant)); }
void BM_MapCras(benchmark::State& state, const MapperOptions& options) { mapWholeLog(state, Source::kCras, options); }
void BM_MapSynthetic(benchmark::State& state, Variant variant) {
  mapWholeLog(state, Source::kSynthetic, mapperOptions(variant));
}

BENCHMARK_CAPTURE(BM_MapCras, dda_fan3deg, Variant::kDefault)->Apply(configure);
BENCHMARK_CAPTURE(BM_MapCras, single_ray, Variant::kSingleRay)->Apply(configure);
BENCHMARK_CAPTURE(BM_MapCras, bresenham_fan3deg, Variant::kBresenham)->Apply(configure);
BENCHMARK_CAPTURE(BM_MapCras, eager_octree, Variant::kEager)->Apply(configure);
BENCHMARK_CAPTURE(BM_MapCras, volume_2cm, volumeOptions(0.02))->Apply(configure);
BENCHMARK_CAPTURE(BM_MapCras, volume_5cm, volumeOptions(0.05))->Apply(configure);
BENCHMARK_CAPTURE(BM_MapCras, volume_2cm_one_thread, volumeOptions(0.02, false))->Apply(configure);
BENCHMARK_CAPTURE(BM_MapCras, volume_5cm_one_thread, volumeOptions(0.05, false))->Apply(configure);
BENCHMARK_CAPTURE(BM_MapSynthetic, dda_fan3deg, Variant::kDefault)->Apply(configure);
BENCHMARK_CAPTURE(BM_MapSynthetic, single_ray, Variant::kSingleRay)->Apply(configure);

/// Stages of mapSonarLog, each timed over all sweeps of the log with the earlier stages' output
/// computed beforehand. Their sum is the pipeline's time (up to the per-sweep call overhead).
enum class Stage {
  kPolarImages,  ///< sweep splitting and makePolarImage
  kCalibrate,    ///< calibrateSweep on each image as recorded (part of kDetect): the self-calibration
  kDetect,       ///< SonarMapper::detectSweep: calibration, band removal, detection on the water
  kIntegrate,    ///< SonarMapper::integrateSweep with the detections: rays and octree updates
  kRaycast,      ///< the part of kIntegrate that plans the sweep's rays and walks their voxels
};

/// Plans every sweep (planSweep) and walks each free ray's voxels with the mapper's traversal,
/// doing nothing with the keys but a checksum (so that every key is computed).
/// @return voxels visited, duplicates included.
std::size_t walkRays(const PreparedSweeps& prepared, const MapperOptions& options) {
  const KeyCoder<16> coder(*options.resolution_m);
  std::vector<PlannedBeam> beams;
  std::vector<FreeRay> rays;
  std::vector<HitPoint> hits;
  std::size_t visited = 0, checksum = 0;
  auto visit = [&](const Key16& key) {
    ++visited;
    checksum = checksum * 31 + key[0] + 7 * key[1] + 13 * key[2];
  };
  for (std::size_t i = 0; i < prepared.polar.size(); ++i) {
    sweepBeams(prepared.polar[i], prepared.detections[i], beams);
    planSweep(beams, options.beam_width_rad, *options.resolution_m, 0.0, rays, hits);
    for (const FreeRay& ray : rays) {
      if (options.ray == RayAlgorithm::kDDA) {
        traverseDDA(coder, ray.start_m, ray.end_m, visit);
      } else {
        traverseBresenham(coder, ray.start_m, ray.end_m, visit);
      }
    }
  }
  benchmark::DoNotOptimize(checksum);
  return visited;
}

void mapStage(benchmark::State& state, Source source, Stage stage, const MapperOptions& options) {
  const SonarLog* log = logOrSkip(state, source);
  if (log == nullptr) return;
  const PreparedSweeps prepared = prepareSweeps(*log, options);
  state.counters["sweeps"] = benchmark::Counter(static_cast<double>(prepared.polar.size()));
  state.counters["beams/s"] =
      benchmark::Counter(static_cast<double>(prepared.beams), benchmark::Counter::kIsIterationInvariantRate);

  if (stage == Stage::kPolarImages) {
    for (auto _ : state) {
      std::vector<PolarImage> images = rawSweeps(*log, options);
      benchmark::DoNotOptimize(images.data());
    }
  } else if (stage == Stage::kCalibrate || stage == Stage::kDetect) {
    const std::vector<PolarImage> raw = rawSweeps(*log, options);
    const SonarMapper mapper(options);
    for (auto _ : state) {
      state.PauseTiming();
      std::vector<PolarImage> images = raw;  // detection cleans its image in place
      for (PolarImage& image : images) image.intensities = image.intensities.clone();
      state.ResumeTiming();
      for (PolarImage& polar : images) {
        if (stage == Stage::kCalibrate) {
          const SweepCalibration calibration =
              calibrateSweep(polar, options.detector.background.calibration, intensitySpan_db(polar));
          benchmark::DoNotOptimize(calibration.background.data());
        } else {
          const std::vector<BeamDetection> detections = mapper.detect(polar);
          benchmark::DoNotOptimize(detections.data());
        }
      }
    }
  } else if (stage == Stage::kRaycast) {
    std::size_t visited = 0;
    for (auto _ : state) {
      visited = walkRays(prepared, options);
      benchmark::DoNotOptimize(visited);
    }
    state.counters["ray_voxels"] = benchmark::Counter(static_cast<double>(visited));
  } else {
    std::optional<SonarMapper> last;
    for (auto _ : state) {
      SonarMapper mapper(options);
      for (std::size_t i = 0; i < prepared.polar.size(); ++i) {
        mapper.integrateSweep(prepared.polar[i], prepared.detections[i]);
      }
      benchmark::DoNotOptimize(mapper.stats().sweeps);
      state.PauseTiming();
      last = std::move(mapper);
      state.ResumeTiming();
    }
    reportMapper(state, *last);
  }
}

void BM_CrasStages(benchmark::State& state, Stage stage, Variant variant) {
  mapStage(state, Source::kCras, stage, mapperOptions(variant));
}
void BM_CrasStages(benchmark::State& state, Stage stage, const MapperOptions& options) {
  mapStage(state, Source::kCras, stage, options);
}
void BM_SyntheticStages(benchmark::State& state, Stage stage, Variant variant) {
  mapStage(state, Source::kSynthetic, stage, mapperOptions(variant));
}

BENCHMARK_CAPTURE(BM_CrasStages, polar_images, Stage::kPolarImages, Variant::kDefault)->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, calibrate, Stage::kCalibrate, Variant::kDefault)->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, detect, Stage::kDetect, Variant::kDefault)->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, integrate_dda_fan3deg, Stage::kIntegrate, Variant::kDefault)->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, raycast_only_dda_fan3deg, Stage::kRaycast, Variant::kDefault)->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, integrate_single_ray, Stage::kIntegrate, Variant::kSingleRay)->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, integrate_bresenham_fan3deg, Stage::kIntegrate, Variant::kBresenham)->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, raycast_only_bresenham_fan3deg, Stage::kRaycast, Variant::kBresenham)
    ->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, integrate_eager_octree, Stage::kIntegrate, Variant::kEager)->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, integrate_volume_2cm, Stage::kIntegrate, volumeOptions(0.02))->Apply(configure);
BENCHMARK_CAPTURE(BM_CrasStages, integrate_volume_5cm, Stage::kIntegrate, volumeOptions(0.05))->Apply(configure);
BENCHMARK_CAPTURE(BM_SyntheticStages, integrate_dda_fan3deg, Stage::kIntegrate, Variant::kDefault)->Apply(configure);

/// readSonarLog on the CRAS .mat: libmatio parsing and per-beam validation.
void BM_ReadCras(benchmark::State& state) {
  const std::string path = crasPath();
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("data file absent: " + path + " (set SONARMAP_DATA to its folder)").c_str());
    return;
  }
  std::size_t beams = 0;
  for (auto _ : state) {
    const SonarLog log = readSonarLog(path);
    beams = log.beams.size();
    benchmark::DoNotOptimize(beams);
  }
  state.counters["beams"] = benchmark::Counter(static_cast<double>(beams));
  state.counters["file_bytes"] = benchmark::Counter(static_cast<double>(std::filesystem::file_size(path)),
                                                    benchmark::Counter::kDefaults, benchmark::Counter::kIs1024);
}

BENCHMARK(BM_ReadCras)->Apply(configure);

}  // namespace
}  // namespace sonarmap::bench
